// The corner table of a small triangle mesh drawn in 2D: vertex numbers (black, in circles), corner numbers (blue,
// inside each triangle next to its vertex), and the swing of the center vertex's corners (red arrows):
// c.swing = c.next.opposite.next turns counterclockwise around the vertex. The green arrow joins one corner to its
// opposite corner across the shared edge. Everything is drawn straight into the pixels (edge functions for the
// triangles, stamped disks for lines, raster2d's bitmap font for the numbers).
#include <cmath>
#include <string>

#include "gallery.hpp"
#include "tessera/mesh/corner_table.hpp"
#include "tessera/raster2d/font.hpp"

namespace tessera::examples {
namespace {

constexpr int kSize = 720;
constexpr double kScale = 170.0;                    // pixels per mesh unit
const Vec2 kOrigin(kSize / 2.0, kSize / 2.0 - 40);  // where vertex 0 goes (the mesh reaches lower than higher)

Vec2 to_pixels(const Vec3& p) { return {kOrigin.x + kScale * p.x, kOrigin.y - kScale * p.y}; }

void fill_triangle(ImageRGB& img, Vec2 a, Vec2 b, Vec2 c, const Vec3f& color) {
  const auto edge = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
  };
  const double area = edge(a, b, c);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const Vec2 p(x + 0.5, y + 0.5);
      const double w0 = edge(b, c, p) / area, w1 = edge(c, a, p) / area, w2 = edge(a, b, p) / area;
      if (w0 >= 0 && w1 >= 0 && w2 >= 0) img(x, y) = color;
    }
}

void disk(ImageRGB& img, Vec2 center, double radius, const Vec3f& color) {
  for (int y = int(center.y - radius - 1); y <= int(center.y + radius + 1); ++y)
    for (int x = int(center.x - radius - 1); x <= int(center.x + radius + 1); ++x)
      if (img.contains(x, y) && glm::distance(Vec2(x + 0.5, y + 0.5), center) <= radius) img(x, y) = color;
}

void line(ImageRGB& img, Vec2 a, Vec2 b, double width, const Vec3f& color) {
  const int steps = int(glm::distance(a, b)) + 1;
  for (int i = 0; i <= steps; ++i) disk(img, a + (b - a) * (double(i) / steps), width / 2, color);
}

/// A line from a to b, shortened by `gap` at both ends, with an arrowhead at b.
void arrow(ImageRGB& img, Vec2 a, Vec2 b, double gap, const Vec3f& color) {
  const Vec2 d = glm::normalize(b - a);
  a += gap * d;
  b -= gap * d;
  line(img, a, b, 3, color);
  const Vec2 side(-d.y, d.x);
  line(img, b, b - 12.0 * d + 6.0 * side, 3, color);
  line(img, b, b - 12.0 * d - 6.0 * side, 3, color);
}

/// An arrow along the circle of `radius` pixels around `center`, counterclockwise on screen from angle a0 to a1
/// (radians, counterclockwise from +x), shortened by `gap` radians at both ends.
void arc_arrow(ImageRGB& img, Vec2 center, double radius, double a0, double a1, double gap, const Vec3f& color) {
  while (a1 <= a0) a1 += 2 * kPi;
  a0 += gap;
  a1 -= gap;
  const auto at = [&](double a) { return center + radius * Vec2(std::cos(a), -std::sin(a)); };
  const int steps = int(radius * (a1 - a0) / 2) + 1;
  for (int i = 0; i < steps; ++i)
    line(img, at(a0 + (a1 - a0) * i / steps), at(a0 + (a1 - a0) * (i + 1) / steps), 3, color);
  const Vec2 tip = at(a1), d = glm::normalize(tip - at(a1 - 0.05)), side(-d.y, d.x);
  line(img, tip, tip - 12.0 * d + 6.0 * side, 3, color);
  line(img, tip, tip - 12.0 * d - 6.0 * side, 3, color);
}

