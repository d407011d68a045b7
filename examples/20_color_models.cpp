// Example 20: the notes' color models as pictures.
//
//   (a) the CIE 1931 xy chromaticity diagram: the horseshoe of visible chromaticities filled with (approximate)
//       colors, the sRGB gamut triangle, the D65 white point, wavelengths along the spectral locus, axes;
//   (b) the RGB color cube, ray-cast per pixel: seen from the white corner, from the black corner, and with the
//       octant [0.5, 1]^3 cut away so that the inside (the gray diagonal's midpoint) shows;
//   (c) the HSV hexcone and (d) the HLS double hexcone, whole and with a wedge cut away.
//
// Every pixel is computed here with plain loops (no canvas): the 3D pictures intersect each eye ray with a convex
// polyhedron (a list of half-spaces) minus an optional convex cut-away region, and color the hit point with the
// library's conversions (hsv_to_rgb, hls_to_rgb). Pixel values are written as they are (no gamma), except the
// chromaticity diagram, whose colors are sRGB-encoded display values.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gallery.hpp"
#include "tessera/color/chromaticity.hpp"
#include "tessera/color/color.hpp"
#include "tessera/color/srgb.hpp"
#include "tessera/raster2d/font.hpp"

namespace {

using tessera::ImageRGB;
using tessera::kPi;
using tessera::Vec2;
using tessera::Vec3;
using tessera::examples::side_by_side;

const Vec3 kInk(0.08, 0.08, 0.1);          // lines and text
const Vec3 kBackground(0.95, 0.95, 0.95);  // behind the 3D solids

// ---- 2D drawing helpers: blend, antialiased lines and rings, labels in raster2d's bitmap font -------------------

void blend(ImageRGB& image, int x, int y, const Vec3& color, double coverage) {
  if (!image.contains(x, y) || coverage <= 0) return;
  const double a = std::min(coverage, 1.0);
  image(x, y) = glm::vec3(Vec3(image(x, y)) * (1.0 - a) + color * a);
}

// A line of the given width: each pixel is covered by how far its center is from the segment (a 1-pixel ramp).
void draw_line(ImageRGB& image, Vec2 a, Vec2 b, const Vec3& color, double width) {
  const double reach = width / 2 + 1;
  const int x0 = int(std::floor(std::min(a.x, b.x) - reach)), x1 = int(std::ceil(std::max(a.x, b.x) + reach));
  const int y0 = int(std::floor(std::min(a.y, b.y) - reach)), y1 = int(std::ceil(std::max(a.y, b.y) + reach));
  const Vec2 ab = b - a;
  const double length2 = std::max(glm::dot(ab, ab), 1e-12);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const Vec2 p(x + 0.5, y + 0.5);
      const double t = std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0);
      blend(image, x, y, color, width / 2 + 0.5 - glm::length(p - (a + t * ab)));
    }
}

// A circle outline of radius r centered at c.
void draw_ring(ImageRGB& image, Vec2 c, double r, const Vec3& color, double width) {
  for (int y = int(c.y - r - width); y <= int(c.y + r + width) + 1; ++y)
    for (int x = int(c.x - r - width); x <= int(c.x + r + width) + 1; ++x)
      blend(image, x, y, color, width / 2 + 0.5 - std::abs(glm::length(Vec2(x + 0.5, y + 0.5) - c) - r));
}

// Draws `text` (raster2d's font, font.hpp) with the middle of its capitals at `center`, each font pixel a scale x
// scale block.
void draw_text(ImageRGB& image, const std::string& text, Vec2 center, const Vec3& color, int scale = 2);

// Draws `text` over a 1-pixel halo of `halo`, so that it stays readable on any color.
void draw_label(ImageRGB& image, const std::string& text, Vec2 center, const Vec3& halo) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) draw_text(image, text, center + Vec2(dx, dy), halo);
  draw_text(image, text, center, kInk);
}

void draw_text(ImageRGB& image, const std::string& text, Vec2 center, const Vec3& color, int scale) {
  // Centered on the ink: the advance width less the gap column after the last character.
  namespace font = tessera::font;
  const int left = int(std::lround(center.x - (font::text_width(text) - 1) * scale / 2.0));
  const int baseline = int(std::lround(center.y - 3.5 * scale)) + font::kAscent * scale;
  for (const font::TextRun& run : font::text_runs(text))
    for (int y = baseline + run.y * scale; y < baseline + (run.y + 1) * scale; ++y)
      for (int x = left + run.x0 * scale; x < left + run.x1 * scale; ++x) blend(image, x, y, color, 1.0);
}

