// The ray caster's eight-ray marcher, compiled with -mavx2 -mfma (libs/volume/CMakeLists.txt); called only where
// cpu_features() has both. Of the shared headers' inline functions it uses only one-line accessors (glm's, and
// RaySamples::regular, PackedVolume::corner_steps), which are inlined, as in libs/accel and libs/fractal: no
// out-of-line AVX2 copy of them is left for the linker to pick.
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

#include "volume_render_internal.hpp"

namespace tessera::volume_render_detail {

namespace {

inline __m256 lerp(__m256 a, __m256 b, __m256 t) { return _mm256_fmadd_ps(t, _mm256_sub_ps(b, a), a); }
/// The low and high int16 of each int32, as floats.
inline __m256 low16(__m256i x) { return _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(x, 16), 16)); }
inline __m256 high16(__m256i x) { return _mm256_cvtepi32_ps(_mm256_srai_epi32(x, 16)); }

}  // namespace

void march8(const Caster& cast, const RaySamples* rays, int count, Vec3f* color, float* alpha, int* k_out) {
  alignas(32) float f[3][8] = {}, d[3][8] = {}, l[3][8] = {};
  alignas(32) int n[8] = {}, regular[8] = {};
  for (int i = 0; i < count; ++i) {
    for (int a = 0; a < 3; ++a) {
      f[a][i] = rays[i].first[a];
      d[a][i] = rays[i].delta[a];
      l[a][i] = rays[i].light[a];
    }
    n[i] = rays[i].n;
    regular[i] = rays[i].regular();
  }
  const PackedVolume& vol = cast.volume;
  const BlockGrid& blocks = cast.blocks;
  const VolumeRenderOptions& o = cast.options;
  __m256 first[3], delta[3], light[3], hi[3], inv_delta[3], forward[3], moving[3];
  __m256i max_cell[3];
  for (int a = 0; a < 3; ++a) {
    first[a] = _mm256_load_ps(f[a]);
    delta[a] = _mm256_load_ps(d[a]);
    inv_delta[a] = _mm256_div_ps(_mm256_set1_ps(1.0f), delta[a]);
    forward[a] =
        _mm256_and_ps(_mm256_cmp_ps(delta[a], _mm256_setzero_ps(), _CMP_GT_OQ), _mm256_set1_ps(1.0f));  // 1 or 0
    moving[a] = _mm256_cmp_ps(delta[a], _mm256_setzero_ps(), _CMP_NEQ_OQ);
    light[a] = _mm256_load_ps(l[a]);
    hi[a] = _mm256_set1_ps(float(vol.dims[a] - 1));
    max_cell[a] = _mm256_set1_epi32(std::max(vol.dims[a] - 2, 0));
  }
  const __m256i n_all = _mm256_load_si256(reinterpret_cast<const __m256i*>(n));
  const __m256i n_regular = _mm256_load_si256(reinterpret_cast<const __m256i*>(regular));
  const __m256 nf = _mm256_cvtepi32_ps(n_all);
  const glm::ivec3 steps = vol.corner_steps();
  // Corner offsets in voxels (a corner is 64 bits: value and gradient x, gradient y and z).
  const int corner[8] = {0,       steps.x,           steps.y,           steps.y + steps.x,
                         steps.z, steps.z + steps.x, steps.z + steps.y, steps.z + steps.y + steps.x};
  const __m256i stride_y = _mm256_set1_epi32(int(vol.stride_y)), stride_z = _mm256_set1_epi32(int(vol.stride_z));
  const __m256i count_x = _mm256_set1_epi32(blocks.count.x), count_y = _mm256_set1_epi32(blocks.count.y);
  const __m256 block_size = _mm256_set1_ps(float(blocks.size)), inv_block = _mm256_set1_ps(1.0f / float(blocks.size));
  const __m256i last_block[3] = {_mm256_set1_epi32(blocks.count.x - 1), _mm256_set1_epi32(blocks.count.y - 1),
                                 _mm256_set1_epi32(blocks.count.z - 1)};
  // 64-bit gathers fill 4 lanes: gathering lanes (0, 1, 4, 5) and (2, 3, 6, 7) and interleaving the halves with
  // shufps gives the eight lanes in order.
  const __m256i halves = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
  const auto* voxels = reinterpret_cast<const long long*>(vol.voxels.data());
  const auto* table = reinterpret_cast<const long long*>(cast.table.entries.data());
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), termination = _mm256_set1_ps(o.termination);
  const __m256 infinity = _mm256_set1_ps(INFINITY);

  alignas(32) int k_in[8] = {};
  for (int i = 0; i < count; ++i) k_in[i] = k_out[i];  // a loop, not std::copy_n: no AVX2 template copy to share
  __m256i k = _mm256_load_si256(reinterpret_cast<const __m256i*>(k_in));
  __m256 red = zero, green = zero, blue = zero, a_acc = zero;
  // The sample index of a lane does not wait for its opacity (a lane past termination keeps stepping and adds
  // nothing), so that the next positions do not depend on the previous sample's gathers and shading: the loop's
  // critical path is then only the empty-block jump.
  for (;;) {
    const __m256i marching = _mm256_cmpgt_epi32(n_regular, k);
    const __m256i active =
        _mm256_and_si256(marching, _mm256_castps_si256(_mm256_cmp_ps(a_acc, termination, _CMP_LT_OQ)));
    if (_mm256_testz_si256(active, active)) break;
    const __m256 kf = _mm256_cvtepi32_ps(k);
    __m256i cell[3], block[3];
    __m256 offset[3];
    for (int a = 0; a < 3; ++a) {
      const __m256 q = _mm256_min_ps(_mm256_max_ps(_mm256_fmadd_ps(kf, delta[a], first[a]), zero), hi[a]);
      cell[a] = _mm256_min_epi32(_mm256_cvttps_epi32(q), max_cell[a]);
      offset[a] = _mm256_sub_ps(q, _mm256_cvtepi32_ps(cell[a]));
      // cell / size: (cell + 0.5) / size is at least 0.5 / size from a whole number, far more than the rounding
      // (cells < 2^23), so truncating it is exact.
      const __m256 quotient =
          _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(cell[a]), _mm256_set1_ps(0.5f)), inv_block);
      block[a] = _mm256_min_epi32(_mm256_cvttps_epi32(quotient), last_block[a]);
    }
    const __m256i block_index = _mm256_add_epi32(
        block[0], _mm256_mullo_epi32(count_x, _mm256_add_epi32(block[1], _mm256_mullo_epi32(count_y, block[2]))));
    const __m256i is_empty =
        _mm256_cmpgt_epi32(_mm256_i32gather_epi32(blocks.empty.data(), block_index, 4), _mm256_setzero_si256());
    // Branchless: whether some lane jumps is a coin toss in noisy data.
    const __m256i skip = _mm256_and_si256(is_empty, marching);
    __m256 exit = infinity;
    for (int a = 0; a < 3; ++a) {
      const __m256 b = _mm256_cvtepi32_ps(block[a]);
      const __m256 bound = _mm256_mul_ps(_mm256_add_ps(b, forward[a]), block_size);  // the far side of the block
      exit = _mm256_min_ps(
          exit, _mm256_blendv_ps(infinity, _mm256_mul_ps(_mm256_sub_ps(bound, first[a]), inv_delta[a]), moving[a]));
    }
    const __m256i inside = _mm256_castps_si256(_mm256_cmp_ps(exit, nf, _CMP_LT_OQ));
    // Where the exit is beyond the ray, cvtt would overflow: those lanes take n instead.
    const __m256i jump =
        _mm256_max_epi32(k, _mm256_sub_epi32(_mm256_cvttps_epi32(_mm256_min_ps(exit, nf)), _mm256_set1_epi32(1)));
    k = _mm256_blendv_epi8(k, _mm256_blendv_epi8(n_all, jump, inside), skip);
    const __m256i sample = _mm256_andnot_si256(is_empty, active);
    if (!_mm256_testz_si256(sample, sample)) {
      const __m256i base =
          _mm256_permutevar8x32_epi32(_mm256_add_epi32(_mm256_add_epi32(cell[0], _mm256_mullo_epi32(cell[1], stride_y)),
                                                       _mm256_mullo_epi32(cell[2], stride_z)),
                                      halves);
      const __m128i base_a = _mm256_castsi256_si128(base), base_b = _mm256_extracti128_si256(base, 1);
      __m256 x_lerped[4][4];  // [corner pair (y, z)][component]
      for (int pair = 0; pair < 4; ++pair) {
        __m256 c[2][4];
        for (int side = 0; side < 2; ++side) {
          const __m128i at = _mm_set1_epi32(corner[2 * pair + side]);
          const __m256i a = _mm256_i32gather_epi64(voxels, _mm_add_epi32(base_a, at), 8);
          const __m256i b = _mm256_i32gather_epi64(voxels, _mm_add_epi32(base_b, at), 8);
          const __m256i value_gx = _mm256_castps_si256(
              _mm256_shuffle_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _MM_SHUFFLE(2, 0, 2, 0)));
          const __m256i gy_gz = _mm256_castps_si256(
              _mm256_shuffle_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _MM_SHUFFLE(3, 1, 3, 1)));
          c[side][0] = low16(value_gx);
          c[side][1] = high16(value_gx);
          c[side][2] = low16(gy_gz);
          c[side][3] = high16(gy_gz);
        }
        for (int comp = 0; comp < 4; ++comp) x_lerped[pair][comp] = lerp(c[0][comp], c[1][comp], offset[0]);
      }
      __m256 s[4];
      for (int comp = 0; comp < 4; ++comp)
        s[comp] = lerp(lerp(x_lerped[0][comp], x_lerped[1][comp], offset[1]),
                       lerp(x_lerped[2][comp], x_lerped[3][comp], offset[1]), offset[2]);
      const __m256 position = _mm256_fmadd_ps(_mm256_add_ps(s[0], _mm256_set1_ps(32768.0f)),
                                              _mm256_set1_ps(TransferTable::kScale), _mm256_set1_ps(0.5f));
      // Entries are 16 bytes: (r, g) and (b, alpha) are 64-bit halves, gathered like the corners.
      const __m256i entry = _mm256_permutevar8x32_epi32(
          _mm256_slli_epi32(_mm256_min_epi32(_mm256_max_epi32(_mm256_cvttps_epi32(position), _mm256_setzero_si256()),
                                             _mm256_set1_epi32(TransferTable::kSize - 1)),
                            1),
          halves);
      const __m128i entry_a = _mm256_castsi256_si128(entry), entry_b = _mm256_extracti128_si256(entry, 1);
      const __m256 rg_a = _mm256_castsi256_ps(_mm256_i32gather_epi64(table, entry_a, 8));
      const __m256 rg_b = _mm256_castsi256_ps(_mm256_i32gather_epi64(table, entry_b, 8));
      const __m256 ba_a = _mm256_castsi256_ps(_mm256_i32gather_epi64(table + 1, entry_a, 8));
      const __m256 ba_b = _mm256_castsi256_ps(_mm256_i32gather_epi64(table + 1, entry_b, 8));
      __m256 r = _mm256_shuffle_ps(rg_a, rg_b, _MM_SHUFFLE(2, 0, 2, 0));
      __m256 g = _mm256_shuffle_ps(rg_a, rg_b, _MM_SHUFFLE(3, 1, 3, 1));
      __m256 b = _mm256_shuffle_ps(ba_a, ba_b, _MM_SHUFFLE(2, 0, 2, 0));
      const __m256 w =
          _mm256_and_ps(_mm256_shuffle_ps(ba_a, ba_b, _MM_SHUFFLE(3, 1, 3, 1)), _mm256_castsi256_ps(sample));
      if (o.shading) {
        const __m256 len2 = _mm256_fmadd_ps(s[1], s[1], _mm256_fmadd_ps(s[2], s[2], _mm256_mul_ps(s[3], s[3])));
        const __m256 lit = _mm256_cmp_ps(len2, _mm256_set1_ps(cast.min_gradient2), _CMP_GT_OQ);
        const __m256 dot =
            _mm256_fmadd_ps(s[1], light[0], _mm256_fmadd_ps(s[2], light[1], _mm256_mul_ps(s[3], light[2])));
        const __m256 abs_dot = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), dot);
        // 1 / |g| by rsqrt and one Newton step (relative error ~1e-7, shorter latency than sqrt and div).
        const __m256 len2_or_1 = _mm256_blendv_ps(one, len2, lit);
        const __m256 r0 = _mm256_rsqrt_ps(len2_or_1);
        const __m256 r1 = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.5f), r0),
                                        _mm256_fnmadd_ps(_mm256_mul_ps(len2_or_1, r0), r0, _mm256_set1_ps(3.0f)));
        const __m256 cosine = _mm256_mul_ps(abs_dot, r1);
        const __m256 clamped = _mm256_min_ps(_mm256_max_ps(cosine, zero), one);
        __m256 pw = one;
        if (cast.power.whole) {
          __m256 square = clamped;
          for (int e = cast.power.whole; e; e >>= 1, square = _mm256_mul_ps(square, square))
            if (e & 1) pw = _mm256_mul_ps(pw, square);
        } else {
          const __m256 ps = _mm256_mul_ps(clamped, _mm256_set1_ps(float(SpecularPower::kSize)));
          const __m256i pi = _mm256_min_epi32(_mm256_cvttps_epi32(ps), _mm256_set1_epi32(SpecularPower::kSize - 1));
          const __m256 p0 = _mm256_i32gather_ps(cast.power.values.data(), pi, 4);
          const __m256 p1 = _mm256_i32gather_ps(cast.power.values.data() + 1, pi, 4);
          pw = lerp(p0, p1, _mm256_sub_ps(ps, _mm256_cvtepi32_ps(pi)));
        }
        const __m256 shade =
            _mm256_blendv_ps(one, _mm256_fmadd_ps(_mm256_set1_ps(o.diffuse), cosine, _mm256_set1_ps(o.ambient)), lit);
        const __m256 highlight = _mm256_and_ps(_mm256_mul_ps(_mm256_set1_ps(o.specular), pw), lit);
        r = _mm256_fmadd_ps(r, shade, highlight);
        g = _mm256_fmadd_ps(g, shade, highlight);
        b = _mm256_fmadd_ps(b, shade, highlight);
      }
      const __m256 weight = _mm256_mul_ps(_mm256_sub_ps(one, a_acc), w);
      red = _mm256_fmadd_ps(weight, r, red);
      green = _mm256_fmadd_ps(weight, g, green);
      blue = _mm256_fmadd_ps(weight, b, blue);
      a_acc = _mm256_add_ps(a_acc, weight);
    }
    k = _mm256_sub_epi32(k, marching);  // marching lanes are all ones (-1): k + 1
  }
  alignas(32) float out[4][8];
  alignas(32) int ks[8];
  _mm256_store_ps(out[0], red);
  _mm256_store_ps(out[1], green);
  _mm256_store_ps(out[2], blue);
  _mm256_store_ps(out[3], a_acc);
  _mm256_store_si256(reinterpret_cast<__m256i*>(ks), k);
  for (int i = 0; i < count; ++i) {
    color[i] = {out[0][i], out[1][i], out[2][i]};
    alpha[i] = out[3][i];
    k_out[i] = ks[i];
  }
}

}  // namespace tessera::volume_render_detail
#endif
