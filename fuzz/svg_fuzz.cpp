// Fuzz target for the SVG front end: parses arbitrary bytes and renders what parses at a tiny size. Malformed input
// must end in tessera::Error (a one-line message), never a crash, a hang or another exception.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tessera/core/error.hpp"
#include "tessera/svg/svg.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const tessera::SvgDocument document =
        tessera::parse_svg(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.svg");
    tessera::SvgRenderOptions options;
    options.width = 16;
    options.height = 12;
    tessera::render_svg(document, options);
  } catch (const tessera::Error&) {
  }
  return 0;
}
