#include "tessera/core/cpu.hpp"

namespace tessera {

const CpuFeatures& cpu_features() {
  static const CpuFeatures features = [] {
    CpuFeatures f;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();  // harmless after main; needed if a static initializer asks first
    f.avx2 = __builtin_cpu_supports("avx2");
    f.fma = __builtin_cpu_supports("fma");
    f.avx512f = __builtin_cpu_supports("avx512f");
    f.avx512bw = __builtin_cpu_supports("avx512bw");
    f.avx512vl = __builtin_cpu_supports("avx512vl");
    f.avx512dq = __builtin_cpu_supports("avx512dq");
#endif
    return f;
  }();
  return features;
}

SimdLevel simd_level(const CpuFeatures& f) {
  if (!(f.avx2 && f.fma)) return SimdLevel::baseline;
  return f.avx512f && f.avx512bw && f.avx512vl && f.avx512dq ? SimdLevel::avx512 : SimdLevel::avx2;
}

const char* simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::avx2:
      return "avx2";
    case SimdLevel::avx512:
      return "avx512";
    default:
      return "baseline";
  }
}

}  // namespace tessera
