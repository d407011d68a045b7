#pragma once
// Tessera's math vocabulary: GLM's GLSL-like vectors and matrices (the notes' shader vocabulary).
//
// Transforms and cameras are in double precision (deep matrix hierarchies stay exact); the hot paths of the renderers
// (rays, boxes, vertices) use float. Column vectors, P' = M * P.
#include <glm/glm.hpp>

namespace tessera {

using Vec2 = glm::dvec2;
using Vec3 = glm::dvec3;
using Vec4 = glm::dvec4;
using Mat3 = glm::dmat3;
using Mat4 = glm::dmat4;

using Vec2f = glm::vec2;
using Vec3f = glm::vec3;
using Vec4f = glm::vec4;
using Mat3f = glm::mat3;
using Mat4f = glm::mat4;

inline constexpr double kPi = 3.14159265358979323846;

/// Degrees to radians (the library takes radians; the command line takes degrees).
constexpr double radians(double degrees) { return degrees * (kPi / 180.0); }
/// Radians to degrees.
constexpr double degrees(double radians) { return radians * (180.0 / kPi); }

}  // namespace tessera