// ---- (a) the CIE 1931 chromaticity diagram --------------------------------------------------------------------

// An approximate display color for a chromaticity: the linear sRGB of (x, y) at Y = 1, negative components clipped,
// scaled so that the largest is 1, then sRGB-encoded. Outside the sRGB triangle this is only the nearest hue.
Vec3 chromaticity_color(const Vec2& xy) {
  Vec3 rgb = glm::max(tessera::xyy_to_rgb(Vec3(xy, 1.0)), Vec3(0.0));
  rgb /= std::max({rgb.x, rgb.y, rgb.z, 1e-12});
  return tessera::srgb_encode(rgb);
}

ImageRGB chromaticity_diagram() {
  constexpr double kScale = 640;           // pixels per unit of x and y
  constexpr double kLeft = 70, kTop = 24;  // the plot's origin is at (kLeft, kTop + 0.9 kScale)
  const auto to_pixel = [&](const Vec2& xy) { return Vec2(kLeft + xy.x * kScale, kTop + (0.9 - xy.y) * kScale); };
  const auto to_xy = [&](double px, double py) { return Vec2((px - kLeft) / kScale, 0.9 - (py - kTop) / kScale); };
  ImageRGB image(int(kLeft + 0.8 * kScale + 24), int(kTop + 0.9 * kScale + 64), glm::vec3(1.0f));

  // Grid every 0.1 behind everything.
  for (int i = 1; i <= 9; ++i) {
    if (i <= 8) draw_line(image, to_pixel({i / 10.0, 0.0}), to_pixel({i / 10.0, 0.9}), Vec3(0.86), 1.0);
    draw_line(image, to_pixel({0.0, i / 10.0}), to_pixel({0.8, i / 10.0}), Vec3(0.86), 1.0);
  }
  // The horseshoe, 4x4 samples per pixel so that its edge is smooth.
  constexpr int kSamples = 4;
  for (int py = 0; py < image.height(); ++py)
    for (int px = 0; px < image.width(); ++px) {
      Vec3 sum(0.0);
      int inside = 0;
      for (int sy = 0; sy < kSamples; ++sy)
        for (int sx = 0; sx < kSamples; ++sx) {
          const Vec2 xy = to_xy(px + (sx + 0.5) / kSamples, py + (sy + 0.5) / kSamples);
          if (xy.y <= 0 || !tessera::is_visible_chromaticity(xy)) continue;
          sum += chromaticity_color(xy);
          ++inside;
        }
      if (inside > 0) blend(image, px, py, sum / double(inside), double(inside) / (kSamples * kSamples));
    }

  // The spectral locus outline, closed by the line of purples, and wavelength ticks pointing away from white.
  const auto table = tessera::cie1931_cmf_table();
  for (size_t i = 0; i < table.size(); ++i) {
    const Vec2 a = tessera::spectral_locus(table[i].wavelength_nm);
    const Vec2 b = tessera::spectral_locus(table[(i + 1) % table.size()].wavelength_nm);
    draw_line(image, to_pixel(a), to_pixel(b), kInk, 1.5);
  }
  const Vec2 white = tessera::d65_white();
  for (int nm : {480, 510, 520, 540, 560, 580, 600, 620, 700}) {
    const Vec2 tangent = tessera::spectral_locus(nm + 1.0) - tessera::spectral_locus(nm - 1.0);
    Vec2 normal = glm::normalize(Vec2(tangent.y, -tangent.x));  // screen y grows downward: flip to point outward
    const Vec2 at = tessera::spectral_locus(nm);
    if (glm::dot(normal, at - white) < 0) normal = -normal;
    const Vec2 p = to_pixel(at), outward(normal.x, -normal.y);
    draw_line(image, p, p + 8.0 * outward, kInk, 1.5);
    draw_text(image, std::to_string(nm), p + 26.0 * outward, kInk);
  }
  draw_text(image, "nm", to_pixel(tessera::spectral_locus(520)) + Vec2(48, -18), kInk);

  // The sRGB gamut triangle with its primaries, and the D65 white point.
  const tessera::RgbGamut gamut = tessera::srgb_gamut();
  const Vec2 corners[] = {gamut.red, gamut.green, gamut.blue};
  const char* names[] = {"R", "G", "B"};
  for (int i = 0; i < 3; ++i) {
    draw_line(image, to_pixel(corners[i]), to_pixel(corners[(i + 1) % 3]), kInk, 2.0);
    const Vec2 inward = glm::normalize(white - corners[i]);
    draw_text(image, names[i], to_pixel(corners[i]) + Vec2(inward.x, -inward.y) * 18.0, kInk);
  }
  draw_ring(image, to_pixel(white), 5.0, kInk, 1.5);
  draw_text(image, "D65", to_pixel(white) + Vec2(26, -10), kInk);

  // Axes with ticks and labels.
  const Vec2 origin = to_pixel({0, 0});
  draw_line(image, origin, to_pixel({0.8, 0}), kInk, 1.5);
  draw_line(image, origin, to_pixel({0, 0.9}), kInk, 1.5);
  for (int i = 0; i <= 8; ++i) {
    const Vec2 p = to_pixel({i / 10.0, 0});
    draw_line(image, p, p + Vec2(0, 6), kInk, 1.5);
    draw_text(image, i == 0 ? "0" : "0." + std::to_string(i), p + Vec2(0, 18), kInk);
  }
  for (int i = 1; i <= 9; ++i) {
    const Vec2 p = to_pixel({0, i / 10.0});
    draw_line(image, p, p - Vec2(6, 0), kInk, 1.5);
    draw_text(image, "0." + std::to_string(i), p - Vec2(30, 0), kInk);
  }
  draw_text(image, "x", to_pixel({0.4, 0}) + Vec2(0, 44), kInk, 3);
  draw_text(image, "y", to_pixel({0, 0.45}) - Vec2(56, 0), kInk, 3);
  return image;
}

