#include "tessera/raster3d/gt.hpp"

namespace tessera::gt {
void detail::throw_no_current_context() {
  throw InvalidInput("gt call without a current context (call gtMakeCurrent first)");
}

void gtMakeCurrent(raster3d::Context* context) { detail::current_context = context; }

namespace {
// The model-view stack: every gt matrix call but gtOrtho/gtPerspective acts on it.
raster3d::Context& model_view() {
  raster3d::Context& c = gtCurrent();
  c.matrix_mode(raster3d::MatrixMode::model_view);
  return c;
}
}  // namespace

void gtInitialize(int width, int height) { gtCurrent().initialize(width, height); }
void gtClear(float r, float g, float b) { gtCurrent().clear(Vec3f(r, g, b)); }
void gtPushMatrix() { model_view().push_matrix(); }
void gtPopMatrix() { model_view().pop_matrix(); }
void gtLoadIdentity() { model_view().load_identity(); }
void gtTranslate(double x, double y, double z) { model_view().translate(x, y, z); }
void gtScale(double x, double y, double z) { model_view().scale(x, y, z); }
void gtRotateX(double angle) { model_view().rotate_x(angle); }
void gtRotateY(double angle) { model_view().rotate_y(angle); }
void gtRotateZ(double angle) { model_view().rotate_z(angle); }
void gtRotate(double angle, double ax, double ay, double az) { model_view().rotate(angle, Vec3(ax, ay, az)); }
void gtLookAt(double ex, double ey, double ez, double cx, double cy, double cz, double ux, double uy, double uz) {
  gtCurrent().look_at(Vec3(ex, ey, ez), Vec3(cx, cy, cz), Vec3(ux, uy, uz));
}
void gtOrtho(double left, double right, double bottom, double top, double near, double far) {
  gtCurrent().ortho(left, right, bottom, top, near, far);
}
void gtPerspective(double fovy, double near, double far) { gtCurrent().perspective(fovy, near, far); }

void gtBeginShape(GtShape kind) { gtCurrent().begin(raster3d::Primitive(int(kind))); }
void gtColor(float r, float g, float b) { gtCurrent().color(Vec3f(r, g, b)); }
void gtTexCoord(double u, double v) { gtCurrent().texcoord(Vec2f(u, v)); }
void gtEndShape() { gtCurrent().end(); }
void gtSwapBuffers() { gtCurrent().swap_buffers(); }

}  // namespace tessera::gt
