#include "tessera/raster2d/gt2d.hpp"

#include <cmath>

#include "tessera/math/transform.hpp"
#include "tessera/raster2d/lines.hpp"

namespace tessera::gt2d {

Context::Context(int width, int height) : image_(width, height, Vec4f(0, 0, 0, 1)) {}

void Context::initialize(int width, int height) {
  image_ = ImageRGBA(width, height, Vec4f(0, 0, 0, 1));
  stack_ = MatrixStack2();
  color_ = Vec4f(1, 1, 1, 1);
  in_shape_ = false;
  has_pending_ = false;
}

void Context::translate(double x, double y) { stack_.multiply(translate2d(x, y)); }
void Context::scale(double x, double y) { stack_.multiply(scale2d(x, y)); }
void Context::rotate(double theta) { stack_.multiply(rotate2d(theta)); }

void Context::begin_shape(GtShape kind) {
  if (in_shape_) throw InvalidInput("gtBeginShape while a shape is open (missing gtEndShape)");
  in_shape_ = true;
  kind_ = kind;
  has_pending_ = false;
}

void Context::vertex(double x, double y) {
  if (!in_shape_) throw InvalidInput("gtVertex outside gtBeginShape/gtEndShape");
  const Vec2 p = transform_point(stack_.top(), Vec2(x, y));
  if (kind_ == GT_POINTS) {
    write_pixel(int(std::round(p.x)), int(std::round(p.y)), color_.x, color_.y, color_.z);
    return;
  }
  if (!has_pending_) {
    pending_ = p;
    has_pending_ = true;
    return;
  }
  has_pending_ = false;
  line_dda(pending_.x, pending_.y, p.x, p.y,
           [&](int px, int py, float) { write_pixel(px, py, color_.x, color_.y, color_.z); });
}

void Context::end_shape() {
  if (!in_shape_) throw InvalidInput("gtEndShape without gtBeginShape");
  in_shape_ = false;
  has_pending_ = false;
}

void Context::write_pixel(int x, int y, float r, float g, float b) {
  const int row = image_.height() - 1 - y;
  if (image_.contains(x, row)) image_(x, row) = Vec4f(r, g, b, 1);
}

namespace {
thread_local Context* current = nullptr;
}  // namespace

void gtMakeCurrent(Context* context) { current = context; }

Context& gtCurrent() {
  if (!current) throw InvalidInput("gt call without a current context (call gtMakeCurrent first)");
  return *current;
}

void gtInitialize(int width, int height) { gtCurrent().initialize(width, height); }
void gtPushMatrix() { gtCurrent().push_matrix(); }
void gtPopMatrix() { gtCurrent().pop_matrix(); }
void gtTranslate(double x, double y) { gtCurrent().translate(x, y); }
void gtScale(double x, double y) { gtCurrent().scale(x, y); }
void gtRotate(double theta) { gtCurrent().rotate(theta); }
void gtColor(float r, float g, float b) { gtCurrent().color(r, g, b); }
void gtBeginShape(GtShape kind) { gtCurrent().begin_shape(kind); }
void gtVertex(double x, double y) { gtCurrent().vertex(x, y); }
void gtEndShape() { gtCurrent().end_shape(); }
void gtWritePixel(int x, int y, float r, float g, float b) { gtCurrent().write_pixel(x, y, r, g, b); }

}  // namespace tessera::gt2d
