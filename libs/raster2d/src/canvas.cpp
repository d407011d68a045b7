#include "tessera/raster2d/canvas.hpp"

#include <algorithm>
#include <cmath>

#include "tessera/color/color.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/curves/flatten.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster2d/blend.hpp"
#include "tessera/raster2d/lines.hpp"
#include "tessera/raster2d/scanline.hpp"

namespace tessera {
namespace {

constexpr double kEllipseTolerance = 0.05;  // device pixels between an ellipse and its polygon
constexpr double kBezierTolerance = 0.02;   // device pixels between a Bezier and its polyline

float channel255(int v) { return float(std::clamp(v, 0, 255)) / 255.0f; }

// A colorMode number as a fraction of its range: clamped to [0, max] as Processing clamps (NaN reads as 0).
double in_range(double v, double max) { return v > 0 ? std::min(v, max) / max : 0.0; }

Vec4f texel(const Vec4f& t) { return t; }
Vec4f texel(const glm::u8vec4& t) { return Vec4f(t) / 255.0f; }

// Texel index v (a whole number) clamped to [0, n): NaN gives 0, so that no cast is undefined.
int clamped_index(double v, int n) { return v >= 0 ? int(std::min(v, double(n - 1))) : 0; }

// The texel nearest to image point uv (texel (i, j) covers [i, i+1) x [j, j+1)), clamped to the image.
template <class Texel>
Vec4f sample_nearest(const Image<Texel>& img, const Vec2& uv) {
  return texel(img(clamped_index(std::floor(uv.x), img.width()), clamped_index(std::floor(uv.y), img.height())));
}

// Bilinear between the four texel centers around uv, indices clamped to the image, interpolated premultiplied (so a
// transparent texel's color does not bleed into its neighbours); a point on a texel center returns that texel as is.
template <class Texel>
Vec4f sample_bilinear(const Image<Texel>& img, const Vec2& uv) {
  const double u = uv.x - 0.5, v = uv.y - 0.5;
  const double fu = std::floor(u), fv = std::floor(v);
  const float tu = float(u - fu), tv = float(v - fv);
  const auto at = [&](double i, double j) {
    return texel(img(clamped_index(i, img.width()), clamped_index(j, img.height())));
  };
  if (tu == 0 && tv == 0) return at(fu, fv);
  const auto premultiplied = [&](double i, double j) {
    const Vec4f t = at(i, j);
    return Vec4f(Vec3f(t) * t.w, t.w);
  };
  const Vec4f top = glm::mix(premultiplied(fu, fv), premultiplied(fu + 1, fv), tu);
  const Vec4f bottom = glm::mix(premultiplied(fu, fv + 1), premultiplied(fu + 1, fv + 1), tu);
  const Vec4f p = glm::mix(top, bottom, tv);
  return p.w > 0 ? Vec4f(Vec3f(p) / p.w, p.w) : Vec4f(0);
}

/// `width`, once a width x height canvas is known to fit the memory budget (a canvas's size comes from its user:
/// volume contour's PNG is 4 times the slice). Per pixel: the float RGBA image (16 bytes) and the 8-bit copy that
/// save() and write_image make (4). Sizes that are not positive are the image's errors.
int budgeted_width(int width, int height) {
  if (width > 0 && height > 0)
    MemoryBudget::check(saturating_product({uint64_t(width), uint64_t(height), 20}),
                        fmt::format("a {}x{} canvas", width, height));
  return width;
}

}  // namespace

Vec4f rgb255(int r, int g, int b, int a) { return {channel255(r), channel255(g), channel255(b), channel255(a)}; }
Vec4f gray255(int v, int a) { return rgb255(v, v, v, a); }

Canvas::Canvas(int width, int height) : image_(budgeted_width(width, height), height, gray255(204)) {}

void Canvas::save(const std::filesystem::path& path) const { write_image(path, image_); }

void Canvas::background(const Vec4f& color) { image_.fill(color); }

void Canvas::color_mode(ColorMode mode, double max1, double max2, double max3, double max_alpha) {
  for (const double m : {max1, max2, max3, max_alpha})
    if (!(m > 0) || !std::isfinite(m))
      throw InvalidInput(
          fmt::format("color_mode ranges must be finite numbers > 0, got {}, {}, {}, {}", max1, max2, max3, max_alpha));
  color_mode_ = mode;
  color_max_ = Vec4(max1, max2, max3, max_alpha);
}

Vec4f Canvas::color(double gray, double alpha) const {
  const auto g = float(in_range(gray, color_max_.x));
  return {g, g, g, float(in_range(alpha, color_max_.w))};
}

Vec4f Canvas::color(double v1, double v2, double v3, double alpha) const {
  Vec3 c(in_range(v1, color_max_.x), in_range(v2, color_max_.y), in_range(v3, color_max_.z));
  if (color_mode_ == ColorMode::hsb) c = hsv_to_rgb(c);  // hue in turns: 1 (the hue's max) is red again
  return {Vec3f(c), float(in_range(alpha, color_max_.w))};
}

void Canvas::stroke_weight(double weight) {
  if (!(weight >= 0) || !std::isfinite(weight))
    throw InvalidInput(fmt::format("stroke_weight must be a finite number >= 0, got {}", weight));
  stroke_weight_ = weight;
}

void Canvas::write_pixel(int x, int y, const Vec4f& color, float coverage) {
  if (!image_.contains(x, y)) return;
  Vec4f& p = image_(x, y);
  p = blend_over(p, color, coverage);
}

// ---- Transformations ------------------------------------------------------------------------------------------------

void Canvas::translate(double dx, double dy) { stack_.multiply(translate2d(dx, dy)); }
void Canvas::rotate(double angle) { stack_.multiply(rotate2d(angle)); }
void Canvas::scale(double sx, double sy) { stack_.multiply(scale2d(sx, sy)); }
void Canvas::shear_x(double angle) { stack_.multiply(shear2d(std::tan(angle), 0)); }
void Canvas::shear_y(double angle) { stack_.multiply(shear2d(0, std::tan(angle))); }

Vec2 Canvas::to_device(double x, double y) const { return transform_point(stack_.top(), Vec2(x, y)); }

double Canvas::device_scale() const {
  const Mat3& m = stack_.top();
  return std::sqrt(std::fabs(m[0][0] * m[1][1] - m[1][0] * m[0][1]));
}

// ---- Device-space drawing: everything below ends in write_pixel ---------------------------------------------------

void Canvas::paint(const Path& path, FillRule rule, const Vec4f& color) {
  scan_path(path, rule, width(), height(), smooth_, [&](int y, int x0, int x1, const float* coverage) {
    for (int x = x0; x < x1; ++x) write_pixel(x, y, color, coverage ? coverage[x - x0] : 1.0f);
  });
}

void Canvas::fill_device(const Path& path) {
  if (fill_) paint(path, fill_rule_, *fill_);
}

void Canvas::stroke_device(const std::vector<Vec2>& points, bool closed) {
  if (!stroke_ || points.empty()) return;
  const Vec4f color = *stroke_;
  const double width_px = stroke_weight_ * device_scale();
  if (width_px > 1.0) {
    StrokeStyle style = stroke_style_;
    style.width = width_px;
    paint(stroke_path(points, closed, style), FillRule::non_zero, color);
    return;
  }
  if (points.size() == 1) {
    point_device(points[0]);
    return;
  }
  // Hairlines: the notes' DDA line or Wu's line, in pixel-index coordinates (centers at integers).
  const float weight = float(width_px);
  auto plot = [&](int x, int y, float intensity) { write_pixel(x, y, color, smooth_ ? intensity * weight : 1.0f); };
  const Vec2 half(0.5, 0.5);
  const size_t segments = closed && points.size() > 2 ? points.size() : points.size() - 1;
  for (size_t i = 0; i < segments; ++i) {
    const Vec2 a = points[i] - half, b = points[(i + 1) % points.size()] - half;
    if (smooth_)
      line_wu(a.x, a.y, b.x, b.y, plot);
    else
      line_dda(a.x, a.y, b.x, b.y, plot);
  }
}

void Canvas::point_device(const Vec2& p) {
  if (!stroke_) return;
  const double diameter = stroke_weight_ * device_scale();
  if (diameter <= 1.0) {
    write_pixel(int(std::floor(p.x)), int(std::floor(p.y)), *stroke_);
    return;
  }
  StrokeStyle dot = stroke_style_;
  dot.width = diameter;
  dot.cap = LineCap::round;
  paint(stroke_path({p}, false, dot), FillRule::non_zero, *stroke_);
}

void Canvas::draw_device_polygon(const std::vector<Vec2>& points) {
  fill_device(Path{{points}});
  stroke_device(points, true);
}

// ---- Primitives -----------------------------------------------------------------------------------------------------

void Canvas::point(double x, double y) { point_device(to_device(x, y)); }

void Canvas::line(double x0, double y0, double x1, double y1) {
  stroke_device({to_device(x0, y0), to_device(x1, y1)}, false);
}

void Canvas::rect(double x, double y, double w, double h) {
  draw_device_polygon({to_device(x, y), to_device(x + w, y), to_device(x + w, y + h), to_device(x, y + h)});
}

void Canvas::triangle(double x0, double y0, double x1, double y1, double x2, double y2) {
  draw_device_polygon({to_device(x0, y0), to_device(x1, y1), to_device(x2, y2)});
}

void Canvas::quad(double x0, double y0, double x1, double y1, double x2, double y2, double x3, double y3) {
  draw_device_polygon({to_device(x0, y0), to_device(x1, y1), to_device(x2, y2), to_device(x3, y3)});
}

int Canvas::ellipse_segments(double w, double h, double sweep) const {
  // The largest device radius: the CTM's largest singular value times the larger semi-axis.
  const Mat3& m = stack_.top();
  const double a = m[0][0], b = m[1][0], c = m[0][1], d = m[1][1];
  const double s1 = a * a + b * b + c * c + d * d, s2 = a * d - b * c;
  const double sigma = std::sqrt(0.5 * (s1 + std::sqrt(std::max(0.0, s1 * s1 - 4 * s2 * s2))));
  const double r = sigma * 0.5 * std::max(std::fabs(w), std::fabs(h));
  const double step = r > kEllipseTolerance ? 2.0 * std::acos(1.0 - kEllipseTolerance / r) : kPi / 2;
  return std::clamp(int(std::ceil(std::fabs(sweep) / step)), 4, 1 << 16);
}

std::vector<Vec2> Canvas::arc_points(double cx, double cy, double w, double h, double start, double sweep, int n,
                                     bool keep_ends) const {
  // Points at equal parameter steps, pushed out by sqrt(step / sin(step)) so each chord's polygon has the area of its
  // elliptic sector (an inscribed polygon would lose ~2/3 of the sagitta along the whole outline). With keep_ends the
  // two end points stay on the ellipse.
  const double step = sweep / n;
  const double grow = std::fabs(step) > 1e-9 ? std::sqrt(step / std::sin(step)) : 1.0;
  std::vector<Vec2> pts;
  pts.reserve(size_t(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double t = start + step * i;
    const double k = keep_ends && (i == 0 || i == n) ? 1.0 : grow;
    pts.push_back(to_device(cx + 0.5 * w * k * std::cos(t), cy + 0.5 * h * k * std::sin(t)));
  }
  return pts;
}

void Canvas::ellipse(double cx, double cy, double w, double h) {
  const int n = ellipse_segments(w, h, 2 * kPi);
  std::vector<Vec2> pts = arc_points(cx, cy, w, h, 0, 2 * kPi, n, false);
  pts.pop_back();  // the last point repeats the first
  draw_device_polygon(pts);
}

void Canvas::arc(double cx, double cy, double w, double h, double start, double stop, ArcMode mode) {
  if (!(stop >= start)) return;
  const double sweep = std::min(stop - start, 2 * kPi);
  std::vector<Vec2> pts = arc_points(cx, cy, w, h, start, sweep, ellipse_segments(w, h, sweep), true);
  if (mode == ArcMode::pie) pts.push_back(to_device(cx, cy));
  fill_device(Path{{pts}});
  stroke_device(pts, mode != ArcMode::open);
}

// ---- Text -----------------------------------------------------------------------------------------------------------

void Canvas::text_size(double px) {
  if (!(px > 0) || !std::isfinite(px))
    throw InvalidInput(fmt::format("text_size must be a finite number > 0, got {}", px));
  text_scale_ = px / font::kSize;
}

double Canvas::text_width(std::string_view str) const { return font::text_width(str) * text_scale_; }

void Canvas::text(std::string_view str, double x, double y) {
  if (!fill_ || str.empty()) return;
  // Where the first baseline lies below y, in font units (Processing's text(): multi-line CENTER and BOTTOM move up
  // by the extra lines).
  const double extra = (font::line_count(str) - 1) * font::kLineHeight;
  double baseline = 0;
  switch (text_align_.second) {
    case TextAlignY::baseline:
      break;
    case TextAlignY::top:
      baseline = font::kAscent;
      break;
    case TextAlignY::center:
      baseline = (font::kAscent - extra) / 2;
      break;
    case TextAlignY::bottom:
      baseline = -(font::kDescent + extra);
      break;
  }
  const double s = text_scale_;
  const auto at = [&](int u, int v) { return to_device(x + u * s, y + (baseline + v) * s); };
  Path glyphs;
  for (const font::TextRun& run : font::text_runs(str, text_align_.first))
    glyphs.contours.push_back({at(run.x0, run.y), at(run.x1, run.y), at(run.x1, run.y + 1), at(run.x0, run.y + 1)});
  paint(glyphs, FillRule::non_zero, *fill_);
}

// ---- Images ---------------------------------------------------------------------------------------------------------

template <class Texel>
void Canvas::draw_image(const Image<Texel>& img, double x, double y, double w, double h) {
  if (img.empty()) return;
  // Image point (u, v) lands on user point (x + u w / width, y + v h / height), then the CTM.
  const Mat3 placement = stack_.top() * translate2d(x, y) * scale2d(w / img.width(), h / img.height());
  const double det = glm::determinant(placement);
  if (!std::isfinite(det) || det == 0) return;
  const Mat3 to_image = glm::inverse(placement);
  for (int k = 0; k < 3; ++k)  // nearly singular: no pixel could be mapped back
    if (!std::isfinite(to_image[k].x) || !std::isfinite(to_image[k].y) || !std::isfinite(to_image[k].z)) return;
  const Path footprint{{{to_device(x, y), to_device(x + w, y), to_device(x + w, y + h), to_device(x, y + h)}}};
  scan_path(footprint, FillRule::non_zero, width(), height(), smooth_, [&](int py, int x0, int x1, const float* c) {
    for (int px = x0; px < x1; ++px) {
      const Vec2 uv = transform_point(to_image, Vec2(px + 0.5, py + 0.5));
      write_pixel(px, py, smooth_ ? sample_bilinear(img, uv) : sample_nearest(img, uv), c ? c[px - x0] : 1.0f);
    }
  });
}

void Canvas::image(const ImageRGBA& img, double x, double y, double w, double h) { draw_image(img, x, y, w, h); }
void Canvas::image(const ImageRGBA8& img, double x, double y, double w, double h) { draw_image(img, x, y, w, h); }

// ---- Shapes ---------------------------------------------------------------------------------------------------------

void Canvas::require_shape(const char* what) const {
  if (!shape_) throw InvalidInput(fmt::format("{} outside begin_shape()/end_shape()", what));
}

void Canvas::begin_shape(ShapeKind kind) {
  if (shape_) throw InvalidInput("begin_shape() while a shape is open (missing end_shape())");
  shape_ = kind;
  contours_.assign(1, {});
  current_ = 0;
}

void Canvas::vertex(double x, double y) {
  require_shape("vertex()");
  contours_[current_].push_back(to_device(x, y));
}

void Canvas::bezier_vertex(double cx1, double cy1, double cx2, double cy2, double x, double y) {
  require_shape("bezier_vertex()");
  if (*shape_ != ShapeKind::polygon || contours_[current_].empty())
    throw InvalidInput("bezier_vertex() needs a Polygon shape and a previous vertex()");
  auto& c = contours_[current_];
  flatten_cubic(c.back(), to_device(cx1, cy1), to_device(cx2, cy2), to_device(x, y), kBezierTolerance, c);
}

void Canvas::quadratic_vertex(double cx, double cy, double x, double y) {
  require_shape("quadratic_vertex()");
  if (*shape_ != ShapeKind::polygon || contours_[current_].empty())
    throw InvalidInput("quadratic_vertex() needs a Polygon shape and a previous vertex()");
  auto& c = contours_[current_];
  flatten_quadratic(c.back(), to_device(cx, cy), to_device(x, y), kBezierTolerance, c);
}

void Canvas::begin_contour() {
  require_shape("begin_contour()");
  if (*shape_ != ShapeKind::polygon || current_ != 0)
    throw InvalidInput("begin_contour() needs a Polygon shape and no open contour");
  contours_.emplace_back();
  current_ = contours_.size() - 1;
}

void Canvas::end_contour() {
  if (!shape_ || current_ == 0) throw InvalidInput("end_contour() without begin_contour()");
  current_ = 0;  // later vertices continue the outline
}

void Canvas::end_shape(bool close) {
  require_shape("end_shape()");
  if (current_ != 0) throw InvalidInput("end_shape() with an open contour (missing end_contour())");
  const ShapeKind kind = *shape_;
  shape_.reset();
  std::vector<std::vector<Vec2>> contours;
  contours.swap(contours_);
  std::erase_if(contours, [](const std::vector<Vec2>& c) { return c.empty(); });
  if (contours.empty()) return;
  const std::vector<Vec2>& v = contours[0];
  const size_t n = v.size();
  switch (kind) {
    case ShapeKind::polygon:
      fill_device(Path{contours});
      stroke_device(contours[0], close);
      for (size_t i = 1; i < contours.size(); ++i) stroke_device(contours[i], true);
      break;
    case ShapeKind::points:
      for (const Vec2& p : v) point_device(p);
      break;
    case ShapeKind::lines:
      for (size_t i = 0; i + 1 < n; i += 2) stroke_device({v[i], v[i + 1]}, false);
      break;
    case ShapeKind::triangles:
      for (size_t i = 0; i + 2 < n; i += 3) draw_device_polygon({v[i], v[i + 1], v[i + 2]});
      break;
    case ShapeKind::triangle_strip:
      for (size_t i = 2; i < n; ++i) draw_device_polygon({v[i - 2], v[i - 1], v[i]});
      break;
    case ShapeKind::triangle_fan:
      for (size_t i = 2; i < n; ++i) draw_device_polygon({v[0], v[i - 1], v[i]});
      break;
    case ShapeKind::quads:
      for (size_t i = 0; i + 3 < n; i += 4) draw_device_polygon({v[i], v[i + 1], v[i + 2], v[i + 3]});
      break;
    case ShapeKind::quad_strip:
      for (size_t i = 0; i + 3 < n; i += 2) draw_device_polygon({v[i], v[i + 1], v[i + 3], v[i + 2]});
      break;
  }
}

}  // namespace tessera