// ---- (b), (c), (d): convex solids ray-cast per pixel ----------------------------------------------------------

// A half-space n . p <= d.
struct Plane {
  Vec3 n;
  double d;
};

// The part of a ray o + t dir inside a convex region (all half-spaces at once), with the planes it enters and
// leaves through (-1 where the region is unbounded); nullopt when the ray misses it.
struct Span {
  double t0, t1;
  int enter, exit;
};
std::optional<Span> clip(const std::vector<Plane>& region, const Vec3& o, const Vec3& dir) {
  Span s{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), -1, -1};
  for (size_t i = 0; i < region.size(); ++i) {
    const double denominator = glm::dot(region[i].n, dir), numerator = region[i].d - glm::dot(region[i].n, o);
    if (std::abs(denominator) < 1e-15) {
      if (numerator < 0) return std::nullopt;  // parallel and outside
      continue;
    }
    const double t = numerator / denominator;
    if (denominator < 0 && t > s.t0) s = {t, s.t1, int(i), s.exit};
    if (denominator > 0 && t < s.t1) s = {s.t0, t, s.enter, int(i)};
  }
  if (s.t0 > s.t1) return std::nullopt;
  return s;
}

// A color solid: a convex polyhedron, an optional convex region cut away from it, and the color of each point.
struct Solid {
  std::vector<Plane> body;
  std::vector<Plane> cut;  // empty: nothing cut away
  std::function<Vec3(const Vec3&)> color;
};

// The nearest visible point of the solid along a ray: its t and the plane of the face it lies on.
struct Hit {
  double t;
  const Plane* face;
};
std::optional<Hit> hit(const Solid& solid, const Vec3& o, const Vec3& dir) {
  const auto body = clip(solid.body, o, dir);
  if (!body || body->t1 < 0 || body->enter < 0) return std::nullopt;
  const auto cut = solid.cut.empty() ? std::nullopt : clip(solid.cut, o, dir);
  if (!cut || body->t0 < cut->t0 || body->t0 > cut->t1)  // enters through the solid's surface
    return Hit{body->t0, &solid.body[size_t(body->enter)]};
  if (cut->t1 < body->t1 && cut->exit >= 0)  // enters through a cut face
    return Hit{cut->t1, &solid.cut[size_t(cut->exit)]};
  return std::nullopt;  // only the cut-away part is on the ray
}

