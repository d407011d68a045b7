#pragma once
// Many colors at once, for convert_many: the hue models' conversions from linear RGB, two colors per SSE2 instruction.
#include <span>

namespace tessera::detail {

/// rgb_to_hsv of every row (r, g, b) of `in` into the same row of `out` (both 3 doubles a color, the same size): the
/// one-color function's operations in its order, two colors at a time, so the same values bit for bit.
void rgb_to_hsv_rows(std::span<const double> in, std::span<double> out);
/// rgb_to_hls of every row, as rgb_to_hsv_rows.
void rgb_to_hls_rows(std::span<const double> in, std::span<double> out);

}  // namespace tessera::detail
