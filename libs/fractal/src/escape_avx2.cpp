// The escape-time loop on AVX2 + FMA: 4 doubles per vector (compiled with -mavx2 -mfma -ffp-contract=off).
#include <immintrin.h>

#include "escape_simd.hpp"

namespace tessera::detail {
namespace {
struct Avx2Ops {
  using D = __m256d;
  static constexpr int kLanes = 4;
  static D load(const double* p) { return _mm256_load_pd(p); }
  static void store(double* p, D a) { _mm256_store_pd(p, a); }
  static D set1(double a) { return _mm256_set1_pd(a); }
  static D add(D a, D b) { return _mm256_add_pd(a, b); }
  static D sub(D a, D b) { return _mm256_sub_pd(a, b); }
  static D mul(D a, D b) { return _mm256_mul_pd(a, b); }
  static D fma(D a, D b, D c) { return _mm256_fmadd_pd(a, b, c); }
  static unsigned greater(D a, D b) { return unsigned(_mm256_movemask_pd(_mm256_cmp_pd(a, b, _CMP_GT_OQ))); }
};
}  // namespace

void escape_points_avx2(const PointBatch& batch, const IterationLimits& limits) {
  escape_points_refill<Avx2Ops, 6>(batch, limits);
}

}  // namespace tessera::detail
