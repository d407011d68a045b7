// JPEG decoding with libjpeg-turbo (internal to the image module).
#pragma once

#include <string>
#include <string_view>

#include "tessera/image/image_io.hpp"

namespace tessera::detail {

/// True when `data` starts like a JPEG file (SOI marker followed by another marker), whatever its name says.
bool is_jpeg(std::string_view data);

/// Decodes the JPEG file `data` (named `name` in messages) to RGBA with alpha 1: an ImageRGBA8 when `keep_8bit`, else
/// that image's to_float. Gray, YCbCr, RGB, CMYK and YCCK files, baseline, extended and progressive. Throws
/// InvalidInput naming the file and the byte offset for a malformed, truncated or damaged file, and MemoryBudgetError
/// (before decoding) for one whose pixels would not fit in the budget.
FileImage decode_jpeg(std::string_view data, const std::string& name, bool keep_8bit);

}  // namespace tessera::detail
