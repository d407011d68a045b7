// The span kernels for AVX-512 (compiled with -mavx512f -mavx512vl -mavx512bw -mavx512dq -mfma
// -ffp-contract=off): sixteen floats per instruction, and the Gouraud rectangles as eight pixels of two rows with mask
// registers. Chosen by span_kernels() where the CPU has these extensions.
#include <immintrin.h>

#include "span_kernels.hpp"

// GCC 12's AVX-512 intrinsics start from _mm512_undefined_*(), which -Wmaybe-uninitialized reports once inlined
// (a GCC warning: clang has no such group, and -Wall would report the unknown name).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace tessera::raster3d::detail {
namespace {

/// The AVX-512 integer compare of a depth function that compares (not never or always).
template <DepthFunc F>
inline constexpr int kDepthCmpInt = F == DepthFunc::less       ? _MM_CMPINT_LT
                                    : F == DepthFunc::equal    ? _MM_CMPINT_EQ
                                    : F == DepthFunc::lequal   ? _MM_CMPINT_LE
                                    : F == DepthFunc::greater  ? _MM_CMPINT_GT
                                    : F == DepthFunc::notequal ? _MM_CMPINT_NE
                                                               : _MM_CMPINT_GE;

/// depth_passes8 for sixteen lanes as a mask register, within `lanes`: one compare instead of two halves.
template <DepthFunc F>
[[gnu::always_inline]] inline __mmask16 depth_passes16(__mmask16 lanes, __m512i d, __m512i s) {
  if constexpr (F == DepthFunc::never)
    return 0;
  else if constexpr (F == DepthFunc::always)
    return lanes;
  else
    return _mm512_mask_cmp_epi32_mask(lanes, d, s, kDepthCmpInt<F>);
}

/// gouraud_rect_avx2 for AVX-512: sixteen lanes, eight pixels of two rows, with mask registers for the masked
/// loads and stores. The same operations per pixel, so the same pixels.
template <DepthFunc F>
void gouraud_rect_avx512(const TriangleRecord& r, const float* planes, int x0, int x1, int y0, int y1, int x_owned,
                         Image<uint32_t>& depth, ImageRGBA8& color, bool write_depth) {
  const int height = depth.height();
  const float* pc = planes;
  const float* px = planes + 4;
  const float* py = planes + 8;
  const __m512i col = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7);
  const __m512i up = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1);  // lanes 8-15: GL row + 1
  __m512i edge_row[3], edge_dy2[3], edge_dx8[3];
  for (int k = 0; k < 3; ++k) {
    const Edge& e = r.edges[k];
    const auto e0 = int32_t(int64_t(e.a) * 256 * x0 + int64_t(e.b) * 256 * y0 + e.c);
    const __m512i lanes = _mm512_add_epi32(_mm512_mullo_epi32(col, _mm512_set1_epi32(e.a * 256)),
                                           _mm512_mullo_epi32(up, _mm512_set1_epi32(e.b * 256)));
    edge_row[k] = _mm512_add_epi32(_mm512_set1_epi32(e0), lanes);
    edge_dy2[k] = _mm512_set1_epi32(e.b * 256 * 2);
    edge_dx8[k] = _mm512_set1_epi32(e.a * 256 * 8);
  }
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f), half = _mm512_set1_ps(0.5f);
  const __m512 rx = _mm512_set1_ps(r.rx), ry = _mm512_set1_ps(r.ry), zdx = _mm512_set1_ps(r.zdx);
  const __m512 zdy = _mm512_set1_ps(r.zdy), za = _mm512_set1_ps(r.za), depth_scale = _mm512_set1_ps(float(kDepthMax));
  const __m512 c255 = _mm512_set1_ps(255.0f), round_magic = _mm512_set1_ps(12582912.0f);
  __m512 pxv[4];
  for (int k = 0; k < 4; ++k) pxv[k] = _mm512_set1_ps(px[k]);
  for (int j = y0; j < y1; j += 2) {
    const bool two = j + 1 < y1;
    const __mmask16 rows = two ? __mmask16(0xffff) : __mmask16(0x00ff);
    const int row = height - 1 - j;
    uint32_t* drow[2] = {depth.row(row), depth.row(two ? row - 1 : row)};
    int32_t* crow[2] = {reinterpret_cast<int32_t*>(color.row(row)),
                        reinterpret_cast<int32_t*>(color.row(two ? row - 1 : row))};
    const __m512i jv = _mm512_add_epi32(_mm512_set1_epi32(j), up);
    const __m512 dy = _mm512_sub_ps(_mm512_add_ps(_mm512_cvtepi32_ps(jv), half), ry);
    __m512 base[4];
    // The row's planes broadcast from memory here (hoisted, twelve vectors were spilled to the stack).
    for (int k = 0; k < 4; ++k)
      base[k] = _mm512_add_ps(_mm512_set1_ps(pc[k]), _mm512_mul_ps(_mm512_set1_ps(py[k]), dy));
    const __m512 rowv = _mm512_cvtepi32_ps(_mm512_sub_epi32(_mm512_set1_epi32(row), up));
    __m512i edge[3] = {edge_row[0], edge_row[1], edge_row[2]};
    for (int x = x0; x < x1; x += 8) {
      const __m512i outside = _mm512_or_si512(_mm512_or_si512(edge[0], edge[1]), edge[2]);
      const __mmask16 cover = _mm512_mask_cmpge_epi32_mask(
          rows & _mm512_cmpgt_epi32_mask(_mm512_set1_epi32(x1 - x), col), outside, _mm512_setzero_si512());
      for (int k = 0; k < 3; ++k) edge[k] = _mm512_add_epi32(edge[k], edge_dx8[k]);
      if (!cover) continue;
      const __m512 fi = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(x), col));
      __m512 z = _mm512_fmadd_ps(zdy, rowv, _mm512_fmadd_ps(zdx, fi, za));
      z = _mm512_min_ps(_mm512_max_ps(z, zero), one);
      const __m512i d = _mm512_cvtps_epi32(_mm512_mul_ps(z, depth_scale));
      // As in gouraud_rect_avx2: whole loads and stores of the pixels this task owns (the second row's only when
      // there is one: drow[1] is drow[0] otherwise).
      const bool whole = write_depth && x + 8 <= x_owned;
      const __m256i stored0 = whole ? _mm256_loadu_si256(reinterpret_cast<const __m256i*>(drow[0] + x))
                                    : _mm256_maskz_loadu_epi32(__mmask8(cover), drow[0] + x);
      const __m256i stored1 = whole && two ? _mm256_loadu_si256(reinterpret_cast<const __m256i*>(drow[1] + x))
                                           : _mm256_maskz_loadu_epi32(__mmask8(cover >> 8), drow[1] + x);
      const __m512i stored = _mm512_inserti64x4(_mm512_castsi256_si512(stored0), stored1, 1);
      const __mmask16 pass = depth_passes16<F>(cover, d, stored);
      if (!pass) continue;
      const __m512 dx = _mm512_sub_ps(_mm512_add_ps(fi, half), rx);
      const __m512 w = _mm512_div_ps(one, _mm512_add_ps(base[0], _mm512_mul_ps(pxv[0], dx)));
      __m512i rgba = _mm512_set1_epi32(int32_t(0xff000000u));
      for (int k = 1; k < 4; ++k) {
        __m512 c = _mm512_mul_ps(_mm512_add_ps(base[k], _mm512_mul_ps(pxv[k], dx)), w);
        c = _mm512_min_ps(_mm512_max_ps(c, zero), one);
        c = _mm512_sub_ps(_mm512_add_ps(_mm512_mul_ps(c, c255), round_magic), round_magic);
        rgba = _mm512_or_si512(rgba, _mm512_slli_epi32(_mm512_cvttps_epi32(c), 8 * (k - 1)));
      }
      _mm256_mask_storeu_epi32(crow[0] + x, __mmask8(pass), _mm512_castsi512_si256(rgba));
      _mm256_mask_storeu_epi32(crow[1] + x, __mmask8(pass >> 8), _mm512_extracti64x4_epi64(rgba, 1));
      if (whole) {
        const __m512i blended = _mm512_mask_blend_epi32(pass, stored, d);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(drow[0] + x), _mm512_castsi512_si256(blended));
        if (two) _mm256_storeu_si256(reinterpret_cast<__m256i*>(drow[1] + x), _mm512_extracti64x4_epi64(blended, 1));
      } else if (write_depth) {
        _mm256_mask_storeu_epi32(drow[0] + x, __mmask8(pass), _mm512_castsi512_si256(d));
        _mm256_mask_storeu_epi32(drow[1] + x, __mmask8(pass >> 8), _mm512_extracti64x4_epi64(d, 1));
      }
    }
    for (int k = 0; k < 3; ++k) edge_row[k] = _mm512_add_epi32(edge_row[k], edge_dy2[k]);
  }
}

}  // namespace

template <DepthFunc F, bool WriteDepth>
void fill_span_avx512(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                      float zdy, float r, uint32_t c32) {
  fill_span_pixels<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
}

template <DepthFunc F>
void test_span_avx512(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                      uint32_t* __restrict d, bool* __restrict pass) {
  test_span_pixels<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
}

TESSERA_SPAN_INSTANTIATE(fill_span_avx512, test_span_avx512)

namespace {
struct Avx512 {
  template <DepthFunc F, bool WriteDepth>
  static constexpr FillSpan* fill = fill_span_avx512<F, WriteDepth>;
  template <DepthFunc F>
  static constexpr TestSpan* test = test_span_avx512<F>;
  template <DepthFunc F>
  static constexpr GouraudRect* gouraud = gouraud_rect_avx512<F>;
};
}  // namespace

constinit const SpanKernels kSpanKernelsAvx512 = span_kernel_table<Avx512>();

}  // namespace tessera::raster3d::detail
