// The notes' three point-in-polygon tests, each filling the pixels it calls inside: a concave polygon (left of each
// panel), where all three agree, and a pentagram (right), where the crossing test's even-odd rule leaves the center
// out and the winding number's nonzero rule fills it. The half-plane test covers a non-convex polygon by a triangle
// fan with parity, so it sides with the crossing test.
#include <cmath>

#include "gallery.hpp"
#include "tessera/accel/shapes.hpp"

TESSERA_EXAMPLE(ex77_point_in_polygon, "77_point_in_polygon", "Point in polygon: crossing, winding, half-plane") {
  using namespace tessera;
  // A concave comb-like polygon and a pentagram, both in [-1, 1]^2.
  const std::vector<Vec2f> comb = {{-0.9f, -0.9f}, {0.9f, -0.9f},  {0.9f, 0.9f},  {0.5f, 0.9f},
                                   {0.5f, -0.3f},  {0.2f, -0.3f},  {0.2f, 0.9f},  {-0.2f, 0.9f},
                                   {-0.2f, -0.3f}, {-0.5f, -0.3f}, {-0.5f, 0.9f}, {-0.9f, 0.9f}};
  std::vector<Vec2f> star;
  for (int i = 0; i < 5; ++i) {
    const double a = kPi / 2 + i * 4 * kPi / 5;
    star.emplace_back(0.95f * float(std::cos(a)), 0.95f * float(std::sin(a)));
  }
  const int s = 160;  // each polygon's square
  const struct {
    PointInPolygon test;
    Vec3f color;
  } tests[] = {{PointInPolygon::crossing, {0.85f, 0.35f, 0.25f}},
               {PointInPolygon::winding, {0.25f, 0.55f, 0.85f}},
               {PointInPolygon::half_plane, {0.3f, 0.7f, 0.35f}}};
  std::vector<ImageRGB> panels;
  for (const auto& t : tests) {
    ImageRGB panel(2 * s + 8, s, Vec3f(1.0f));
    for (int k = 0; k < 2; ++k) {
      const std::vector<Vec2f>& poly = k == 0 ? comb : star;
      for (int y = 0; y < s; ++y)
        for (int x = 0; x < s; ++x) {
          // Pixel center to [-1, 1]^2, y up.
          const Vec2f p(2 * (float(x) + 0.5f) / float(s) - 1, 1 - 2 * (float(y) + 0.5f) / float(s));
          if (point_in_polygon(poly, p, t.test)) panel(k * (s + 8) + x, y) = t.color;
        }
    }
    panels.push_back(panel);
  }
  gallery.add("77_point_in_polygon.png", examples::side_by_side(panels),
              "Crossing test (left), winding number (middle) and half-plane test (right) on a concave polygon and a "
              "pentagram: only the winding number's nonzero rule fills the pentagram's center.");
}
