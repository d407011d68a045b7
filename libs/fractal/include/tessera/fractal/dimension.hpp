#pragma once
// Fractal dimension of a binary image by box counting: N(s) = number of s x s grid boxes holding at least one set
// pixel; for a fractal N(s) ~ (1/s)^D, so D is the least-squares slope of log N(s) against log(1/s).
#include <cstdint>
#include <vector>

#include "tessera/image/image.hpp"

namespace tessera {

/// Which box sizes are counted: min_box, min_box * factor, ... (rounded, distinct) up to max_box.
struct BoxCountOptions {
  int min_box = 2;    ///< smallest box side in pixels (>= 1); 1 only sees single pixels, the raster's own scale
  int max_box = 0;    ///< largest box side in pixels; 0 = a quarter of the image's shorter side (at least min_box)
  double factor = 2;  ///< ratio between successive sizes (> 1); 3 suits pictures of triadic sets (Cantor, Koch)
};

/// The counts and the fitted dimension.
struct BoxCountResult {
  std::vector<int> sizes;       ///< box sides s, increasing
  std::vector<int64_t> counts;  ///< N(s): boxes (aligned to the top-left corner, partial ones at the edges included)
  double dimension = 0;         ///< least-squares slope of log N(s) over log(1/s)
};

/// Box-counting dimension of the nonzero pixels of `mask`. Throws InvalidInput when the mask is empty (no set
/// pixel), when fewer than two box sizes fit, or for bad options.
BoxCountResult box_counting_dimension(const Image<uint8_t>& mask, const BoxCountOptions& options = {});

}  // namespace tessera
