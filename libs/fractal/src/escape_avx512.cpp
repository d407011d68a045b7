// The escape-time loop on AVX-512F: 8 doubles per vector (compiled with -mavx512f -mfma -ffp-contract=off).
#include <immintrin.h>

#include "escape_simd.hpp"

namespace tessera::detail {
namespace {
struct Avx512Ops {
  using D = __m512d;
  static constexpr int kLanes = 8;
  static D load(const double* p) { return _mm512_load_pd(p); }
  static void store(double* p, D a) { _mm512_store_pd(p, a); }
  static D set1(double a) { return _mm512_set1_pd(a); }
  static D add(D a, D b) { return _mm512_add_pd(a, b); }
  static D sub(D a, D b) { return _mm512_sub_pd(a, b); }
  static D mul(D a, D b) { return _mm512_mul_pd(a, b); }
  static D fma(D a, D b, D c) { return _mm512_fmadd_pd(a, b, c); }
  static unsigned greater(D a, D b) { return unsigned(_mm512_cmp_pd_mask(a, b, _CMP_GT_OQ)); }
};
}  // namespace

void escape_points_avx512(const PointBatch& batch, const IterationLimits& limits) {
  escape_points_refill<Avx512Ops, 6>(batch, limits);
}

}  // namespace tessera::detail
