// The umbrella header alone is enough: it compiles without any other Tessera include, names something of every
// layer, and its version macros agree with project(VERSION) (EXPECTED_VERSION, passed by CMake) and with each other.
// Built twice: in the build tree (ctest umbrella.header_alone) and against an installed Tessera (install_test.sh).
#include <cstdio>
#include <cstring>
#include <string>

#include "tessera/tessera.hpp"

int main() {
  const std::string joined = std::to_string(TESSERA_VERSION_MAJOR) + "." + std::to_string(TESSERA_VERSION_MINOR) + "." +
                             std::to_string(TESSERA_VERSION_PATCH);
  bool ok = joined == TESSERA_VERSION_STRING && std::strlen(tessera::kGitHash) > 0;
#ifdef EXPECTED_VERSION
  ok = ok && joined == EXPECTED_VERSION;
#endif
  // A name from the bottom (core), the middle (mesh) and the top (scene) of the layers.
  ok = ok && tessera::simd_level_name(tessera::SimdLevel::avx2) == std::string("avx2");
  ok = ok && tessera::make_cube().face_count() == 6;
  ok = ok && sizeof(tessera::Scene) > 0;
  std::printf("umbrella: tessera %s (git %s): %s\n", tessera::kVersion, tessera::kGitHash, ok ? "ok" : "wrong");
  return ok ? 0 : 1;
}
