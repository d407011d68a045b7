#pragma once
// The ray caster's prepared data, shared by the scalar caster (volume_render.cpp) and the AVX2 marcher
// (volume_render_avx2.cpp, compiled with -mavx2 -mfma): the packed volume, the tabulated transfer function, the
// empty-block grid, the specular power, a ray's samples and the scalar march(). Private to libs/volume.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "tessera/core/memory.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/volume/volume_render.hpp"

namespace tessera::volume_render_detail {

using Corner = std::array<int16_t, 4>;  // quantized value, gradient x, y, z

/// Rounds to the nearest int16 (halves away from zero), saturating; NaN gives 0: no value reaching here converts
/// to an integer out of range or from a non-finite float (undefined behaviour).
inline int16_t quantize(double x) {
  if (!(x > -32768.5)) return x < 0 ? INT16_MIN : 0;
  if (!(x < 32767.5)) return INT16_MAX;
  return int16_t(int(x + (x >= 0 ? 0.5 : -0.5)));
}

/// The volume as the ray caster reads it: per voxel the value and the central-difference gradient (world units),
/// each quantized to 16 bits and interleaved, so that one 8-byte load per cell corner gives everything a shaded
/// sample needs (VTK's fixed-point mapper also works on 16-bit values with precomputed gradients). Built once per
/// VolumeRenderer instead of six extra trilinear samples per step.
///
/// The scales are in double: a float range below ~2e-34 makes 65535 / (hi - lo) overflow a float, and one beyond
/// float's limit (values of both signs near 3e38) makes hi - lo overflow; in double both are finite for any two
/// finite floats, so a tiny range spans the 65536 levels as a unit range does, and a huge one is not flattened.
struct PackedVolume {
  glm::ivec3 dims;
  size_t stride_y, stride_z;
  double value_scale;     ///< quantized = (v - lo) * value_scale - 32768
  double gradient_scale;  ///< quantized = g * gradient_scale (g in world units)
  RawVector<Corner> voxels;

  PackedVolume(const Volume<float>& v, double lo, double hi)
      : dims(v.dims()), stride_y(size_t(dims.x)), stride_z(size_t(dims.x) * size_t(dims.y)) {
    value_scale = hi > lo ? 65535.0 / (hi - lo) : 0.0;
    // No gradient component exceeds (hi - lo) / (smallest spacing) (a one-sided difference across the whole range):
    // that bound sets the gradient's scale, so no pass is spent finding the actual largest one. The differences are
    // multiplied by smallest spacing / (n spacing) (at most 1) and 32767 / (hi - lo): no product overflows, even
    // where the gradient itself would (huge values over tiny spacings).
    const Vec3 sp = v.spacing();
    const double min_spacing = std::min({sp.x, sp.y, sp.z});
    const double per_range = hi > lo ? 32767.0 / (hi - lo) : 0.0;
    gradient_scale = per_range * min_spacing;
    // 8 bytes a voxel beside the float volume's 4: checked against the memory budget before it is allocated.
    MemoryBudget::check(saturating_product({uint64_t(v.voxel_count()), sizeof(Corner)}),
                        fmt::format("volume render: values and gradients of {}x{}x{} voxels", dims.x, dims.y, dims.z));
    voxels.resize(v.voxel_count());
    // Per axis: the factor of a difference over n voxels is per_range * min_spacing / (n spacing).
    const Vec3 unit = per_range * (min_spacing / sp);
    parallel_for(0, dims.z, 1, [&](int64_t z0, int64_t z1) {
      for (int z = int(z0); z < int(z1); ++z)
        for (int y = 0; y < dims.y; ++y) pack_row(v, y, z, unit, lo, &voxels[v.index(0, y, z)]);
    });
  }

  /// Packs row (y, z): value and Volume::gradient (central differences, one-sided on the border) quantized, in one
  /// pass without Volume::gradient's per-voxel clamps (only the row's two ends are border voxels along x). `unit`
  /// is the quantized gradient of a difference of 1 across one voxel, per axis.
  void pack_row(const Volume<float>& v, int y, int z, const Vec3& unit, double lo, Corner* out) const {
    const glm::ivec3 d = v.dims();
    const float* row = &v(0, y, z);
    const int y0 = std::max(y - 1, 0), y1 = std::min(y + 1, d.y - 1), z0 = std::max(z - 1, 0),
              z1 = std::min(z + 1, d.z - 1);
    const float* ylo = &v(0, y0, z);
    const float* yhi = &v(0, y1, z);
    const float* zlo = &v(0, y, z0);
    const float* zhi = &v(0, y, z1);
    const double sy = y1 > y0 ? unit.y / (y1 - y0) : 0.0, sz = z1 > z0 ? unit.z / (z1 - z0) : 0.0;
    const auto pack = [&](int x, int x0, int x1, double sx) {
      const double level = (double(row[x]) - lo) * value_scale;  // in [0, 65535] for values in [lo, hi]
      out[x] = {int16_t(int(level >= 0 ? std::min(level, 65535.0) + 0.5 : 0.0) - 32768),
                quantize((double(row[x1]) - row[x0]) * sx), quantize((double(yhi[x]) - ylo[x]) * sy),
                quantize((double(zhi[x]) - zlo[x]) * sz)};
    };
    const auto border = [&](int x) {
      const int x0 = std::max(x - 1, 0), x1 = std::min(x + 1, d.x - 1);
      pack(x, x0, x1, x1 > x0 ? unit.x / (x1 - x0) : 0.0);
    };
    border(0);
    const double sx = unit.x / 2;
    for (int x = 1; x + 1 < d.x; ++x) pack(x, x - 1, x + 1, sx);
    if (d.x > 1) border(d.x - 1);
  }

