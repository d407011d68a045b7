// The SVG renderer: viewport mapping, flattening in device space, clipping to the image, and fill/stroke through the
// canvas's fill_path and stroke_path.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "tessera/core/memory_budget.hpp"
#include "tessera/curves/bezier.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera {
namespace {

// An axis-aligned box: the image grown by a margin.
struct Box {
  Vec2 lo, hi;
};

// True when all points lie beyond one side of the box: a curve whose control polygon is that far out cannot touch the
// box, and replacing it by its chord keeps every winding number inside the box (the chord lies in the same half-plane,
// and a horizontal ray from a point inside crosses both the same number of times, signed).
bool beyond_one_side(const Box& box, const std::vector<Vec2>& points) {
  const auto all = [&](auto&& pred) { return std::all_of(points.begin(), points.end(), pred); };
  return all([&](const Vec2& p) { return p.x < box.lo.x; }) || all([&](const Vec2& p) { return p.x > box.hi.x; }) ||
         all([&](const Vec2& p) { return p.y < box.lo.y; }) || all([&](const Vec2& p) { return p.y > box.hi.y; });
}

// Curves larger than this many box sizes are split before flattening (see flatten_curve).
constexpr double kSplitFactor = 64;

// Appends the flattened curve (device coordinates) to `out`. With a cull box, a curve beyond one side of it becomes its
// chord, and a curve far larger than the box is split in halves (de Casteljau) first, so that only the pieces near
// the box are flattened finely: bounded work for absurd coordinates. Smaller curves are flattened whole, exactly as
// flatten_cubic does.
void flatten_curve(const Bezier2& curve, double tolerance, const Box* cull, int depth, std::vector<Vec2>& out) {
  if (cull) {
    if (beyond_one_side(*cull, curve.points)) return out.push_back(curve.back());
    Vec2 lo = curve.front(), hi = curve.front();
    for (const Vec2& p : curve.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const Vec2 extent = hi - lo, box = cull->hi - cull->lo;
    if (depth < 64 && std::max(extent.x, extent.y) > kSplitFactor * std::max(box.x, box.y)) {
      const auto [first, second] = split(curve, 0.5);
      flatten_curve(first, tolerance, cull, depth + 1, out);
      flatten_curve(second, tolerance, cull, depth + 1, out);
      return;
    }
  }
  flatten(curve, tolerance, out);
}

// Flattens subpaths mapped through m (quadratics degree-elevated to cubics, as flatten_quadratic does); with a cull
// box, curves are culled and split as flatten_curve describes.
std::vector<SvgPolyline> flatten(const std::vector<SvgSubpath>& subpaths, const Mat3& m, double tolerance,
                                 const Box* cull) {
  std::vector<SvgPolyline> lines;
  for (const SvgSubpath& sub : subpaths) {
    SvgPolyline line{{transform_point(m, sub.start)}, sub.closed};
    for (const SvgSegment& s : sub.segments) {
      const Vec2 p0 = line.points.back(), c1 = transform_point(m, s.c1), end = transform_point(m, s.end);
      if (s.kind == SvgSegment::Kind::line)
        line.points.push_back(end);
      else if (s.kind == SvgSegment::Kind::quadratic)
        flatten_curve(elevate_degree(quadratic(p0, c1, end)), tolerance, cull, 0, line.points);
      else
        flatten_curve(cubic(p0, c1, transform_point(m, s.c2), end), tolerance, cull, 0, line.points);
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

// Clips a polyline (closed: a contour) to the box by projecting what lies outside onto the box's boundary lines,
// after splitting each edge where it crosses them. Every point inside the box keeps its winding number, and the moved
// parts stay at least the box's margin away from the image, so neither fills nor strokes narrower than the margin
// change inside the image; coordinates stay bounded for fill_path. Consecutive duplicates are dropped.
std::vector<Vec2> clip_to_box(const std::vector<Vec2>& points, bool closed, const Box& box) {
  std::vector<Vec2> out;
  const auto add = [&](const Vec2& p) {
    const Vec2 q = glm::clamp(p, box.lo, box.hi);
    if (out.empty() || out.back() != q) out.push_back(q);
  };
  if (points.empty()) return out;
  add(points[0]);
  const size_t edges = closed ? points.size() : points.size() - 1;
  for (size_t i = 0; i < edges; ++i) {
    const Vec2 a = points[i], b = points[(i + 1) % points.size()];
    std::array<double, 4> ts{};  // crossings with the four boundary lines, kept sorted
    size_t n = 0;
    for (int axis = 0; axis < 2; ++axis)
      for (const double v : {box.lo[axis], box.hi[axis]})
        if ((a[axis] - v) * (b[axis] - v) < 0) {
          const double t = (v - a[axis]) / (b[axis] - a[axis]);
          size_t k = n++;
          for (; k > 0 && ts[k - 1] > t; --k) ts[k] = ts[k - 1];
          ts[k] = t;
        }
    for (size_t k = 0; k < n; ++k) add(a + ts[k] * (b - a));
    add(b);
  }
  if (closed && out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

[[noreturn]] void overflow(const std::string& source, const SvgShape& shape) {
  throw InvalidInput(located(at_line(source, shape.line),
                             fmt::format("<{}>: coordinates overflow after the transforms", shape.element)));
}

bool finite(const Vec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// Throws when a control point of the shape is not finite in device space (a scale that overflows).
void require_finite(const std::string& source, const SvgShape& shape, const Mat3& m) {
  for (const SvgSubpath& sub : shape.subpaths) {
    if (!finite(transform_point(m, sub.start))) overflow(source, shape);
    for (const SvgSegment& s : sub.segments)
      for (const Vec2& p : {s.c1, s.c2, s.end})
        if (!finite(transform_point(m, p))) overflow(source, shape);
  }
}

// The largest factor by which the 2x2 matrix a stretches a vector: its largest singular value.
double max_stretch(const glm::dmat2& a) {
  const double s = 0.5 * (a[0][0] * a[0][0] + a[0][1] * a[0][1] + a[1][0] * a[1][0] + a[1][1] * a[1][1]);
  const double det = glm::determinant(a);
  return std::sqrt(s + std::sqrt(std::max(0.0, s * s - det * det)));
}

// The stroke outline in device space. SVG strokes are shapes of user space, so each device polyline is mapped into
// the pen space (user space scaled uniformly by the largest stretch s of the linear part a, where one unit is at most
// one device pixel and stroke_path's tolerances hold in pixels), stroked with the width times s, and the outline
// mapped back: exact for non-uniform scales and skews. A singular a squashes the shape to a line and draws nothing.
Path stroke_outline(const std::vector<SvgPolyline>& lines, const Box& box, const Box& image_box, StrokeStyle style,
                    const glm::dmat2& a) {
  Path outline;
  if (glm::determinant(a) == 0) return outline;
  const double s = max_stretch(a);
  const glm::dmat2 to_pen = s * glm::inverse(a), from_pen = a / s;
  style.width *= s;
  for (const SvgPolyline& line : lines) {
    std::vector<Vec2> points = clip_to_box(line.points, line.closed, box);
    if (points.size() < 2) continue;
    for (Vec2& p : points) p = to_pen * p;
    for (const auto& contour : stroke_path(points, line.closed, style).contours) {
      std::vector<Vec2> device(contour.size());
      std::transform(contour.begin(), contour.end(), device.begin(), [&](const Vec2& p) { return from_pen * p; });
      outline.contours.push_back(clip_to_box(device, true, image_box));
    }
  }
  return outline;
}

Vec4f with_opacity(const Vec4f& color, float opacity) { return {color.x, color.y, color.z, color.w * opacity}; }

void draw_shape(ImageRGBA& image, const std::string& source, const SvgShape& shape, const Mat3& m,
                const SvgRenderOptions& options) {
  const SvgStyle& style = shape.style;
  const bool stroked = style.stroke && style.stroke_style.width > 0;
  if (!style.fill && !stroked) return;
  require_finite(source, shape, m);
  const glm::dmat2 a(m);
  // How far a stroke reaches from its center line in device pixels (miters up to the limit, square caps to sqrt 2).
  const double reach =
      stroked ? 0.5 * style.stroke_style.width * max_stretch(a) * std::max(style.stroke_style.miter_limit, 1.5) : 0;
  const Vec2 size(image.width(), image.height());
  const Box image_box{Vec2(-2.0), size + 2.0};
  const Box box{image_box.lo - reach, image_box.hi + reach};
  const std::vector<SvgPolyline> lines = flatten(shape.subpaths, m, options.tolerance, &box);
  if (style.fill) {
    Path path;
    for (const SvgPolyline& line : lines) path.contours.push_back(clip_to_box(line.points, true, image_box));
    fill_path(image, path, style.fill_rule, with_opacity(*style.fill, style.fill_opacity * style.opacity),
              options.antialias);
  }
  if (stroked) {
    const Path outline = stroke_outline(lines, box, image_box, style.stroke_style, a);
    for (const auto& contour : outline.contours)
      if (!std::all_of(contour.begin(), contour.end(), finite)) overflow(source, shape);
    fill_path(image, outline, FillRule::non_zero, with_opacity(*style.stroke, style.stroke_opacity * style.opacity),
              options.antialias);
  }
}

// The transform that fits `box` (x, y, width, height) into [0, width] x [0, height] following preserveAspectRatio.
Mat3 fit(const Vec4& box, double width, double height, const SvgAspect& aspect) {
  double sx = width / box.z, sy = height / box.w;
  if (!aspect.none) sx = sy = aspect.slice ? std::max(sx, sy) : std::min(sx, sy);
  const double tx = aspect.none ? 0 : aspect.align_x * (width - box.z * sx);
  const double ty = aspect.none ? 0 : aspect.align_y * (height - box.w * sy);
  return translate2d(tx - box.x * sx, ty - box.y * sy) * scale2d(sx, sy);
}

// The root's viewport size: width and height, each falling back on the viewBox's; none when unknown or zero.
std::optional<Vec2> viewport_size(const SvgDocument& document) {
  Vec2 size(document.width.value_or(0), document.height.value_or(0));
  if (document.view_box) {
    if (!document.width) size.x = document.view_box->z;
    if (!document.height) size.y = document.view_box->w;
  }
  if (size.x <= 0 || size.y <= 0) return std::nullopt;
  return size;
}

}  // namespace

Size2 svg_output_size(const SvgDocument& document, const SvgRenderOptions& options) {
  double w = options.width, h = options.height;
  if (w <= 0 || h <= 0) {
    const std::optional<Vec2> intrinsic = viewport_size(document);
    if (!intrinsic)
      throw InvalidInput(
          fmt::format("{}: the SVG has no size (width/height or viewBox missing or zero); give the "
                      "output size",
                      document.source));
    if (w <= 0 && h <= 0) {
      w = std::ceil(intrinsic->x);
      h = std::ceil(intrinsic->y);
    } else if (w <= 0) {
      w = std::ceil(h * intrinsic->x / intrinsic->y);
    } else {
      h = std::ceil(w * intrinsic->y / intrinsic->x);
    }
  }
  if (!(w >= 1 && w <= 65536 && h >= 1 && h <= 65536))
    throw InvalidInput(
        fmt::format("{}: output size {}x{} is invalid (1 to 65536 pixels per side)", document.source, w, h));
  return {int(w), int(h)};
}

Mat3 svg_viewport_transform(const SvgDocument& document, int width, int height) {
  const std::optional<Vec2> viewport = viewport_size(document);
  if (!viewport) return Mat3(1.0);
  const Mat3 to_viewport =
      document.view_box ? fit(*document.view_box, viewport->x, viewport->y, document.aspect) : Mat3(1.0);
  // The viewport scaled into the image, centered (xMidYMid meet), when the image size differs from it.
  return fit(Vec4(0, 0, viewport->x, viewport->y), width, height, SvgAspect{}) * to_viewport;
}

std::vector<SvgPolyline> flatten_svg_subpaths(const std::vector<SvgSubpath>& subpaths, const Mat3& to_device,
                                              double tolerance) {
  return flatten(subpaths, to_device, tolerance, nullptr);
}

ImageRGBA render_svg(const SvgDocument& document, const SvgRenderOptions& options) {
  const Size2 size = svg_output_size(document, options);
  // Per pixel: the float RGBA image (16 bytes), one shape's coverage accumulator (4) and the 8-bit copy a writer makes.
  constexpr uint64_t kBytesPerPixel = sizeof(ImageRGBA::Pixel) + sizeof(float) + 4;
  MemoryBudget::check(saturating_product({uint64_t(size.width), uint64_t(size.height), kBytesPerPixel}),
                      fmt::format("{}: rendering at {}x{} pixels", document.source, size.width, size.height));
  ImageRGBA image(size.width, size.height, options.background);
  const Mat3 view = svg_viewport_transform(document, size.width, size.height);
  for (const SvgShape& shape : document.shapes)
    draw_shape(image, document.source, shape, view * shape.transform, options);
  return image;
}

}  // namespace tessera
