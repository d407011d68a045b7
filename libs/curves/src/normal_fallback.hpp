#pragma once
// The normal of a parametric surface where its partial derivatives may vanish or be parallel (poles of a sphere,
// the collapsed control rows of the teapot's lid and bottom): shared by parametric surfaces and Bezier patches.
#include <array>
#include <cmath>

#include "tessera/curves/surface.hpp"

namespace tessera::detail {

/// The unit (du x dv)(u, v) from partials(u, v) -> {du, dv}. When |du x dv| <= 1e-10 scale^2 (scale: a typical
/// partial-derivative length) the normal is taken at (u, v) moved toward the domain's center by 1e-6, 1e-4, then 1e-2
/// of the way: the limit direction at a collapsed edge or corner. Zero when every try is degenerate.
template <class Partials>
Vec3 normal_with_fallback(const Partials& partials, double u, double v, ParamInterval ur, ParamInterval vr,
                          double scale) {
  const double threshold = 1e-10 * scale * scale;
  const double cu = 0.5 * (ur.lo + ur.hi), cv = 0.5 * (vr.lo + vr.hi);
  for (const double f : {0.0, 1e-6, 1e-4, 1e-2}) {
    const std::array<Vec3, 2> d = partials(u + f * (cu - u), v + f * (cv - v));
    const Vec3 n = glm::cross(d[0], d[1]);
    const double len = glm::length(n);
    if (len > threshold && std::isfinite(len)) return n / len;
  }
  return Vec3(0.0);
}

}  // namespace tessera::detail
