#pragma once
// What the CPU can run: one query for every module that picks an instruction set at run time (accel, fractal,
// raster3d, volume), instead of each asking the CPU itself.
#include <cstdint>

namespace tessera {

/// The x86 instruction set extensions Tessera's vector paths use, each true only when the CPU has it and the
/// operating system saves its registers (the compiler's runtime checks XGETBV). All false on other architectures.
struct CpuFeatures {
  bool avx2 = false;
  bool fma = false;
  bool avx512f = false;
  bool avx512bw = false;
  bool avx512vl = false;
  bool avx512dq = false;
};

/// The features of this CPU, asked once (thread-safe).
const CpuFeatures& cpu_features();

/// The widest instruction set level a path may assume: each level includes the one below.
enum class SimdLevel : uint8_t {
  baseline,  // x86-64 (SSE2)
  avx2,      // AVX2 and FMA
  avx512,    // AVX-512 F, BW, VL and DQ, with AVX2 and FMA
};

/// The widest SimdLevel that `features` (by default, this CPU's) has.
SimdLevel simd_level(const CpuFeatures& features = cpu_features());

/// The level's name: "baseline", "avx2" or "avx512".
const char* simd_level_name(SimdLevel level);

}  // namespace tessera
