// Internal: evaluating masks on points scaled by a power of two, so that sums and cross products of coordinates near
// the ends of double's range neither overflow (inf - inf made NaN vertices of finite input) nor underflow.
#pragma once

#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "tessera/core/error.hpp"
#include "tessera/math/types.hpp"

namespace tessera::detail {

/// The binary exponent e of the largest finite |coordinate| of `points` when it lies outside [2^-128, 2^128], else
/// 0. Subdivision and limit masks are affine combinations (the limit normal is a direction), so evaluating them on
/// the points times 2^-e and scaling the positions back by 2^e gives the same result, bit for bit unless a small
/// coordinate becomes subnormal: with coordinates of magnitude at most 1, mask sums and tangent cross products stay
/// far from overflow.
inline int rescale_exponent(const std::vector<Vec3>& points) {
  double largest = 0;
  for (const Vec3& p : points)
    for (int a = 0; a < 3; ++a)
      if (std::isfinite(p[a])) largest = std::max(largest, std::fabs(p[a]));
  if (largest == 0) return 0;
  int e = 0;
  std::frexp(largest, &e);
  return std::abs(e) > 128 ? e : 0;
}

/// Multiplies every coordinate by 2^e (exact, but for subnormals).
inline void scale_by_power_of_two(std::vector<Vec3>& points, int e) {
  for (Vec3& p : points)
    for (int a = 0; a < 3; ++a) p[a] = std::ldexp(p[a], e);
}

/// Throws InvalidInput naming `what`, the attribute `attribute` and the first entry of `values` (positions, uvs,
/// colors, normals) that is not finite: a result that is not finite is an error, never a file.
template <class V>
void require_finite(const std::vector<V>& values, const char* what, const char* attribute) {
  for (size_t i = 0; i < values.size(); ++i)
    for (int a = 0; a < V::length(); ++a)
      if (!std::isfinite(values[i][a]))
        throw InvalidInput(fmt::format("{}: {} {} of the result is not finite ({}; are the input's values finite?)", what,
                                       attribute, i, values[i][a]));
}

}  // namespace tessera::detail
