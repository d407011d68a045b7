// libFuzzer target for the OFF reader: any input must parse or throw tessera::Error, never crash or hang.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tessera/core/error.hpp"
#include "tessera/mesh/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    tessera::read_off(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.off");
  } catch (const tessera::Error&) {
  }
  return 0;
}
