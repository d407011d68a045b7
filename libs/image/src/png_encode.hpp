// PNG encoding with zlib (internal to the image module).
#pragma once

#include <cstdint>
#include <string>

namespace tessera::detail {

/// Encodes 8-bit RGB (channels 3) or RGBA (channels 4) pixels, rows top first with no padding, as a complete PNG
/// file. Each row gets the filter with the smallest sum of absolute values (libpng's heuristic); bands of rows are
/// deflated in parallel and joined into one zlib stream, so the bytes do not depend on the thread count.
std::string encode_png(const uint8_t* pixels, int width, int height, int channels);

}  // namespace tessera::detail