// True when p, a point on the face `face`, lies within `width` of one of the face's edges: its distance, measured
// inside the face, to another bounding plane. A plane of the cut-away region counts only where p is (nearly) inside
// that region's other half-spaces.
bool near_edge(const Solid& solid, const Plane& face, const Vec3& p, double width) {
  const Vec3 face_normal = glm::normalize(face.n);
  const auto near = [&](const Plane& plane) {
    const double length = glm::length(plane.n);
    const Vec3 n = plane.n / length;
    const double in_face = glm::length(n - glm::dot(n, face_normal) * face_normal);  // sine of the angle between
    return &plane != &face && in_face > 1e-6 && std::abs(glm::dot(n, p) - plane.d / length) < width * in_face;
  };
  for (const Plane& plane : solid.body)
    if (near(plane)) return true;
  for (const Plane& plane : solid.cut) {
    bool in_others = true;
    for (const Plane& other : solid.cut)
      if (&other != &plane && glm::dot(other.n, p) - other.d > width * glm::length(other.n)) in_others = false;
    if (in_others && near(plane)) return true;
  }
  return false;
}

// True when p belongs to the solid: inside its body (with a little tolerance) and not strictly inside the cut.
bool part_of(const Solid& solid, const Vec3& p) {
  constexpr double kTolerance = 1e-6;
  for (const Plane& plane : solid.body)
    if (glm::dot(plane.n, p) > plane.d + kTolerance) return false;
  if (solid.cut.empty()) return true;
  for (const Plane& plane : solid.cut)
    if (glm::dot(plane.n, p) >= plane.d - kTolerance) return true;
  return false;
}

// A perspective camera looking from `eye` at `target` (y up), with a vertical field of view.
struct Camera {
  Vec3 eye, forward, right, up;
  double tan_half_fov;
  Camera(const Vec3& eye_, const Vec3& target, double fov_degrees)
      : eye(eye_),
        forward(glm::normalize(target - eye_)),
        right(glm::normalize(glm::cross(forward, Vec3(0, 1, 0)))),
        up(glm::cross(right, forward)),
        tan_half_fov(std::tan(tessera::radians(fov_degrees) / 2)) {}
  // The eye ray's direction through (px, py) of a w x h image.
  Vec3 ray(double px, double py, int w, int h) const {
    const double sx = (2 * px / w - 1) * tan_half_fov * w / h, sy = (1 - 2 * py / h) * tan_half_fov;
    return glm::normalize(forward + sx * right + sy * up);
  }
  // The pixel position of a 3D point.
  Vec2 project(const Vec3& p, int w, int h) const {
    const Vec3 v = p - eye;
    const double depth = glm::dot(v, forward);
    const double sx = glm::dot(v, right) / depth / tan_half_fov, sy = glm::dot(v, up) / depth / tan_half_fov;
    return {(sx * h / w + 1) * w / 2, (1 - sy) * h / 2};
  }
};

// A label naming a point of the solid (`anchor`), written at `text_at`; drawn only when the anchor is in sight.
struct Label {
  std::string text;
  Vec3 anchor, text_at;
};

// Renders one view of a solid into a w x h panel: 3x3 samples per pixel, dark edges, then the visible labels.
ImageRGB render(const Solid& solid, const Camera& camera, int w, int h, const std::vector<Label>& labels) {
  ImageRGB image(w, h);
  constexpr int kSamples = 3;
  const double edge_width = 0.0065;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      Vec3 sum(0.0);
      for (int sy = 0; sy < kSamples; ++sy)
        for (int sx = 0; sx < kSamples; ++sx) {
          const Vec3 dir = camera.ray(px + (sx + 0.5) / kSamples, py + (sy + 0.5) / kSamples, w, h);
          const auto found = hit(solid, camera.eye, dir);
          if (!found) {
            sum += kBackground;
            continue;
          }
          const Vec3 p = camera.eye + found->t * dir;
          sum += near_edge(solid, *found->face, p, edge_width) ? kInk : glm::clamp(solid.color(p), 0.0, 1.0);
        }
      image(px, py) = glm::vec3(sum / double(kSamples * kSamples));
    }
  for (const Label& label : labels) {
    const Vec3 to_anchor = label.anchor - camera.eye;
    const auto in_front = hit(solid, camera.eye, glm::normalize(to_anchor));
    if (!part_of(solid, label.anchor) || (in_front && in_front->t < glm::length(to_anchor) - 1e-4)) continue;
    draw_label(image, label.text, camera.project(label.text_at, w, h), kBackground);
  }
  return image;
}

