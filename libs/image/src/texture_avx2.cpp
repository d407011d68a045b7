// Texture2D::sample_lanes for 8-bit textures, eight points at a time with AVX2 gathers (CMakeLists.txt gives this
// file -mavx2 -mfma; texture.cpp calls it only where the CPU has them). The same filters as texture.cpp's, in float.
#include <immintrin.h>

#include <algorithm>

#include "texture_lanes.hpp"

namespace tessera {
namespace {

/// The texel indices x0 and x1 = x0 + 1 along one axis of n texels, wrapped by repeat or clamp, for eight lanes of
/// floors f. No division: a power-of-two size wraps by a mask, any other by a multiply with 1 / n and one correction.
inline void wrap8(__m256 f, int n, Wrap wrap, __m256i& x0, __m256i& x1) {
  const __m256i size = _mm256_set1_epi32(n), one = _mm256_set1_epi32(1);
  // Beyond 2^24 a float has no fraction left (nor a meaningful texel): the bound keeps the conversion in int32.
  const __m256 limit = _mm256_set1_ps(16777216.0f);
  f = _mm256_min_ps(_mm256_max_ps(f, _mm256_sub_ps(_mm256_setzero_ps(), limit)), limit);
  if (wrap == Wrap::repeat) {
    __m256i x;
    if ((n & (n - 1)) == 0) {
      x = _mm256_and_si256(_mm256_cvttps_epi32(f), _mm256_set1_epi32(n - 1));
    } else {
      const __m256 q = _mm256_floor_ps(_mm256_mul_ps(f, _mm256_set1_ps(1.0f / float(n))));
      x = _mm256_cvttps_epi32(_mm256_sub_ps(f, _mm256_mul_ps(q, _mm256_set1_ps(float(n)))));
      // The reciprocal's rounding can leave x one period off: bring it into [0, n).
      x = _mm256_add_epi32(x, _mm256_and_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), x), size));
      x = _mm256_sub_epi32(x, _mm256_andnot_si256(_mm256_cmpgt_epi32(size, x), size));
    }
    x0 = x;
    x1 = _mm256_add_epi32(x, one);
    x1 = _mm256_andnot_si256(_mm256_cmpeq_epi32(x1, size), x1);  // n wraps to 0
    return;
  }
  const __m256i x = _mm256_cvttps_epi32(f), last = _mm256_set1_epi32(n - 1), zero = _mm256_setzero_si256();
  x0 = _mm256_min_epi32(_mm256_max_epi32(x, zero), last);
  x1 = _mm256_min_epi32(_mm256_max_epi32(_mm256_add_epi32(x, one), zero), last);
}

/// Channel c of eight RGBA8 texels, as floats 0 to 255.
inline __m256 channel8(__m256i texels, int c) {
  return _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(texels, 8 * c), _mm256_set1_epi32(0xff)));
}

/// a + (b - a) t: glm::mix up to rounding.
inline __m256 mix8(__m256 a, __m256 b, __m256 t) { return _mm256_fmadd_ps(_mm256_sub_ps(b, a), t, a); }

