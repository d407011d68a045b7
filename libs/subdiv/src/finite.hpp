// Internal: checks that a result is finite. Subdivision and limit masks are affine combinations (the limit normal is
// a direction), so they are evaluated on points scaled by a power of two where coordinates pass 2^+-128
// (tessera/math/power_of_two.hpp) and the positions scaled back: the same result, bit for bit unless a small
// coordinate becomes subnormal, with no overflow (inf - inf made NaN vertices of finite input) or underflow.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "tessera/core/error.hpp"

namespace tessera::detail {

/// Throws InvalidInput naming `what`, the attribute `attribute` and the first entry of `values` (positions, uvs,
/// colors, normals) that is not finite: a result that is not finite is an error, never a file.
template <class V>
void require_finite(const std::vector<V>& values, const char* what, const char* attribute) {
  for (size_t i = 0; i < values.size(); ++i)
    for (int a = 0; a < V::length(); ++a)
      if (!std::isfinite(values[i][a]))
        throw InvalidInput(fmt::format("{}: {} {} of the result is not finite ({}; are the input's values finite?)",
                                       what, attribute, i, values[i][a]));
}

}  // namespace tessera::detail
