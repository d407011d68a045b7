#pragma once
// A Processing-style 2D canvas: shapes, fill and stroke styles, a matrix stack, all ending in write_pixel().
//
// Processing's coordinates (DESIGN.md section 3): origin top-left, y down, pixel (x, y) covers [x, x+1) x [y, y+1).
// Fills are half-open (rect(100, 200, 10, 10) covers exactly x in [100, 110), y in [200, 210)); smooth() gives exact
// area coverage instead. Colors are straight (non-premultiplied) RGBA in [0, 1]; rgb255() makes them from Processing's
// 0-255 ints. Angles are radians, measured from +x toward +y (clockwise on screen, as Processing).
//
// Processing -> Tessera: size(w, h) -> Canvas(w, h); background, fill/noFill, stroke/noStroke, strokeWeight,
// strokeJoin, strokeCap, smooth/noSmooth -> background, fill/no_fill, stroke/no_stroke, stroke_weight, stroke_join,
// stroke_cap, smooth/no_smooth; point, line, rect, ellipse, arc, triangle, quad -> the same names; beginShape(kind),
// vertex, bezierVertex, quadraticVertex, beginContour, endContour, endShape(CLOSE) -> begin_shape(ShapeKind),
// vertex, bezier_vertex, quadratic_vertex, begin_contour, end_contour, end_shape(true); pushMatrix, popMatrix,
// translate, rotate, scale, shearX, shearY, applyMatrix, resetMatrix -> push_matrix, pop_matrix, translate, rotate,
// scale, shear_x, shear_y, apply_matrix, reset_matrix; save(path) -> save(path). Only Processing's default modes are
// offered (rectMode(CORNER), ellipseMode(CENTER)).
#include <filesystem>
#include <optional>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/matrix_stack.hpp"
#include "tessera/raster2d/path.hpp"

namespace tessera {

/// A straight RGBA color from Processing's 0-255 integers (clamped), as color(r, g, b, a).
Vec4f rgb255(int r, int g, int b, int a = 255);
/// A gray from a 0-255 integer, as color(v, a).
Vec4f gray255(int v, int a = 255);

/// What begin_shape() builds from its vertices (Processing's beginShape kinds; Polygon is the default, no argument).
enum class ShapeKind { polygon, points, lines, triangles, triangle_strip, triangle_fan, quads, quad_strip };

/// How arc() closes (Processing's OPEN, CHORD, PIE). Open fills the region up to the chord but strokes only the arc.
enum class ArcMode { open, chord, pie };

/// A Processing-style drawing surface over an ImageRGBA. Every drawing call ends in write_pixel(). Filling is the
/// scanline rasterizer of scanline.hpp; strokes of a device width above one pixel are outlines (stroke_path) filled
/// with the nonzero rule; thinner strokes are the notes' DDA line (no_smooth) or Wu's line (smooth).
class Canvas {
 public:
  /// size(width, height): an opaque canvas of Processing's default gray (204); fill white, stroke black, stroke
  /// weight 1, round caps, miter joins, smooth. Throws InvalidInput for a negative size.
  Canvas(int width, int height);

  int width() const { return image_.width(); }
  int height() const { return image_.height(); }
  /// The pixels drawn so far (straight RGBA).
  const ImageRGBA& image() const { return image_; }
  /// Writes the image (PNG, PPM, ... by extension) atomically via write_image. Throws IoError / InvalidInput.
  void save(const std::filesystem::path& path) const;

  // ---- Style -------------------------------------------------------------------------------------------------------
  /// Replaces every pixel with `color` (no blending), as Processing's background().
  void background(const Vec4f& color);
  void fill(const Vec4f& color) { fill_ = color; }
  void no_fill() { fill_.reset(); }
  void stroke(const Vec4f& color) { stroke_ = color; }
  void no_stroke() { stroke_.reset(); }
  /// Stroke width in user units (scaled by the CTM). Throws InvalidInput when negative or not finite.
  void stroke_weight(double weight);
  void stroke_join(LineJoin join) { stroke_style_.join = join; }
  void stroke_cap(LineCap cap) { stroke_style_.cap = cap; }
  /// Antialiasing on (the default, as Processing) or off (pixel-center rule, aliased lines).
  void smooth() { smooth_ = true; }
  void no_smooth() { smooth_ = false; }
  /// The rule for shapes with contours (a Tessera extension; Processing's behavior is NonZero, the default).
  void fill_rule(FillRule rule) { fill_rule_ = rule; }

