#include "tessera/fractal/draw.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "tessera/core/error.hpp"
#include "tessera/raster2d/path.hpp"

namespace tessera {
namespace {

void check_frame(const PictureFrame& frame) {
  if (frame.width <= 0 || frame.height <= 0 || frame.width > 65536 || frame.height > 65536)
    throw InvalidInput(fmt::format("picture size {}x{} is invalid (1..65536 each)", frame.width, frame.height));
  if (!(frame.margin >= 0) || 2 * frame.margin >= std::min(frame.width, frame.height))
    throw InvalidInput(
        fmt::format("picture margin {} does not fit a {}x{} picture", frame.margin, frame.width, frame.height));
  if (!(frame.window.w > 0) || !(frame.window.h > 0)) throw InvalidInput("picture window must have a positive size");
}

ImageRGBA paper(const PictureFrame& frame, const Vec3f& color) {
  check_frame(frame);
  return ImageRGBA(frame.width, frame.height, Vec4f(color, 1.0f));
}

}  // namespace

PictureFrame frame_around(const std::vector<Vec2>& points, int width, int height, double margin) {
  if (points.empty()) throw InvalidInput("cannot frame an empty set of points");
  Vec2 lo = points.front(), hi = points.front();
  for (const Vec2& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  PictureFrame frame{width, height, margin};
  check_frame(frame);
  // Plane units per pixel: the larger of the two directions' needs, so that everything fits.
  const double inner_w = width - 2 * margin, inner_h = height - 2 * margin;
  const double unit = std::max({(hi.x - lo.x) / inner_w, (hi.y - lo.y) / inner_h, 1e-300});
  const Vec2 center = 0.5 * (lo + hi);
  frame.window = {center.x - 0.5 * inner_w * unit, center.y - 0.5 * inner_h * unit, inner_w * unit, inner_h * unit};
  return frame;
}

Vec2 to_pixels(const PictureFrame& frame, Vec2 p) {
  const double sx = (frame.width - 2 * frame.margin) / frame.window.w;
  const double sy = (frame.height - 2 * frame.margin) / frame.window.h;
  return {frame.margin + (p.x - frame.window.x) * sx, frame.height - frame.margin - (p.y - frame.window.y) * sy};
}

std::vector<std::vector<Vec2>> as_polygons(const std::vector<Rect>& rects) {
  std::vector<std::vector<Vec2>> out;
  out.reserve(rects.size());
  for (const Rect& r : rects) out.push_back({{r.x, r.y}, {r.x + r.w, r.y}, {r.x + r.w, r.y + r.h}, {r.x, r.y + r.h}});
  return out;
}

std::vector<std::vector<Vec2>> as_polygons(const std::vector<Triangle2>& triangles) {
  std::vector<std::vector<Vec2>> out;
  out.reserve(triangles.size());
  for (const Triangle2& t : triangles) out.push_back({t.a, t.b, t.c});
  return out;
}

void add_polygons(ImageRGBA& picture, const std::vector<std::vector<Vec2>>& polygons, const PictureFrame& frame,
                  const Vec3f& color, bool antialias) {
  Path path;
  path.contours.reserve(polygons.size());
  for (const auto& polygon : polygons) {
    std::vector<Vec2> contour;
    contour.reserve(polygon.size());
    for (const Vec2& p : polygon) contour.push_back(to_pixels(frame, p));
    path.contours.push_back(std::move(contour));
  }
  fill_path(picture, path, FillRule::non_zero, Vec4f(color, 1.0f), antialias);
}

void add_curve(ImageRGBA& picture, const std::vector<Vec2>& polyline, bool closed, const PictureFrame& frame,
               const Vec3f& color, double line_width, bool antialias) {
  if (!(line_width > 0)) throw InvalidInput(fmt::format("line width must be positive, got {}", line_width));
  std::vector<Vec2> pixels;
  pixels.reserve(polyline.size());
  for (const Vec2& p : polyline) pixels.push_back(to_pixels(frame, p));
  StrokeStyle style;
  style.width = line_width;
  style.join = LineJoin::round;
  style.cap = LineCap::round;
  fill_path(picture, stroke_path(pixels, closed, style), FillRule::non_zero, Vec4f(color, 1.0f), antialias);
}

ImageRGBA draw_polygons(const std::vector<std::vector<Vec2>>& polygons, const PictureFrame& frame,
                        const DrawStyle& style) {
  ImageRGBA picture = paper(frame, style.paper);
  add_polygons(picture, polygons, frame, style.ink, style.antialias);
  return picture;
}

ImageRGBA draw_curve(const std::vector<Vec2>& polyline, bool closed, const PictureFrame& frame,
                     const DrawStyle& style) {
  ImageRGBA picture = paper(frame, style.paper);
  add_curve(picture, polyline, closed, frame, style.ink, style.line_width, style.antialias);
  return picture;
}

Image<uint8_t> ink_mask(const ImageRGBA& picture, float threshold, bool invert) {
  Image<uint8_t> mask(picture.width(), picture.height());
  for (int y = 0; y < picture.height(); ++y)
    for (int x = 0; x < picture.width(); ++x) {
      const Vec4f& p = picture(x, y);
      const float paper = invert ? 0.0f : 1.0f;  // what shows through where the picture is transparent
      const float luminance = p.w * (0.2126f * p.x + 0.7152f * p.y + 0.0722f * p.z) + (1 - p.w) * paper;
      mask(x, y) = uint8_t((luminance < threshold) != invert);
    }
  return mask;
}

}  // namespace tessera
