#pragma once
// Orthonormal frames: a basis (s, t, n) around a unit vector, for shading and sampling.
#include <cmath>

#include "tessera/math/types.hpp"

namespace tessera {

/// A right-handed orthonormal basis with n as its third axis.
struct Frame {
  Vec3f s, t, n;

  /// A frame around unit vector n, branch-free (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
  static Frame from_normal(const Vec3f& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3f(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3f(b, sign + n.y * n.y * a, -n.y), n};
  }
  /// World to local coordinates.
  Vec3f to_local(const Vec3f& v) const { return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)}; }
  /// Local to world coordinates.
  Vec3f to_world(const Vec3f& v) const { return v.x * s + v.y * t + v.z * n; }
};

}  // namespace tessera