  // ---- Primitives (user coordinates, transformed by the CTM) -------------------------------------------------------
  /// A point in the stroke color: one pixel, or a disk of diameter stroke_weight when that exceeds one pixel.
  void point(double x, double y);
  void line(double x0, double y0, double x1, double y1);
  /// The rectangle with corner (x, y), width w and height h (rectMode(CORNER)).
  void rect(double x, double y, double w, double h);
  /// The ellipse centered at (cx, cy) with diameters w and h (ellipseMode(CENTER)), flattened so the polygon stays
  /// within 0.05 device pixels of the curve (with the area of the ellipse).
  void ellipse(double cx, double cy, double w, double h);
  /// The part of ellipse(cx, cy, w, h) from angle `start` to `stop` (radians, stop >= start; nothing when stop <
  /// start, at most one full turn).
  void arc(double cx, double cy, double w, double h, double start, double stop, ArcMode mode = ArcMode::open);
  void triangle(double x0, double y0, double x1, double y1, double x2, double y2);
  void quad(double x0, double y0, double x1, double y1, double x2, double y2, double x3, double y3);

  // ---- Shapes from vertices
  // ------------------------------------------------------------------------------------------
  /// Starts collecting vertices. Throws InvalidInput when a shape is already open.
  void begin_shape(ShapeKind kind = ShapeKind::polygon);
  /// Adds a vertex (transformed by the CTM now, as Processing). Throws InvalidInput outside begin_shape/end_shape.
  void vertex(double x, double y);
  /// A cubic Bezier from the last vertex through controls (cx1, cy1), (cx2, cy2) to (x, y), flattened by
  /// flatten_cubic to 0.02 device pixels. Throws InvalidInput without a previous vertex or outside a Polygon shape.
  void bezier_vertex(double cx1, double cy1, double cx2, double cy2, double x, double y);
  /// A quadratic Bezier from the last vertex through (cx, cy) to (x, y) (flatten_quadratic). Throws as bezier_vertex.
  void quadratic_vertex(double cx, double cy, double x, double y);
  /// Starts a hole (a further closed contour) of a Polygon shape. Throws InvalidInput outside one, or when nested.
  void begin_contour();
  /// Ends the contour begun by begin_contour(). Throws InvalidInput without one.
  void end_contour();
  /// Draws the collected shape; `close` closes a Polygon's outline stroke (CLOSE). Throws InvalidInput without
  /// begin_shape or with an open contour.
  void end_shape(bool close = false);

  // ---- Transformations (each multiplies the CTM on the right: the call written last acts first)
  // ----------------------
  void push_matrix() { stack_.push(); }
  /// Throws InvalidInput on underflow (a pop without a push).
  void pop_matrix() { stack_.pop(); }
  void translate(double dx, double dy);
  /// Rotation by `angle` radians from +x toward +y (clockwise on screen, y down).
  void rotate(double angle);
  void scale(double s) { scale(s, s); }
  void scale(double sx, double sy);
  /// x' = x + tan(angle) y (Processing's shearX).
  void shear_x(double angle);
  /// y' = y + tan(angle) x (Processing's shearY).
  void shear_y(double angle);
  /// CTM = CTM * m for a 3x3 homogeneous 2D matrix.
  void apply_matrix(const Mat3& m) { stack_.multiply(m); }
  /// CTM = identity (the stack's depth is unchanged).
  void reset_matrix() { stack_.load_identity(); }
  /// The current transformation matrix.
  const Mat3& matrix() const { return stack_.top(); }

  // ---- Pixels
  // --------------------------------------------------------------------------------------------------------
  /// Composites `color` (straight RGBA, its alpha scaled by `coverage` in [0, 1]) source-over onto pixel (x, y);
  /// pixels outside the canvas are ignored. The primitive every drawing call ends in.
  void write_pixel(int x, int y, const Vec4f& color, float coverage = 1.0f);

 private:
  Vec2 to_device(double x, double y) const;
  double device_scale() const;  // sqrt |det| of the CTM's linear part: how strokes scale
  int ellipse_segments(double w, double h, double sweep) const;
  std::vector<Vec2> arc_points(double cx, double cy, double w, double h, double start, double sweep, int n,
                               bool keep_ends) const;
  void paint(const Path& path, FillRule rule, const Vec4f& color);  // scan_path -> write_pixel
  void fill_device(const Path& path);
  void stroke_device(const std::vector<Vec2>& points, bool closed);
  void point_device(const Vec2& p);
  void draw_device_polygon(const std::vector<Vec2>& points);  // fill and closed stroke
  void require_shape(const char* what) const;

  ImageRGBA image_;
  MatrixStack2 stack_;
  std::optional<Vec4f> fill_ = Vec4f(1, 1, 1, 1);
  std::optional<Vec4f> stroke_ = Vec4f(0, 0, 0, 1);
  double stroke_weight_ = 1;
  StrokeStyle stroke_style_{1, LineJoin::miter, LineCap::round, 4};
  bool smooth_ = true;
  FillRule fill_rule_ = FillRule::non_zero;
  // The shape under construction (device coordinates): contour 0 is the outline, the rest are holes; vertices go to
  // contours_[current_] (non-zero between begin_contour and end_contour).
  std::optional<ShapeKind> shape_;
  std::vector<std::vector<Vec2>> contours_;
  size_t current_ = 0;
};

}  // namespace tessera
