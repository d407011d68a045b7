#pragma once
// What the two OSMesa comparison programs share (osmesa_compare_test.cpp, osmesa_stencil_blend_test.cpp).
#include "tessera/math/transform.hpp"
#include "tessera/math/types.hpp"

namespace tessera::osmesa_compare {

/// The clear color of both renderers.
inline const Vec3f kBackground{0.1f, 0.15f, 0.2f};

/// OpenGL's perspective projection (gluPerspective) of a w x h image, the field of view in degrees.
inline Mat4 persp(double fovy_degrees, int w, int h, double n, double f) {
  return perspective(radians(fovy_degrees), double(w) / double(h), n, f);
}

}  // namespace tessera::osmesa_compare