/// Draws a non-negative integer with the middle of its ink at `center`, in raster2d's bitmap font (font.hpp) scaled
/// `scale` times.
void number(ImageRGB& img, Vec2 center, uint32_t value, int scale, const Vec3f& color) {
  const std::string digits = std::to_string(value);
  const int w = (font::text_width(digits) - 1) * scale, h = font::kAscent * scale;  // the digits' ink
  const int x0 = int(center.x) - w / 2, baseline = int(center.y) - h / 2 + h;
  for (const font::TextRun& run : font::text_runs(digits))
    for (int y = baseline + run.y * scale; y < baseline + (run.y + 1) * scale; ++y)
      for (int x = x0 + run.x0 * scale; x < x0 + run.x1 * scale; ++x)
        if (img.contains(x, y)) img(x, y) = color;
}

/// A hexagonal fan around vertex 0 plus three outer triangles, counterclockwise.
CornerTable example_mesh() {
  std::vector<Vec3> g{Vec3(0, 0, 0)};
  for (int i = 0; i < 6; ++i) g.emplace_back(1.3 * std::cos(i * kPi / 3), 1.3 * std::sin(i * kPi / 3), 0);
  for (int i : {0, 2, 4}) {
    const double a = (i + 0.5) * kPi / 3;
    g.emplace_back(1.95 * std::cos(a), 1.95 * std::sin(a), 0);
  }
  std::vector<uint32_t> v;
  for (uint32_t i = 0; i < 6; ++i) v.insert(v.end(), {0, 1 + i, 1 + (i + 1) % 6});
  v.insert(v.end(), {1, 7, 2, 3, 8, 4, 5, 9, 6});
  return CornerTable(std::move(g), std::move(v));
}

}  // namespace
}  // namespace tessera::examples

TESSERA_EXAMPLE(ex31_corner_table, "31_corner_table", "Corner table: corners, opposite and swing") {
  using namespace tessera;
  using namespace tessera::examples;
  const CornerTable t = example_mesh();
  ImageRGB img(kSize, kSize, Vec3f(1.0f));
  const auto corner_point = [&](uint32_t c) {
    const uint32_t tri = CornerTable::triangle(c);
    const Vec3 centroid = (t.position(3 * tri) + t.position(3 * tri + 1) + t.position(3 * tri + 2)) / 3.0;
    return to_pixels(glm::mix(t.position(c), centroid, 0.5));
  };
  for (uint32_t tri = 0; tri < t.triangle_count(); ++tri)
    fill_triangle(img, to_pixels(t.position(3 * tri)), to_pixels(t.position(3 * tri + 1)),
                  to_pixels(t.position(3 * tri + 2)), tri < 6 ? Vec3f(0.82f, 0.89f, 0.98f) : Vec3f(0.9f, 0.9f, 0.9f));
  for (uint32_t c = 0; c < t.corner_count(); ++c)
    line(img, to_pixels(t.position(c)), to_pixels(t.position(CornerTable::next(c))), 2, Vec3f(0.2f));
  // The swing cycle of vertex 0 (red arcs through its corners) and one opposite pair (green: corner 25 and its
  // opposite across edge 5-6).
  const Vec3f red(0.85f, 0.1f, 0.1f), green(0.0f, 0.55f, 0.2f), blue(0.1f, 0.2f, 0.8f);
  const Vec2 center = to_pixels(t.geometry()[0]);
  const auto angle = [&](uint32_t c) {
    const Vec2 d = corner_point(c) - center;
    return std::atan2(-d.y, d.x);
  };
  const double radius = glm::distance(corner_point(t.corners_around(0).front()), center);
  for (uint32_t c : t.corners_around(0)) arc_arrow(img, center, radius, angle(c), angle(t.swing(c)), 0.3, red);
  arrow(img, corner_point(25), corner_point(t.opposite(25)), 16, green);
  for (uint32_t c = 0; c < t.corner_count(); ++c) number(img, corner_point(c), c, 2, blue);
  for (uint32_t v = 0; v < t.vertex_count(); ++v) {
    disk(img, to_pixels(t.geometry()[v]), 15, Vec3f(0.1f));
    disk(img, to_pixels(t.geometry()[v]), 13, Vec3f(1.0f));
    number(img, to_pixels(t.geometry()[v]), v, 2, Vec3f(0.0f));
  }
  gallery.add("31_corner_table.png", img,
              "A corner table: vertices (black circles), corners 3t, 3t+1, 3t+2 of triangle t (blue), the swing "
              "c.next.opposite.next of the center vertex's corners turning counterclockwise (red), and corner 25 "
              "with its opposite corner across edge 5-6 (green).");
}
