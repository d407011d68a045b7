// The span kernels for AVX2 with FMA (compiled with -mavx2 -mfma -ffp-contract=off): eight floats per instruction
// instead of SSE2's four, and the Gouraud rectangles eight pixels at a time. Chosen by span_kernels() where the CPU
// has AVX2 and FMA (and no AVX-512).
#include <immintrin.h>

#include "span_kernels.hpp"

namespace tessera::raster3d::detail {
namespace {

/// A depth comparison of eight lanes (values below 2^24, so signed compares are exact): all ones where it passes.
template <DepthFunc F>
[[gnu::always_inline]] inline __m256i depth_passes8(__m256i d, __m256i s) {
  if constexpr (F == DepthFunc::never)
    return _mm256_setzero_si256();
  else if constexpr (F == DepthFunc::less)
    return _mm256_cmpgt_epi32(s, d);
  else if constexpr (F == DepthFunc::equal)
    return _mm256_cmpeq_epi32(d, s);
  else if constexpr (F == DepthFunc::lequal)
    return _mm256_xor_si256(_mm256_cmpgt_epi32(d, s), _mm256_set1_epi32(-1));
  else if constexpr (F == DepthFunc::greater)
    return _mm256_cmpgt_epi32(d, s);
  else if constexpr (F == DepthFunc::notequal)
    return _mm256_xor_si256(_mm256_cmpeq_epi32(d, s), _mm256_set1_epi32(-1));
  else if constexpr (F == DepthFunc::gequal)
    return _mm256_xor_si256(_mm256_cmpgt_epi32(s, d), _mm256_set1_epi32(-1));
  else
    return _mm256_set1_epi32(-1);
}

/// Rasterizes a Gouraud record (three color varyings, ColorFragmentShader) over the rectangle [x0, x1) x [y0, y1)
/// (GL pixels) eight pixels at a time: coverage from the edge functions in 32-bit lanes, depth as fragment_depth and
/// depth24, the early depth test, then the color planes with one division per eight pixels and to_color8's rounding.
/// The same IEEE operations in the same order as raster_tile's scalar loop, so the same pixels. The task owns the
/// pixels left of x_owned in these rows (its tile's): eight of them are rewritten whole, uncovered lanes unchanged.
template <DepthFunc F>
void gouraud_rect_avx2(const TriangleRecord& r, const float* planes, int x0, int x1, int y0, int y1, int x_owned,
                       Image<uint32_t>& depth, ImageRGBA8& color, bool write_depth) {
  const int height = depth.height();
  const float* pc = planes;
  const float* px = planes + 4;
  const float* py = planes + 8;
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  // Edge functions at the lanes of the first chunk of row y0, and their steps per row and per chunk.
  __m256i edge_row[3], edge_dy[3], edge_dx8[3];
  for (int k = 0; k < 3; ++k) {
    const Edge& e = r.edges[k];
    const auto e0 = int32_t(int64_t(e.a) * 256 * x0 + int64_t(e.b) * 256 * y0 + e.c);
    edge_row[k] = _mm256_add_epi32(_mm256_set1_epi32(e0), _mm256_mullo_epi32(lane, _mm256_set1_epi32(e.a * 256)));
    edge_dy[k] = _mm256_set1_epi32(e.b * 256);
    edge_dx8[k] = _mm256_set1_epi32(e.a * 256 * 8);
  }
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
  const __m256 rx = _mm256_set1_ps(r.rx), zdx = _mm256_set1_ps(r.zdx), zdy = _mm256_set1_ps(r.zdy);
  const __m256 za = _mm256_set1_ps(r.za), depth_scale = _mm256_set1_ps(float(kDepthMax));
  const __m256 c255 = _mm256_set1_ps(255.0f), round_magic = _mm256_set1_ps(12582912.0f);
  const __m256i alpha = _mm256_set1_epi32(int32_t(0xff000000u));
  __m256 pxv[4];
  for (int k = 0; k < 4; ++k) pxv[k] = _mm256_set1_ps(px[k]);
  for (int j = y0; j < y1; ++j) {
    const int row = height - 1 - j;
    uint32_t* drow = depth.row(row);
    int32_t* crow = reinterpret_cast<int32_t*>(color.row(row));
    const float dy = float(j) + 0.5f - r.ry;
    __m256 base[4];
    for (int k = 0; k < 4; ++k) base[k] = _mm256_set1_ps(pc[k] + py[k] * dy);
    const __m256 rowv = _mm256_set1_ps(float(row));
    __m256i edge[3] = {edge_row[0], edge_row[1], edge_row[2]};
    for (int x = x0; x < x1; x += 8) {
      // E >= 0 for the three edges: the sign bits of their OR are clear.
      const __m256i outside = _mm256_or_si256(_mm256_or_si256(edge[0], edge[1]), edge[2]);
      const __m256i cover =
          _mm256_andnot_si256(_mm256_srai_epi32(outside, 31), _mm256_cmpgt_epi32(_mm256_set1_epi32(x1 - x), lane));
      for (int k = 0; k < 3; ++k) edge[k] = _mm256_add_epi32(edge[k], edge_dx8[k]);
      if (_mm256_testz_si256(cover, cover)) continue;
      const __m256 fi = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(x), lane));
      __m256 z = _mm256_fmadd_ps(zdy, rowv, _mm256_fmadd_ps(zdx, fi, za));
      z = _mm256_min_ps(_mm256_max_ps(z, zero), one);
      const __m256i d = _mm256_cvtps_epi32(_mm256_mul_ps(z, depth_scale));
      // Eight pixels this task owns: whole loads and a blended whole store, which the next triangle's load of the
      // same pixels can take from the store buffer (a masked store does not forward: the load waited for it).
      const bool whole = write_depth && x + 8 <= x_owned;
      const __m256i stored = whole ? _mm256_loadu_si256(reinterpret_cast<const __m256i*>(drow + x))
                                   : _mm256_maskload_epi32(reinterpret_cast<const int*>(drow + x), cover);
      const __m256i pass = _mm256_and_si256(cover, depth_passes8<F>(d, stored));
      if (_mm256_testz_si256(pass, pass)) continue;
      const __m256 dx = _mm256_sub_ps(_mm256_add_ps(fi, half), rx);
      const __m256 w = _mm256_div_ps(one, _mm256_add_ps(base[0], _mm256_mul_ps(pxv[0], dx)));
      __m256i rgba = alpha;
      for (int k = 1; k < 4; ++k) {
        __m256 c = _mm256_mul_ps(_mm256_add_ps(base[k], _mm256_mul_ps(pxv[k], dx)), w);
        c = _mm256_min_ps(_mm256_max_ps(c, zero), one);
        c = _mm256_sub_ps(_mm256_add_ps(_mm256_mul_ps(c, c255), round_magic), round_magic);
        rgba = _mm256_or_si256(rgba, _mm256_slli_epi32(_mm256_cvttps_epi32(c), 8 * (k - 1)));
      }
      _mm256_maskstore_epi32(crow + x, pass, rgba);
      if (whole)
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(drow + x), _mm256_blendv_epi8(stored, d, pass));
      else if (write_depth)
        _mm256_maskstore_epi32(reinterpret_cast<int*>(drow + x), pass, d);
    }
    for (int k = 0; k < 3; ++k) edge_row[k] = _mm256_add_epi32(edge_row[k], edge_dy[k]);
  }
}

}  // namespace

template <DepthFunc F, bool WriteDepth>
void fill_span_avx2(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                    float zdy, float r, uint32_t c32) {
  fill_span_pixels<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
}

template <DepthFunc F>
void test_span_avx2(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                    uint32_t* __restrict d, bool* __restrict pass) {
  test_span_pixels<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
}

TESSERA_SPAN_INSTANTIATE(fill_span_avx2, test_span_avx2)

namespace {
struct Avx2 {
  template <DepthFunc F, bool WriteDepth>
  static constexpr FillSpan* fill = fill_span_avx2<F, WriteDepth>;
  template <DepthFunc F>
  static constexpr TestSpan* test = test_span_avx2<F>;
  template <DepthFunc F>
  static constexpr GouraudRect* gouraud = gouraud_rect_avx2<F>;
};
}  // namespace

constinit const SpanKernels kSpanKernelsAvx2 = span_kernel_table<Avx2>();

}  // namespace tessera::raster3d::detail
