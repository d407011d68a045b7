#pragma once
// Scaling by powers of two, so that sums, differences and cross products of coordinates near the ends of double's
// range neither overflow (inf - inf makes NaN) nor underflow to 0. Multiplying by 2^e is exact (but for subnormals),
// so an algorithm that is linear in its points (subdivision masks, smoothing steps), or whose result is a direction
// (normals), can run on the scaled points and scale back, and give the unit-scale result.
#include <algorithm>
#include <cmath>
#include <span>

#include "tessera/math/types.hpp"

namespace tessera {

/// The binary exponent e of `largest` (a magnitude) when it lies outside [2^-128, 2^128], else 0; 0 for 0 and for
/// non-finite values (which are left to propagate). Scaling by 2^-e brings the magnitude into [0.5, 1).
inline int rescale_exponent(double largest) {
  if (largest == 0 || !std::isfinite(largest)) return 0;
  int e = 0;
  std::frexp(largest, &e);
  return std::abs(e) > 128 ? e : 0;
}

/// The largest finite |component| of v.
inline double largest_component(const Vec3& v) {
  double largest = 0;
  for (int a = 0; a < 3; ++a)
    if (std::isfinite(v[a])) largest = std::max(largest, std::fabs(v[a]));
  return largest;
}

/// The largest finite |coordinate| of `points`.
inline double largest_coordinate(std::span<const Vec3> points) {
  double largest = 0;
  for (const Vec3& p : points) largest = std::max(largest, largest_component(p));
  return largest;
}

/// rescale_exponent of the largest finite coordinate of `points`.
inline int rescale_exponent(std::span<const Vec3> points) { return rescale_exponent(largest_coordinate(points)); }

/// v times 2^e, component by component.
inline Vec3 ldexp(const Vec3& v, int e) {
  return e ? Vec3(std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e)) : v;
}

/// Multiplies every point by 2^e.
inline void scale_by_power_of_two(std::span<Vec3> points, int e) {
  if (e)
    for (Vec3& p : points) p = ldexp(p, e);
}

}  // namespace tessera
