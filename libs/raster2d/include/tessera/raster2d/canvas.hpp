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
// stroke_cap, smooth/no_smooth (background, fill and stroke take a Vec4f or Processing's numbers: gray, gray + alpha,
// three components, three + alpha); colorMode(RGB|HSB, max...), color(...) -> color_mode(ColorMode::rgb|hsb, max...),
// color(...); point, line, rect, ellipse, arc, triangle, quad -> the same names; beginShape(kind), vertex,
// bezierVertex, quadraticVertex, beginContour, endContour, endShape(CLOSE) -> begin_shape(ShapeKind), vertex,
// bezier_vertex, quadratic_vertex, begin_contour, end_contour, end_shape(true); pushMatrix, popMatrix, translate,
// rotate, scale, shearX, shearY, applyMatrix, resetMatrix -> push_matrix, pop_matrix, translate, rotate, scale,
// shear_x, shear_y, apply_matrix, reset_matrix; text, textSize, textAlign, textWidth, textAscent, textDescent -> text,
// text_size, text_align(TextAlignX, TextAlignY), text_width, text_ascent, text_descent (the built-in bitmap font of
// font.hpp, no textFont); image(img, x, y[, w, h]) -> image(img, x, y[, w, h]); save(path) -> save(path). Only
// Processing's default modes are offered (rectMode(CORNER), ellipseMode(CENTER), imageMode(CORNER)).
#include <filesystem>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/matrix_stack.hpp"
#include "tessera/raster2d/font.hpp"
#include "tessera/raster2d/path.hpp"

namespace tessera {

/// A straight RGBA color from Processing's 0-255 integers (clamped), as color(r, g, b, a).
Vec4f rgb255(int r, int g, int b, int a = 255);
/// A gray from a 0-255 integer, as color(v, a).
Vec4f gray255(int v, int a = 255);

/// What begin_shape() builds from its vertices (Processing's beginShape kinds; Polygon is the default, no argument).
enum class ShapeKind { polygon, points, lines, triangles, triangle_strip, triangle_fan, quads, quad_strip };

/// How color_mode() reads the numbers given to fill, stroke, background and color (Processing's RGB and HSB).
enum class ColorMode { rgb, hsb };

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
  /// background(color(...)): the numbers read as color() reads them.
  void background(double gray) { background(color(gray)); }
  void background(double gray, double alpha) { background(color(gray, alpha)); }
  void background(double v1, double v2, double v3) { background(color(v1, v2, v3)); }
  void background(double v1, double v2, double v3, double alpha) { background(color(v1, v2, v3, alpha)); }
  void fill(const Vec4f& color) { fill_ = color; }
  /// fill(color(...)): the numbers read as color() reads them.
  void fill(double gray) { fill(color(gray)); }
  void fill(double gray, double alpha) { fill(color(gray, alpha)); }
  void fill(double v1, double v2, double v3) { fill(color(v1, v2, v3)); }
  void fill(double v1, double v2, double v3, double alpha) { fill(color(v1, v2, v3, alpha)); }
  void no_fill() { fill_.reset(); }
  void stroke(const Vec4f& color) { stroke_ = color; }
  /// stroke(color(...)): the numbers read as color() reads them.
  void stroke(double gray) { stroke(color(gray)); }
  void stroke(double gray, double alpha) { stroke(color(gray, alpha)); }
  void stroke(double v1, double v2, double v3) { stroke(color(v1, v2, v3)); }
  void stroke(double v1, double v2, double v3, double alpha) { stroke(color(v1, v2, v3, alpha)); }
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

  // ---- Color (Processing's colorMode and color) --------------------------------------------------------------------
  /// colorMode(mode): how later numbers are read; the ranges stay (Processing's start: RGB, every range 255).
  void color_mode(ColorMode mode) { color_mode_ = mode; }
  /// colorMode(mode, max): every range, alpha's too, becomes [0, max]. Throws InvalidInput unless max > 0 and finite.
  void color_mode(ColorMode mode, double max) { color_mode(mode, max, max, max, max); }
  /// colorMode(mode, max1, max2, max3): the three components' ranges (red, green, blue or hue, saturation,
  /// brightness); alpha's stays. Throws InvalidInput unless each max > 0 and finite.
  void color_mode(ColorMode mode, double max1, double max2, double max3) {
    color_mode(mode, max1, max2, max3, color_max_.w);
  }
  /// colorMode(mode, max1, max2, max3, maxA). Throws InvalidInput unless each max > 0 and finite.
  void color_mode(ColorMode mode, double max1, double max2, double max3, double max_alpha);
  /// color(gray): as Processing, a gray read against the FIRST range (in HSB too: colorMode(HSB, 360, 100, 100) makes
  /// color(180) a middle gray), clamped to it; opaque.
  Vec4f color(double gray) const { return color(gray, color_max_.w); }
  /// color(gray, alpha): alpha read against the alpha range.
  Vec4f color(double gray, double alpha) const;
  /// color(v1, v2, v3): red, green, blue (RGB) or hue, saturation, brightness (HSB; libs/color's hsv_to_rgb), each
  /// clamped to [0, its max] and divided by it; opaque. In HSB a hue of max is red again.
  Vec4f color(double v1, double v2, double v3) const { return color(v1, v2, v3, color_max_.w); }
  /// color(v1, v2, v3, alpha).
  Vec4f color(double v1, double v2, double v3, double alpha) const;

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

