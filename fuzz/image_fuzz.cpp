// libFuzzer target for Tessera's own image readers (PPM/PGM and PFM; the other formats are stb_image's): the first
// byte picks the format, the rest is the file. tessera::Error is the expected outcome for a malformed file; anything
// else (a crash, another exception, a sanitizer report, an allocation beyond kMaxReadPixels) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tessera/core/error.hpp"
#include "tessera/image/image_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string_view file(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const tessera::ImageRGBA image = tessera::decode_image(file, data[0] % 2 ? "fuzz.pfm" : "fuzz.ppm");
    if (image.width() < 1 || image.height() < 1) __builtin_trap();
  } catch (const tessera::Error&) {
  }
  return 0;
}
