#pragma once
// The notes' `gt` layer for 3D: gtPushMatrix, gtPopMatrix, gtTranslate, gtScale, gtRotateX/Y/Z, gtRotate,
// gtOrtho, gtPerspective, gtLookAt, gtBeginShape, gtVertex, gtNormal, gtColor, gtEndShape, as thin functions over a
// raster3d::Context, like raster2d's gt2d layer.
//
// Each Context owns all its state; the only global is the current-context pointer (per thread, as OpenGL's), set by
// gtMakeCurrent. The names keep the notes' spelling so code can be copied from the notes. Angles are radians (the
// notes and GLSL; DESIGN.md section 3), including gtPerspective's field of view. As the notes' course library,
// gtOrtho and gtPerspective set the projection matrix, and every other matrix call changes the model-view stack.
#include "tessera/raster3d/context.hpp"

namespace tessera::gt {

/// The shape kinds of gtBeginShape (OpenGL's primitives).
enum GtShape {
  GT_POINTS,
  GT_LINES,
  GT_LINE_STRIP,
  GT_LINE_LOOP,
  GT_TRIANGLES,
  GT_TRIANGLE_STRIP,
  GT_TRIANGLE_FAN,
  GT_QUADS,
  GT_POLYGON,
};

namespace detail {
// The current context of this thread (constinit: read without a TLS wrapper call from the inline functions below).
inline constinit thread_local raster3d::Context* current_context = nullptr;
[[noreturn]] void throw_no_current_context();
}  // namespace detail

/// Makes `context` current for the gt* functions on this thread (null to release). The caller keeps it alive.
void gtMakeCurrent(raster3d::Context* context);
/// The current context. Throws InvalidInput when there is none.
inline raster3d::Context& gtCurrent() {
  if (!detail::current_context) [[unlikely]]
    detail::throw_no_current_context();
  return *detail::current_context;
}

/// gtInitialize(width, height): resizes the current context and resets its state (Context::initialize).
void gtInitialize(int width, int height);
/// gtClear(r, g, b): clears color and depth.
void gtClear(float r, float g, float b);
/// The model-view stack (Context::push_matrix and friends on MatrixMode::model_view).
void gtPushMatrix();
void gtPopMatrix();
void gtLoadIdentity();
void gtTranslate(double x, double y, double z);
void gtScale(double x, double y, double z);
void gtRotateX(double angle);
void gtRotateY(double angle);
void gtRotateZ(double angle);
void gtRotate(double angle, double ax, double ay, double az);
/// The notes' camera(ex, ey, ez, cx, cy, cz, ux, uy, uz): model-view = model-view * look_at.
void gtLookAt(double ex, double ey, double ez, double cx, double cy, double cz, double ux, double uy, double uz);
/// Projection = ortho(left, right, bottom, top, near, far).
void gtOrtho(double left, double right, double bottom, double top, double near, double far);
/// Projection = perspective(fovy radians, the viewport's aspect, near, far).
void gtPerspective(double fovy, double near, double far);
/// Immediate mode. gtVertex and gtNormal are inline: they are called once per vertex.
void gtBeginShape(GtShape kind);
inline void gtVertex(double x, double y, double z) { gtCurrent().vertex(x, y, z); }
inline void gtNormal(double x, double y, double z) { gtCurrent().normal(Vec3f(x, y, z)); }
void gtColor(float r, float g, float b);
void gtTexCoord(double u, double v);
void gtEndShape();
/// Draws everything pending and presents the frame (Context::swap_buffers).
void gtSwapBuffers();

}  // namespace tessera::gt