// (b) The RGB cube [0,1]^3 with R along x, G along y (up), B along z; the color of a point is the point.
std::vector<Label> cube_labels() {
  const char* names[8] = {"K", "B", "G", "C", "R", "M", "Y", "W"};  // index = 4 r + 2 g + b
  std::vector<Label> labels;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i >> 2) & 1, (i >> 1) & 1, i & 1);
    labels.push_back({names[i], corner, Vec3(0.5) + (corner - Vec3(0.5)) * 1.3});
  }
  return labels;
}

ImageRGB rgb_cube() {
  Solid cube;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 n(0.0);
    n[axis] = 1;
    cube.body.push_back({n, 1.0});   // coordinate <= 1
    cube.body.push_back({-n, 0.0});  // coordinate >= 0
  }
  cube.color = [](const Vec3& p) { return p; };
  Solid cutaway = cube;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 n(0.0);
    n[axis] = -1;
    cutaway.cut.push_back({n, -0.5});  // the octant where every coordinate >= 0.5
  }
  const Vec3 center(0.5);
  const Camera from_white(center + Vec3(2.4, 1.9, 3.0), center, 36),
      from_black(center - Vec3(2.4, 1.9, 3.0), center, 36);
  return side_by_side({render(cube, from_white, 400, 400, cube_labels()),
                       render(cube, from_black, 400, 400, cube_labels()),
                       render(cutaway, from_white, 400, 400, cube_labels())});
}

// (c), (d): hue around the vertical axis. A point (x, z) of a horizontal section has plane coordinates (a, b) =
// (x, -z), so hue grows counterclockwise seen from above (the notes), red (hue 0) along +x.
Vec2 plane_coords(const Vec3& p) { return {p.x, -p.z}; }
// The half-space ca a + cb b <= cy y + d in 3D.
Plane plane_ab(double ca, double cb, double cy, double d) { return {Vec3(ca, -cy, -cb), d}; }

const double kCos30 = std::sqrt(3.0) / 2;

// The hexagonal "radius" of a plane point: 1 on the hexagon with vertices at hue k/6 on the unit circle.
double hex_norm(const Vec2& q) {
  double n = 0;
  for (int k = 0; k < 6; ++k) {
    const double angle = kPi / 6 + k * kPi / 3;  // the edges' outward normals
    n = std::max(n, glm::dot(q, Vec2(std::cos(angle), std::sin(angle))) / kCos30);
  }
  return n;
}

// The hexcone's hue of a plane point: the fraction of the way around the hexagon's edges, counted from red (Smith
// 1978): sector k between vertices k and k + 1, t along that edge.
double hex_hue(const Vec2& q) {
  const double n = hex_norm(q);
  if (n == 0) return 0;
  const Vec2 on_edge = q / n;
  const double angle = std::atan2(q.y, q.x);
  const int k = std::min(5, int(std::floor(tessera::wrap_hue(angle / (2 * kPi)) * 6)));
  const Vec2 vk(std::cos(k * kPi / 3), std::sin(k * kPi / 3)),
      vk1(std::cos((k + 1) * kPi / 3), std::sin((k + 1) * kPi / 3));
  return (k + std::clamp(glm::dot(on_edge - vk, vk1 - vk), 0.0, 1.0)) / 6;  // edge length 1
}

// Six half-spaces hex_norm(q) <= slope * y + offset: the sides of a hexagonal pyramid.
void add_hexagon_sides(std::vector<Plane>& planes, double slope, double offset) {
  for (int k = 0; k < 6; ++k) {
    const double angle = kPi / 6 + k * kPi / 3;
    planes.push_back(plane_ab(std::cos(angle), std::sin(angle), slope * kCos30, offset * kCos30));
  }
}

// A wedge around the vertical axis from hue h0 to h1 (turns, less than half a turn apart): the part cut away.
std::vector<Plane> hue_wedge(double h0, double h1) {
  const Vec2 u0(std::cos(2 * kPi * h0), std::sin(2 * kPi * h0)), u1(std::cos(2 * kPi * h1), std::sin(2 * kPi * h1));
  // Inside when cross(u0, q) >= 0 and cross(q, u1) >= 0.
  return {plane_ab(u0.y, -u0.x, 0, 0), plane_ab(-u1.y, u1.x, 0, 0)};
}

