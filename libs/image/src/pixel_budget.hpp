// The size and memory checks every image reader makes from a header, before decoding (internal to the image module).
#pragma once

#include <cstdint>
#include <string>

namespace tessera::detail {

/// Refuses an image size that is invalid or larger than kMaxReadPixels, or whose decoding needs more than the memory
/// budget: `bytes_per_pixel` is what the reader holds at its peak (the decoder's samples plus the image: 16 bytes of
/// float RGBA, or 4 of 8-bit RGBA when an 8-bit file is read natively), counted from the header before any pixel is
/// decoded (a 746 KB PNG can declare 16000x16000 pixels). Throws InvalidInput or MemoryBudgetError naming `name`.
void check_pixel_count(const std::string& name, long long width, long long height, uint64_t bytes_per_pixel);

}  // namespace tessera::detail