  /// The cell holding voxel coordinates p (clamped to the grid; its lower corner) and p's offset in it.
  glm::ivec3 locate(const Vec3f& p, Vec3f& offset) const {
    const Vec3f q = glm::clamp(p, Vec3f(0.0f), Vec3f(dims - 1));
    const glm::ivec3 cell = glm::min(glm::ivec3(q), glm::max(dims - 2, 0));
    offset = q - Vec3f(cell);
    return cell;
  }
  /// Memory offsets of a cell's corners from its lower corner (0 along an axis of one voxel).
  glm::ivec3 corner_steps() const {
    return {dims.x > 1 ? 1 : 0, dims.y > 1 ? int(stride_y) : 0, dims.z > 1 ? int(stride_z) : 0};
  }

  /// Trilinear (value, gradient) in quantized units at `offset` in `cell`.
  Vec4f interpolate(const glm::ivec3& cell, const Vec3f& offset) const {
    const glm::ivec3 st = corner_steps();
    const size_t dx = size_t(st.x), dy = size_t(st.y), dz = size_t(st.z);
    const Corner* c = voxels.data() + size_t(cell.x) + stride_y * size_t(cell.y) + stride_z * size_t(cell.z);
#if defined(__SSE2__)
    // Four components at once: sign-extend the four int16 of a corner to floats, then seven lerps.
    const auto load = [](const Corner& a) {
      const __m128i x = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(a.data()));
      return _mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(x, x), 16));
    };
    const auto lerp = [](__m128 a, __m128 b, __m128 t) { return _mm_add_ps(a, _mm_mul_ps(t, _mm_sub_ps(b, a))); };
    const __m128 tx = _mm_set1_ps(offset.x), ty = _mm_set1_ps(offset.y), tz = _mm_set1_ps(offset.z);
    const __m128 c00 = lerp(load(c[0]), load(c[dx]), tx), c10 = lerp(load(c[dy]), load(c[dy + dx]), tx);
    const __m128 c01 = lerp(load(c[dz]), load(c[dz + dx]), tx), c11 = lerp(load(c[dz + dy]), load(c[dz + dy + dx]), tx);
    alignas(16) float out[4];
    _mm_store_ps(out, lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz));
    return Vec4f(out[0], out[1], out[2], out[3]);
#else
    const auto load = [](const Corner& a) { return Vec4f(a[0], a[1], a[2], a[3]); };
    const auto lerp = [](const Vec4f& a, const Vec4f& b, float t) { return a + t * (b - a); };
    const Vec4f c00 = lerp(load(c[0]), load(c[dx]), offset.x), c10 = lerp(load(c[dy]), load(c[dy + dx]), offset.x);
    const Vec4f c01 = lerp(load(c[dz]), load(c[dz + dx]), offset.x);
    const Vec4f c11 = lerp(load(c[dz + dy]), load(c[dz + dy + dx]), offset.x);
    return lerp(lerp(c00, c10, offset.y), lerp(c01, c11, offset.y), offset.z);
#endif
  }
};

/// The transfer function tabulated over the value range (16384 entries, the nearest one is used: 256 KiB, which
/// stays in the L2 cache, where a table per quantized value missed it), with each entry's opacity already corrected
/// to the step (alpha = 1 - (1 - opacity)^step): a sample costs one lookup instead of a search and a pow.
struct TransferTable {
  static constexpr int kSize = 16384;
  static constexpr float kScale = float(kSize - 1) / 65535.0f;  ///< entry = (quantized + 32768) * kScale, rounded
  std::vector<Vec4f> entries;                                   ///< rgb, alpha per step
  std::vector<int> lit_before;  ///< entries with a non-zero alpha before entry i (for any_lit)

