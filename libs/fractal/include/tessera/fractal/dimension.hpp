#pragma once
// Fractal dimension of a binary image by box counting: N(s) = number of s x s grid boxes holding at least one set
// pixel; for a fractal N(s) ~ (1/s)^D, so D is the least-squares slope of log N(s) against log(1/s).
#include <cstdint>
#include <vector>

#include "tessera/image/image.hpp"

namespace tessera {

/// Which box sizes are counted: max_box, max_box / factor, max_box / factor², ... down to min_box. The sizes are real
/// numbers of pixels: anchored at the set's extent, every size divides it into factorᵏ boxes, so a filled square or
/// a straight line is measured exactly whatever its size in pixels.
struct BoxCountOptions {
  double min_box = 1;  ///< smallest box side in pixels (>= 1: smaller boxes only see single pixels again)
  double max_box = 0;  ///< largest box side in pixels; 0 = the set's extent (the longer side of its bounding box)
  double factor = 2;   ///< ratio between successive sizes (> 1); 3 suits pictures of triadic sets (Cantor, Koch)
};

/// The counts and the fitted dimension.
struct BoxCountResult {
  int extent = 0;               ///< longer side of the set pixels' bounding box (the grid starts at its corner)
  std::vector<double> sizes;    ///< box sides s in pixels, decreasing from max_box
  std::vector<int64_t> counts;  ///< N(s): boxes of the grid from the bounding box's corner that hold a set pixel
  size_t fitted = 0;            ///< how many sizes the fit used: those with N(s) >= 2 (one box says nothing)
  double dimension = 0;         ///< least-squares slope of log N(s) over log(1/s), over the fitted sizes
};

/// Box-counting dimension of the nonzero pixels of `mask`. The grid starts at the corner of the set's bounding box,
/// so where the set lies in the picture and the picture's aspect ratio do not matter. Throws InvalidInput when the
/// mask is empty (no set pixel), when fewer than two sizes with N(s) >= 2 fit, or for bad options.
BoxCountResult box_counting_dimension(const Image<uint8_t>& mask, const BoxCountOptions& options = {});

}  // namespace tessera