/// The notes' bilinear filter (Texture2D::bilinear) of eight lanes on one RGBA8 level, in float, scaled by 255 (the
/// caller divides once): the four texels gathered at once.
inline void bilinear8(const ImageRGBA8& level, const Sampler& sampler, __m256 u, __m256 v, __m256 out[4]) {
  const int w = level.width(), h = level.height();
  const __m256 x = _mm256_fmsub_ps(u, _mm256_set1_ps(float(w)), _mm256_set1_ps(0.5f));
  const __m256 y = _mm256_fmsub_ps(v, _mm256_set1_ps(float(h)), _mm256_set1_ps(0.5f));
  const __m256 fx = _mm256_floor_ps(x), fy = _mm256_floor_ps(y);
  const __m256 a = _mm256_sub_ps(x, fx), b = _mm256_sub_ps(y, fy);
  __m256i x0, x1, y0, y1;
  wrap8(fx, w, sampler.wrap_u, x0, x1);
  wrap8(fy, h, sampler.wrap_v, y0, y1);
  // Texel rows count from the bottom: row h - 1 - y of the image.
  const __m256i top_row = _mm256_set1_epi32(h - 1), width = _mm256_set1_epi32(w);
  const __m256i lower = _mm256_mullo_epi32(_mm256_sub_epi32(top_row, y0), width);
  const __m256i upper = _mm256_mullo_epi32(_mm256_sub_epi32(top_row, y1), width);
  const int* texels = reinterpret_cast<const int*>(level.row(0));
  const __m256i t00 = _mm256_i32gather_epi32(texels, _mm256_add_epi32(lower, x0), 4);
  const __m256i t10 = _mm256_i32gather_epi32(texels, _mm256_add_epi32(lower, x1), 4);
  const __m256i t01 = _mm256_i32gather_epi32(texels, _mm256_add_epi32(upper, x0), 4);
  const __m256i t11 = _mm256_i32gather_epi32(texels, _mm256_add_epi32(upper, x1), 4);
  for (int c = 0; c < 4; ++c) {
    const __m256 bottom = mix8(channel8(t00, c), channel8(t10, c), a);
    const __m256 top = mix8(channel8(t01, c), channel8(t11, c), a);
    out[c] = mix8(bottom, top, b);
  }
}

}  // namespace

void sample_lanes_avx2(const Texture2D& t, const float* u, const float* v, const float* lod, float* const out[4],
                       int n) {
  const Sampler& sampler = t.sampler();
  const int last = t.levels() - 1;
  for (int l = 0; l < n; l += 8) {
    const __m256 lu = _mm256_loadu_ps(u + l), lv = _mm256_loadu_ps(v + l);
    __m256 result[4];
    if (sampler.filter == Filter::bilinear) {
      bilinear8(t.level_rgba8(0), sampler, lu, lv, result);
    } else {
      // The lanes' levels (a quad's are equal): each distinct lower level once over all eight lanes, kept where it is
      // the lane's, blended with the next level where the lane's lod has a fraction.
      // In vectors (eight scalar stores read back as one vector would stall the load).
      const __m256 clamped = _mm256_min_ps(_mm256_max_ps(_mm256_loadu_ps(lod + l), _mm256_setzero_ps()),
                                           _mm256_set1_ps(float(last)));  // NaN -> 0
      const __m256i lanes_level = _mm256_cvttps_epi32(clamped);
      const __m256 weights = _mm256_sub_ps(clamped, _mm256_cvtepi32_ps(lanes_level));
      alignas(32) int lower[8];
      _mm256_store_si256(reinterpret_cast<__m256i*>(lower), lanes_level);
      for (int k = 0; k < 8; ++k) {
        if (k > 0 && std::find(lower, lower + k, lower[k]) != lower + k) continue;  // done with an earlier lane
        __m256 near[4], far[4];
        bilinear8(t.level_rgba8(lower[k]), sampler, lu, lv, near);
        const bool blends = lower[k] < last;
        if (blends) bilinear8(t.level_rgba8(lower[k] + 1), sampler, lu, lv, far);
        const __m256 mine = _mm256_castsi256_ps(_mm256_cmpeq_epi32(lanes_level, _mm256_set1_epi32(lower[k])));
        for (int c = 0; c < 4; ++c) {
          const __m256 value = blends ? mix8(near[c], far[c], weights) : near[c];
          result[c] = k == 0 ? value : _mm256_blendv_ps(result[c], value, mine);
        }
      }
    }
    const __m256 scale = _mm256_set1_ps(1.0f / 255.0f);
    for (int c = 0; c < 4; ++c) _mm256_storeu_ps(out[c] + l, _mm256_mul_ps(result[c], scale));
  }
}

}  // namespace tessera
