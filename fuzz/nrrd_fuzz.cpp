// libFuzzer target for the NRRD reader: parses the input from memory (detached data files refused); every rejection
// must be a tessera::Error, never a crash, a hang or an unbounded allocation.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tessera/core/error.hpp"
#include "tessera/volume/volume_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    (void)tessera::parse_nrrd(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.nrrd");
  } catch (const tessera::Error&) {
  }
  return 0;
}