  TransferTable(const TransferFunction& tf, double lo, double hi, float step)
      : entries(kSize), lit_before(kSize + 1, 0) {
    // In double: hi - lo of two finite floats can overflow a float; each entry's value lies in [lo, hi].
    const double span = hi > lo ? hi - lo : 0.0;
    for (int i = 0; i < kSize; ++i) {
      const Vec4f c = tf(float(lo + span * i / (kSize - 1)));
      // 1 - (1 - a)^step in double, as -expm1(step log1p(-a)): in float, 1 - pow rounds to 0 for small steps and
      // the volume would vanish.
      const double alpha = c.w >= 1 ? 1.0 : -std::expm1(double(step) * std::log1p(-double(c.w)));
      entries[size_t(i)] = Vec4f(Vec3f(c), float(alpha));
      lit_before[size_t(i) + 1] = lit_before[size_t(i)] + (entries[size_t(i)].w > 0);
    }
  }
  /// The entry of an interpolated quantized value (in [-32768, 32767]).
  static int index(float quantized) { return std::clamp(int((quantized + 32768.0f) * kScale + 0.5f), 0, kSize - 1); }
  const Vec4f& operator()(float quantized) const { return entries[size_t(index(quantized))]; }
  /// Whether some value in quantized [lo, hi] has a non-zero alpha (interpolated values stay in that range).
  bool any_lit(int lo, int hi) const {
    return lit_before[size_t(index(float(hi))) + 1] > lit_before[size_t(index(float(lo)))];
  }
};

/// Empty flags per block of `block` cells per side: a block is empty when every table entry its voxels' quantized
/// range can reach has zero alpha, so skipping its samples leaves the image unchanged.
struct BlockGrid {
  int size;
  glm::ivec3 count;
  std::vector<int32_t> empty;                   ///< int32 so that 8 lanes can gather them
  std::array<std::vector<int32_t>, 3> of_cell;  ///< block coordinate of each cell coordinate, per axis

  BlockGrid(const PackedVolume& v, int block, const TransferTable& table) : size(block) {
    const glm::ivec3 d = v.dims;
    count = glm::max((d - 1 + block - 1) / block, glm::ivec3(1));
    empty.resize(size_t(count.x) * size_t(count.y) * size_t(count.z));
    parallel_for(0, count.z, 1, [&](int64_t b0, int64_t b1) {
      for (int bz = int(b0); bz < int(b1); ++bz)
        for (int by = 0; by < count.y; ++by)
          for (int bx = 0; bx < count.x; ++bx) {
            int lo = INT16_MAX, hi = INT16_MIN;
            for (int z = bz * block; z <= std::min((bz + 1) * block, d.z - 1); ++z)
              for (int y = by * block; y <= std::min((by + 1) * block, d.y - 1); ++y)
                for (int x = bx * block; x <= std::min((bx + 1) * block, d.x - 1); ++x) {
                  const int q = v.voxels[size_t(x) + v.stride_y * size_t(y) + v.stride_z * size_t(z)][0];
                  lo = std::min(lo, q);
                  hi = std::max(hi, q);
                }
            empty[index(glm::ivec3(bx, by, bz))] = !table.any_lit(lo, hi);
          }
    });
    for (int axis = 0; axis < 3; ++axis) {
      of_cell[size_t(axis)].resize(size_t(std::max(d[axis] - 1, 1)));
      for (int c = 0; c < int(of_cell[size_t(axis)].size()); ++c)
        of_cell[size_t(axis)][size_t(c)] = std::min(c / size, count[axis] - 1);
    }
  }
  size_t index(const glm::ivec3& b) const {
    return size_t(b.x) + size_t(count.x) * (size_t(b.y) + size_t(count.y) * size_t(b.z));
  }
  /// The block of a cell (a table per axis: a division per axis and sample showed in the profile).
  glm::ivec3 block_of(const glm::ivec3& cell) const {
    return {of_cell[0][size_t(cell.x)], of_cell[1][size_t(cell.y)], of_cell[2][size_t(cell.z)]};
  }
  /// The sample parameter (in steps from `first`) where a ray first + s * delta leaves block b.
  float exit(const glm::ivec3& b, const Vec3f& first, const Vec3f& delta) const {
    float s = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
      if (delta[axis] > 0) s = std::min(s, (float((b[axis] + 1) * size) - first[axis]) / delta[axis]);
      if (delta[axis] < 0) s = std::min(s, (float(b[axis] * size) - first[axis]) / delta[axis]);
    }
    return s;
  }
};

