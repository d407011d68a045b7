// libFuzzer target for the .bpt reader: parse arbitrary bytes from memory; tessera::Error is the expected outcome for
// malformed input, anything else (a crash, another exception, a sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tessera/core/error.hpp"
#include "tessera/curves/bpt.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto patches = tessera::parse_bpt(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
    // What parses must round-trip.
    if (tessera::parse_bpt(tessera::format_bpt(patches), "fuzz-again").size() != patches.size()) __builtin_trap();
  } catch (const tessera::Error&) {
  }
  return 0;
}