  // ---- Text: the built-in bitmap font (font.hpp), drawn in the fill color under the CTM --------------------------
  /// Draws `str` anchored at (x, y) as text_align() says ('\n' starts a line text_leading() lower; '\r' is ignored;
  /// characters outside printable ASCII draw a box). Each ink pixel of a glyph is a square of side text_size() / 8
  /// user units, and the squares are filled as one path under the CTM: with an integer scale and whole device
  /// coordinates every glyph pixel is exactly scale x scale device pixels; otherwise no_smooth() samples the bitmap at
  /// pixel centers (nearest neighbour) and smooth() gives each pixel its covered area. Nothing without a fill.
  void text(std::string_view str, double x, double y);
  /// textSize(px): the height from the top of the capitals to the bottom of the descenders, in user units; the
  /// bitmap's 8 rows are scaled by px / 8 (Tessera's default is 8, the font's native size; Processing's is 12).
  /// Throws InvalidInput unless px > 0 and finite.
  void text_size(double px);
  /// textAlign(alignX, alignY) (Processing's default: LEFT, BASELINE).
  void text_align(TextAlignX x, TextAlignY y = TextAlignY::baseline) { text_align_ = {x, y}; }
  /// textWidth(str): the widest line's advance width (6 units a character, so a trailing column of gap included).
  double text_width(std::string_view str) const;
  /// textAscent(): the capitals' height, 7/8 of text_size().
  double text_ascent() const { return font::kAscent * text_scale_; }
  /// textDescent(): the descenders' depth below the baseline, 1/8 of text_size().
  double text_descent() const { return font::kDescent * text_scale_; }
  /// The distance from one line's baseline to the next: 10/8 of text_size().
  double text_leading() const { return font::kLineHeight * text_scale_; }

  // ---- Images (Processing's image(), imageMode(CORNER)) --------------------------------------------------------
  /// Draws `img` with its top-left corner at (x, y), one image pixel per user unit, under the CTM.
  void image(const ImageRGBA& img, double x, double y) { image(img, x, y, img.width(), img.height()); }
  /// Draws `img` stretched over the rectangle (x, y, w, h) under the CTM (negative w or h mirror it). Each device
  /// pixel the rectangle covers (its footprint is filled as rect() fills, so smooth() antialiases its edges) maps its
  /// center back through the inverse of CTM x the rectangle's placement and samples the image there: smooth() samples
  /// bilinearly between texel centers (clamped at the image's edges), no_smooth() takes the nearest texel (Processing
  /// ties image smoothing to smooth() the same way). The sample, straight RGBA, is composited source-over with its
  /// alpha times the coverage; an identity placement copies the image exactly in either mode. Nothing when the image
  /// is empty or the placement is singular.
  void image(const ImageRGBA& img, double x, double y, double w, double h);
  /// The same for an 8-bit image (each channel / 255, no gamma).
  void image(const ImageRGBA8& img, double x, double y) { image(img, x, y, img.width(), img.height()); }
  void image(const ImageRGBA8& img, double x, double y, double w, double h);

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
  template <class Texel>
  void draw_image(const Image<Texel>& img, double x, double y, double w, double h);

  ImageRGBA image_;
  MatrixStack2 stack_;
  std::optional<Vec4f> fill_ = Vec4f(1, 1, 1, 1);
  std::optional<Vec4f> stroke_ = Vec4f(0, 0, 0, 1);
  double stroke_weight_ = 1;
  StrokeStyle stroke_style_{1, LineJoin::miter, LineCap::round, 4};
  bool smooth_ = true;
  FillRule fill_rule_ = FillRule::non_zero;
  ColorMode color_mode_ = ColorMode::rgb;
  Vec4 color_max_{255, 255, 255, 255};  // the ranges of colorMode: v1, v2, v3, alpha
  double text_scale_ = 1;               // user units per font unit: text_size() / 8
  std::pair<TextAlignX, TextAlignY> text_align_{TextAlignX::left, TextAlignY::baseline};
  // The shape under construction (device coordinates): contour 0 is the outline, the rest are holes; vertices go to
  // contours_[current_] (non-zero between begin_contour and end_contour).
  std::optional<ShapeKind> shape_;
  std::vector<std::vector<Vec2>> contours_;
  size_t current_ = 0;
};

}  // namespace tessera