/// c^shininess for c in [0, 1]: by repeated squaring when the exponent is a whole number up to 1024 (the usual
/// case), else from a table (the specular term is a pow per sample otherwise).
struct SpecularPower {
  static constexpr int kSize = 1024;
  int whole = 0;  ///< the exponent when it is a whole number in [1, 1024], else 0
  std::array<float, kSize + 1> values;
  explicit SpecularPower(float exponent) {
    if (exponent >= 1 && exponent <= 1024 && exponent == std::floor(exponent)) whole = int(exponent);
    for (int i = 0; i <= kSize; ++i) values[size_t(i)] = std::pow(float(i) / kSize, exponent);
  }
  float operator()(float c) const {
    c = std::clamp(c, 0.0f, 1.0f);
    if (whole) {
      float result = 1, base = c;
      for (int e = whole; e; e >>= 1, base *= base)
        if (e & 1) result *= base;
      return result;
    }
    const float s = c * kSize;
    const int i = std::min(int(s), kSize - 1);
    return values[size_t(i)] + (s - float(i)) * (values[size_t(i) + 1] - values[size_t(i)]);
  }
};

/// One ray's samples in voxel space: sample k < n is at first + k * delta, except that when the last segment is
/// shorter than a step (last_fraction < 1) the last sample is at the middle of that segment, `last_point`.
struct RaySamples {
  Vec3f first{0.0f}, delta{0.0f}, light{0.0f}, last_point{0.0f};
  int n = 0;
  float last_fraction = 0;  ///< the last segment's length in steps, in [0, 1]
  bool short_last() const { return last_fraction < 1; }
  /// Samples that are a whole step apart (the SIMD path marches these; the scalar one finishes the ray).
  int regular() const { return short_last() ? n - 1 : n; }
};

/// What every ray reads; march() is the scalar ray caster, march8 (AVX2) its eight-ray version.
struct Caster {
  const PackedVolume& volume;
  const TransferTable& table;
  const BlockGrid& blocks;
  const SpecularPower& power;
  const VolumeRenderOptions& options;
  float step;
  float min_gradient2;  ///< a gradient shorter than this (squared, quantized units) leaves the sample unshaded

  /// Composites samples k, k + 1, ... of `ray` onto (color, alpha) until the ray ends or is opaque.
  void march(const RaySamples& ray, int k, Vec3f& color, float& alpha) const {
    for (; k < ray.n && alpha < options.termination; ++k) {
      const bool last = k == ray.n - 1 && ray.short_last();
      const Vec3f p = last ? ray.last_point : ray.first + float(k) * ray.delta;
      Vec3f offset;
      const glm::ivec3 cell = volume.locate(p, offset);
      const glm::ivec3 b = blocks.block_of(cell);
      if (blocks.empty[blocks.index(b)]) {
        // Jump to the sample before the one where the ray leaves the block (the samples skipped are at least a
        // step inside it, so rounding cannot skip a sample of another block).
        const float exit = blocks.exit(b, ray.first, ray.delta);
        k = exit < float(ray.n) ? std::max(k, int(exit) - 1) : ray.n;
        continue;
      }
      // No branch on a clear sample (alpha 0 adds nothing): in noisy data its outcome is a coin toss.
      const Vec4f s = volume.interpolate(cell, offset);
      Vec4f c = table(s.x);
      // An empty last segment (last_fraction 0) adds nothing, even where the entry is opaque (0 * -inf).
      if (last)
        c.w = ray.last_fraction > 0 ? float(-std::expm1(double(ray.last_fraction) * std::log1p(-double(c.w)))) : 0.0f;
      Vec3f rgb(c);
      if (options.shading) {
        const Vec3f g(s.y, s.z, s.w);
        const float len2 = glm::dot(g, g);
        const bool lit = len2 > min_gradient2;
        const float cosine = std::abs(glm::dot(g, ray.light)) / std::sqrt(lit ? len2 : 1.0f);  // Blinn: h = l
        const float shade = lit ? options.ambient + options.diffuse * cosine : 1.0f;
        const float highlight = lit ? options.specular * power(cosine) : 0.0f;
        rgb = rgb * shade + Vec3f(highlight);
      }
      color += (1 - alpha) * c.w * rgb;
      alpha += (1 - alpha) * c.w;
    }
  }
};

#if defined(__x86_64__) || defined(__i386__)
#define TESSERA_VOLUME_AVX2 1
/// march() for up to 8 rays at once (AVX2 + FMA): each lane keeps its own sample index, so empty-block jumps and
/// early termination stay per ray; the lanes' cell corners, table entries and block flags are gathered. Marches
/// the regular samples only, each lane from its k[] on entry, and returns each lane's next sample in k[]; the caller
/// finishes every ray with march()
/// (the shorter last segment). The same samples, skips and arithmetic as march(), up to rounding (FMA). Only for a
/// CPU with AVX2 and FMA (cpu_features()), voxel indices below 2^31 and dims below 2^23.
void march8(const Caster& cast, const RaySamples* rays, int count, Vec3f* color, float* alpha, int* k_out);
#endif

}  // namespace tessera::volume_render_detail
