#pragma once
// The notes' `gt` layer for 2D: gtInitialize, gtPushMatrix, gtPopMatrix, gtTranslate, gtScale, gtRotate,
// gtBeginShape(GT_LINES), gtVertex, gtEndShape, gtWritePixel, as thin functions over a gt2d::Context.
//
// Each Context owns its image, matrix stack and shape state, so two contexts never interfere; the only global is
// the current-context pointer (per thread, as OpenGL's), set by gtMakeCurrent. The function names keep the notes'
// spelling (gtVertex, not gt_vertex) so code can be copied from the notes; the Context methods are snake_case.
//
// Coordinates, as the notes: gtVertex(x, y) is multiplied by the CTM, and the result is in pixels with the origin at
// the bottom-left, y up, pixel (i, j) centered on the integer point (i, j). GT_LINES pairs vertices into segments
// drawn with the notes' DDA line() (lines.hpp), which calls gtWritePixel(round(x), round(y), color). gtWritePixel(x, y)
// writes image row height - 1 - y (the image's row 0 is the top). To draw the notes' unit-square pictures (circles of
// radius 1, circle_image in [0, 1]^2) call gtScale(width, height) first, as the notes' [-2, 2] -> [0, 400] mapping
// (add 2, multiply by 100) is gtScale(100, 100) * gtTranslate(2, 2).
#include "tessera/image/image.hpp"
#include "tessera/math/matrix_stack.hpp"

namespace tessera::gt2d {

/// The notes' shape kinds: GT_LINES joins vertex pairs with lines; GT_POINTS writes each vertex's pixel.
enum GtShape { GT_POINTS, GT_LINES };

/// A drawing context of the gt layer: image, CTM stack, current color, the shape being built.
class Context {
 public:
  /// A width x height black image, white drawing color, identity CTM. Throws InvalidInput for a negative size.
  Context(int width, int height);

  /// gtInitialize: resizes to width x height, clears to black, resets the stack to [identity], color to white.
  void initialize(int width, int height);
  /// gtPushMatrix: replicates the CTM onto the top of the stack.
  void push_matrix() { stack_.push(); }
  /// gtPopMatrix: pops the top and throws it away. Throws InvalidInput on underflow.
  void pop_matrix() { stack_.pop(); }
  /// gtTranslate(x, y): CTM = CTM * T.
  void translate(double x, double y);
  /// gtScale(x, y): CTM = CTM * S.
  void scale(double x, double y);
  /// gtRotate(theta): CTM = CTM * R, counterclockwise by theta radians (y up).
  void rotate(double theta);
  /// gtColor(r, g, b): the color (in [0, 1]) later pixels are written with (a Tessera addition; the notes pass
  /// "3 color values" to gtWritePixel).
  void color(float r, float g, float b) { color_ = Vec4f(r, g, b, 1); }
  /// gtBeginShape(kind). Throws InvalidInput when a shape is already open.
  void begin_shape(GtShape kind);
  /// gtVertex(x, y): transforms (x, y) by the CTM; every second vertex of GT_LINES draws a line() from the previous
  /// one. Throws InvalidInput outside gtBeginShape/gtEndShape.
  void vertex(double x, double y);
  /// gtEndShape: ends the shape (an unpaired last GT_LINES vertex is dropped). Throws InvalidInput without a shape.
  void end_shape();
  /// gtWritePixel(x, y, r, g, b): sets pixel (x, y) (origin bottom-left, y up); pixels outside are ignored.
  void write_pixel(int x, int y, float r, float g, float b);

  const ImageRGBA& image() const { return image_; }
  const Mat3& matrix() const { return stack_.top(); }
  size_t stack_depth() const { return stack_.depth(); }

 private:
  ImageRGBA image_;
  MatrixStack2 stack_;
  Vec4f color_{1, 1, 1, 1};
  bool in_shape_ = false;
  GtShape kind_ = GT_LINES;
  bool has_pending_ = false;
  Vec2 pending_{0, 0};  // the first vertex of a GT_LINES pair, transformed
};

/// Makes `context` current for the gt* functions on this thread (null to release). The caller keeps it alive.
void gtMakeCurrent(Context* context);
/// The current context. Throws InvalidInput when there is none.
Context& gtCurrent();

/// The notes' functions on the current context (each throws InvalidInput without one; see the Context methods).
void gtInitialize(int width, int height);
void gtPushMatrix();
void gtPopMatrix();
void gtTranslate(double x, double y);
void gtScale(double x, double y);
void gtRotate(double theta);
void gtColor(float r, float g, float b);
void gtBeginShape(GtShape kind);
void gtVertex(double x, double y);
void gtEndShape();
void gtWritePixel(int x, int y, float r, float g, float b);

}  // namespace tessera::gt2d