// Labels for the hexagon's corners (the pure hues) at height y, and for black and white on the axis.
std::vector<Label> hue_labels(double y, const Vec3& black, const Vec3& white) {
  const char* names[6] = {"R", "Y", "G", "C", "B", "M"};
  std::vector<Label> labels;
  for (int k = 0; k < 6; ++k) {
    const Vec3 corner(std::cos(k * kPi / 3), y, -std::sin(k * kPi / 3));
    labels.push_back({names[k], corner, Vec3(1.2 * corner.x, y, 1.2 * corner.z)});
  }
  labels.push_back({"K", black, black - Vec3(0, 0.12, 0)});
  labels.push_back({"W", white, white + Vec3(0, 0.12, 0)});
  return labels;
}

// (c) The HSV hexcone: V up from the black apex (V = 0) to the hexagonal top (V = 1); S from the axis (0) to the
// sides (1); H around. The color of a point is hsv_to_rgb(H, S, V).
ImageRGB hsv_cone() {
  Solid cone;
  add_hexagon_sides(cone.body, 1.0, 0.0);     // hex_norm <= V
  cone.body.push_back({Vec3(0, 1, 0), 1.0});  // V <= 1
  cone.color = [](const Vec3& p) {
    const Vec2 q = plane_coords(p);
    const double v = std::max(p.y, 0.0), s = v > 0 ? std::min(hex_norm(q) / v, 1.0) : 0.0;
    return tessera::hsv_to_rgb(Vec3(hex_hue(q), s, v));
  };
  Solid cutaway = cone;
  cutaway.cut = hue_wedge(-0.04, 0.21);
  const auto labels = hue_labels(1.0, Vec3(0, 0, 0), Vec3(0, 1, 0));
  const Camera camera(Vec3(2.5, 1.48, -1.3), Vec3(0, 0.45, 0), 40);
  return side_by_side({render(cone, camera, 460, 320, labels), render(cutaway, camera, 460, 320, labels)});
}

// (d) The HLS double hexcone: L up from black (0) through the hexagon of pure hues (L = 1/2) to white (1); S from
// the axis (0) to the sides (1). The color of a point is hls_to_rgb(H, L, S).
ImageRGB hls_double_cone() {
  Solid cone;
  add_hexagon_sides(cone.body, 2.0, 0.0);   // lower cone: hex_norm <= 2 L
  add_hexagon_sides(cone.body, -2.0, 2.0);  // upper cone: hex_norm <= 2 (1 - L)
  cone.color = [](const Vec3& p) {
    const Vec2 q = plane_coords(p);
    const double l = std::clamp(p.y, 0.0, 1.0), capacity = 1 - std::abs(2 * l - 1);
    const double s = capacity > 0 ? std::min(hex_norm(q) / capacity, 1.0) : 0.0;
    return tessera::hls_to_rgb(Vec3(hex_hue(q), l, s));
  };
  Solid cutaway = cone;
  cutaway.cut = hue_wedge(-0.04, 0.21);
  const auto labels = hue_labels(0.5, Vec3(0, 0, 0), Vec3(0, 1, 0));
  const Camera camera(Vec3(2.6, 1.07, -1.35), Vec3(0, 0.45, 0), 40);
  return side_by_side({render(cone, camera, 460, 320, labels), render(cutaway, camera, 460, 320, labels)});
}

}  // namespace

TESSERA_EXAMPLE(ex20_color_models, "20_color_models", "Color models") {
  gallery.add("20_cie_chromaticity.png", chromaticity_diagram(),
              "CIE 1931 xy chromaticity diagram: the spectral locus (wavelengths in nm) filled with approximate "
              "colors, the sRGB gamut triangle and the D65 white point");
  gallery.add("20_rgb_cube.png", rgb_cube(),
              "The RGB color cube seen from the white corner, from the black corner, and with the octant "
              "[0.5,1]^3 cut away (gray at its inner corner)");
  gallery.add("20_hsv_hexcone.png", hsv_cone(),
              "The HSV hexcone: value up from black, saturation out from the gray axis, hue around (red 0, "
              "counterclockwise); right: a wedge cut away");
  gallery.add("20_hls_double_cone.png", hls_double_cone(),
              "The HLS double hexcone: lightness from black through the pure hues (L = 1/2) to white; right: a "
              "wedge cut away");
}
