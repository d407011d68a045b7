// libFuzzer target for every image reader behind tessera::decode_image (what read_image, textures and slice stacks
// use): the first byte picks the file name's extension (.png .jpg .jpeg .bmp .tga .hdr .ppm .pgm .pnm .pfm, or an
// unknown .gif), the rest is the file. The extension picks Tessera's own reader for PPM/PGM and PFM and stb_image for
// the others, except that JPEG and binary Netpbm files go to libjpeg-turbo and Tessera's reader by their signatures
// (stb_image goes by the content too, so any of its formats can arrive under any of those names). The memory budget
// is 16 MiB, so that a header declaring a large image is refused before decoding (as a decompression bomb would be)
// and one input stays well under a second under the sanitizers (at 64 MiB, 3-million-pixel TGAs from 23 bytes took
// over a second each, and past libFuzzer's timeout on a loaded machine).
// tessera::Error is the expected outcome for a malformed file; anything else (a crash, another exception, a sanitizer
// report) is a bug, and so is a decoded image that is empty, or one whose values are outside [0, 1] (8- and 16-bit
// formats: PNG, JPEG, BMP, TGA, PPM/PGM), negative or not finite (Radiance HDR), or not finite (PFM, whose
// reader refuses NaN and infinity).
// The native read (8-bit files kept 8-bit, what textures use) must decode the same file to the same values: v/255 of
// each 8-bit sample is the float read's value, and a float result is the float read's, bit for bit.
// stb_image is compiled with the project (libs/image/src/stb.cpp), so libFuzzer's coverage, ASan and UBSan see inside
// it; libjpeg-turbo is Debian's prebuilt library (fuzzed by OSS-Fuzz), seen only through intercepted calls. Before
// stb was compiled here, this target found a JPEG that decoded differently on each read (stb read memory it never
// wrote), and instrumenting stb then showed its DHT parser writing past its Huffman tables: hence libjpeg-turbo.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <variant>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/image/image_io.hpp"

namespace {

constexpr std::string_view kNames[] = {"fuzz.png", "fuzz.jpg", "fuzz.jpeg", "fuzz.bmp", "fuzz.tga", "fuzz.hdr",
                                       "fuzz.ppm", "fuzz.pgm", "fuzz.pnm",  "fuzz.pfm", "fuzz.gif"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  tessera::MemoryBudget::set_limit(uint64_t(16) << 20);
  const std::string_view name = kNames[data[0] % std::size(kNames)];
  const std::string_view file(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const tessera::ImageRGBA image = tessera::decode_image(file, name);
    if (image.width() < 1 || image.height() < 1) __builtin_trap();
    if (name.ends_with(".pfm")) {
      for (const auto& p : image.pixels())
        for (int c = 0; c < 4; ++c)
          if (!std::isfinite(p[c])) __builtin_trap();
      return 0;
    }
    // stb_image decodes Radiance files (magic "#?") to linear floats, whatever the name says.
    const bool netpbm = name.ends_with(".ppm") || name.ends_with(".pgm") || name.ends_with(".pnm");
    const bool hdr = !netpbm && file.starts_with("#?");
    for (const auto& p : image.pixels())
      for (int c = 0; c < 4; ++c)
        if (!(p[c] >= 0 && (hdr ? std::isfinite(p[c]) : p[c] <= 1))) __builtin_trap();
    const tessera::FileImage native = tessera::decode_image_native(file, name);
    if (const auto* bytes = std::get_if<tessera::ImageRGBA8>(&native)) {
      if (bytes->width() != image.width() || bytes->height() != image.height()) __builtin_trap();
      for (size_t i = 0; i < image.pixels().size(); ++i)
        for (int c = 0; c < 4; ++c)
          if (float(bytes->pixels()[i][c]) / 255.f != image.pixels()[i][c]) __builtin_trap();
    } else if (std::get<tessera::ImageRGBA>(native).pixels().size() != image.pixels().size()) {
      __builtin_trap();
    }
  } catch (const tessera::Error&) {
  }
  return 0;
}
