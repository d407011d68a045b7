#pragma once
// The pipeline's implementation: the template parts (vertex stage, per-tile loops) live here so the shaders inline.
// What does not depend on the shaders is compiled in raster3d's sources: clipping, triangle setup and binning
// (src/pipeline_setup.cpp), the raster thread and pipeline_for (src/pipeline_schedule.cpp), and the span kernels of
// each instruction set (src/span_*.cpp), which the templates call through a table.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/raster3d/detail/pipeline_setup.hpp"
#include "tessera/raster3d/framebuffer.hpp"
#include "tessera/raster3d/shaders.hpp"

namespace tessera::raster3d::detail {

/// Runs the vertex shader on vertices [0, count) in parallel (pipeline_for) into the current draw input's vertices.
template <class VS>
const float* run_vertex_stage(RasterScratch& scratch, uint32_t count, const VS& vs) {
  using V = VaryingsOf<VS>;
  constexpr int n = varying_count<V>;
  static_assert(n <= kMaxVaryings, "too many varyings");
  constexpr int stride = 4 + n;
  std::vector<float>& vertices = scratch.inputs[size_t(scratch.input)].vertices;
  vertices.resize(size_t(count) * stride);
  float* out = vertices.data();
  pipeline_for(scratch, PipelineSide::caller, 0, count, 1024, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const auto v = vs(uint32_t(i));
      float* d = out + i * stride;
      const Vec4f p = v.position;
      d[0] = p.x, d[1] = p.y, d[2] = p.z, d[3] = p.w;
      if constexpr (n > 0) std::memcpy(d + 4, &v.varyings, sizeof(float) * n);
    }
  });
  return out;
}

/// A 32-bit word that may alias the 8-bit RGBA pixels (one store per pixel in the constant-color loop).
using AliasedU32 = uint32_t __attribute__((may_alias));

/// Whether a fragment of depth d passes against the stored depth s.
template <DepthFunc F>
inline bool depth_passes(uint32_t d, uint32_t s) {
  if constexpr (F == DepthFunc::never)
    return false;
  else if constexpr (F == DepthFunc::less)
    return d < s;
  else if constexpr (F == DepthFunc::equal)
    return d == s;
  else if constexpr (F == DepthFunc::lequal)
    return d <= s;
  else if constexpr (F == DepthFunc::greater)
    return d > s;
  else if constexpr (F == DepthFunc::notequal)
    return d != s;
  else if constexpr (F == DepthFunc::gequal)
    return d >= s;
  else
    return true;
}

/// The stencil test of `face` against the stored value s: (ref & mask) func (s & mask).
bool stencil_passes(const StencilFace& face, uint8_t s);
/// Applies `op` of `face` to the stored value s (through its write mask).
void stencil_apply(const StencilFace& face, StencilOp op, uint8_t& s);

/// The blend of fragment color `src` over the stored `dst` by `f` (BlendFunction).
glm::u8vec4 blend_colors(const BlendFunction& f, const Vec4f& src, glm::u8vec4 dst);

/// Writes fragment color c to the stored color, blended (params.blend) or stored. Callers skip it when
/// params.color_write is off (the color mask, or a depth_only framebuffer, which has no color to refer to).
inline void write_color(const SetupParams& params, const Vec4f& c, glm::u8vec4& stored) {
  stored = params.blend ? blend_colors(params.blend_function, c, stored) : to_color8(c);
}

/// The stencil test and the depth test outcome `depth_pass` of a fragment, with their stencil operations on s
/// (params.stencil_test on): whether the fragment goes on to the fragment shader.
inline bool stencil_and_depth(const StencilFace& face, bool depth_pass, uint8_t& s) {
  if (!stencil_passes(face, s)) {
    stencil_apply(face, face.fail, s);
    return false;
  }
  stencil_apply(face, depth_pass ? face.zpass : face.zfail, s);
  return depth_pass;
}

// The span kernels: the per-pixel loops that do not depend on the shaders. raster3d compiles them once per
// instruction set in its own sources (span_kernels.cpp for the baseline, span_avx2.cpp, span_avx512.cpp, each with its
// compiler flags), and the templates below reach them through the table of the widest set the CPU has (span_kernels,
// asked once per tile). Every set makes the same IEEE operations, so the same pixels.

/// One constant color c32 over image-row pixels [lo, hi) of image row r with the depth plane (za, zdx, zdy): the
/// depth test, then the depth (when written) and color writes of the pixels that pass, branch-free.
using FillSpan = void(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                      float zdy, float r, uint32_t c32);

/// The depth test of image-row pixels [lo, hi) of row r (early z): their depths into d[i - lo], the outcome into
/// pass[i - lo].
using TestSpan = void(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                      uint32_t* __restrict d, bool* __restrict pass);

/// Rasterizes a Gouraud record (three color varyings, ColorFragmentShader; `planes` its plane data) over the
/// rectangle [x0, x1) x [y0, y1) (GL pixels, fits_int32_block) eight pixels at a time, in the same IEEE operations
/// as raster_tile's scalar loop. The caller owns the pixels left of x_owned in these rows (its tile's).
using GouraudRect = void(const TriangleRecord& r, const float* planes, int x0, int x1, int y0, int y1, int x_owned,
                         Image<uint32_t>& depth, ImageRGBA8& color, bool write_depth);

inline constexpr int kDepthFuncs = 8;  // DepthFunc's values, never to always: the tables' index

/// The span kernels of one instruction set, by DepthFunc.
struct SpanKernels {
  FillSpan* fill[kDepthFuncs][2];     // [func][depth write]
  TestSpan* test[kDepthFuncs];        // [func]
  GouraudRect* gouraud[kDepthFuncs];  // [func]; null in the baseline set (raster_tile's scalar loop does it)
};

/// A cap on the instruction set of the span kernels (tests set it to 0 to compare with the baseline; -1: none).
int& span_isa_cap();

/// The widest instruction set the CPU has (core's simd_level, asked once), under span_isa_cap: 2 AVX-512, 1 AVX2 with
/// FMA, 0 the baseline.
int span_isa();

/// The span kernels of span_isa().
const SpanKernels& span_kernels();

/// The kernels of each set by name, for the tests that compare the sets (instantiated for every DepthFunc; call the
/// AVX2 and AVX-512 ones only where span_isa() has them).
template <DepthFunc F, bool WriteDepth>
void fill_span_loop(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                    float zdy, float r, uint32_t c32);
template <DepthFunc F, bool WriteDepth>
void fill_span_avx2(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                    float zdy, float r, uint32_t c32);
template <DepthFunc F, bool WriteDepth>
void fill_span_avx512(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                      float zdy, float r, uint32_t c32);
template <DepthFunc F>
void test_span_loop(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                    uint32_t* __restrict d, bool* __restrict pass);
template <DepthFunc F>
void test_span_avx2(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                    uint32_t* __restrict d, bool* __restrict pass);
template <DepthFunc F>
void test_span_avx512(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                      uint32_t* __restrict d, bool* __restrict pass);

/// Calls fn(std::integral_constant<DepthFunc, F>) for the runtime value f.
template <class Fn>
void dispatch_depth_func(DepthFunc f, Fn&& fn) {
  switch (f) {
    case DepthFunc::never:
      return fn(std::integral_constant<DepthFunc, DepthFunc::never>());
    case DepthFunc::less:
      return fn(std::integral_constant<DepthFunc, DepthFunc::less>());
    case DepthFunc::equal:
      return fn(std::integral_constant<DepthFunc, DepthFunc::equal>());
    case DepthFunc::lequal:
      return fn(std::integral_constant<DepthFunc, DepthFunc::lequal>());
    case DepthFunc::greater:
      return fn(std::integral_constant<DepthFunc, DepthFunc::greater>());
    case DepthFunc::notequal:
      return fn(std::integral_constant<DepthFunc, DepthFunc::notequal>());
    case DepthFunc::gequal:
      return fn(std::integral_constant<DepthFunc, DepthFunc::gequal>());
    case DepthFunc::always:
      return fn(std::integral_constant<DepthFunc, DepthFunc::always>());
  }
}

/// The covered pixels [lo, hi) of GL row j inside the record's three edges and [lo, hi). Always inlined: called from
/// three loops, GCC kept it out of line, which cost large constant triangles 9% (the fill benchmark).
[[gnu::always_inline]] inline void edge_span(const TriangleRecord& r, int j, int& lo, int& hi) {
  if (hi - lo <= 8) {
    // Narrow rows (small triangles): test the few centers directly; the covered run is contiguous (convexity).
    int64_t e0[3], step[3];
    for (int k = 0; k < 3; ++k) {
      e0[k] = int64_t(r.edges[k].b) * 256 * j + r.edges[k].c;
      step[k] = int64_t(r.edges[k].a) * 256;
    }
    const auto inside = [&](int i) {
      return (e0[0] + step[0] * i) >= 0 && (e0[1] + step[1] * i) >= 0 && (e0[2] + step[2] * i) >= 0;
    };
    while (lo < hi && !inside(lo)) ++lo;
    while (hi > lo && !inside(hi - 1)) --hi;
    return;
  }
  for (const Edge& e : r.edges) {
    const int64_t e0 = int64_t(e.b) * 256 * j + e.c;  // E at i = 0
    const int64_t step = int64_t(e.a) * 256;
    // Doubles hold these integers exactly (|E| < 2^53) and the quotient's floor is exact: a non-integer quotient is
    // at least 1/|step| away from an integer, far more than the division's rounding error.
    if (step > 0) {
      lo = std::max(lo, int(-std::floor(double(e0) / double(step))));  // i >= ceil(-e0 / step)
    } else if (step < 0) {
      hi = std::min(hi, int(std::floor(double(e0) / double(-step))) + 1);  // i <= floor(e0 / -step)
    } else if (e0 < 0) {
      hi = lo;
      return;
    }
  }
}

/// Whether the record's edges cover every pixel center of [x0, x1) x [y0, y1) (not empty): the edge functions are
/// linear, so inside at the four corner centers means inside everywhere.
inline bool covers_rectangle(const TriangleRecord& r, int x0, int x1, int y0, int y1) {
  for (const Edge& e : r.edges) {
    const int64_t ax = int64_t(e.a) * 256, by = int64_t(e.b) * 256;
    const int64_t low_x = ax * (ax < 0 ? x1 - 1 : x0), low_y = by * (by < 0 ? y1 - 1 : y0);  // the smallest corner
    if (low_x + low_y + e.c < 0) return false;
  }
  return true;
}

/// Whether the record's edge functions stay within int32 over the rectangle [x0, x1) x [y0, y1), eight pixels
/// beyond its right side and one row above it (the vector loops' lanes), so that they can be stepped in 32-bit lanes.
/// A bound rather than the four corners (a third of the work per record): |E| is at most its value at (x0, y0)
/// plus its steps across the rectangle.
inline bool fits_int32_block(const TriangleRecord& r, int x0, int x1, int y0, int y1) {
  constexpr int64_t kLimit = int64_t(1) << 30;
  for (const Edge& e : r.edges) {
    const int64_t ax = int64_t(e.a) * 256, by = int64_t(e.b) * 256;
    if (ax > (1 << 20) || ax < -(1 << 20)) return false;
    const int64_t corner = ax * x0 + by * y0 + e.c;
    if (std::abs(corner) + std::abs(ax) * (x1 + 8 - x0) + std::abs(by) * (y1 - y0) > kLimit) return false;
  }
  return true;
}

/// The varying planes of a record (not constant) at the centers of GL row j: (c + cy dy) for 1/w and each varying,
/// so that a pixel adds cx dx (each plane evaluated directly at the pixel center, as the vector loops do).
template <int N>
[[gnu::always_inline]] inline std::array<float, N + 1> row_planes(const TriangleRecord& r, const float* data, int j) {
  const float* pc = data;
  const float* py = data + 2 * (N + 1);
  const float dy = float(j) + 0.5f - r.ry;
  std::array<float, N + 1> base;
  for (int k = 0; k <= N; ++k) base[k] = pc[k] + py[k] * dy;
  return base;
}

/// Interpolates the varyings perspective-correctly at dx from the record's origin along a row (base from row_planes,
/// px and py the planes' slopes) and runs the fragment shader; false when it discards.
template <int N, class V, class FS>
[[gnu::always_inline]] inline bool interpolated_fragment(const FS& fs, const float* base, const float* px,
                                                         const float* py, float dx, Vec4f& c) {
  const float w = 1.0f / (base[0] + px[0] * dx);
  std::array<float, N> values;
  for (int q = 0; q < N; ++q) values[q] = (base[q + 1] + px[q + 1] * dx) * w;
  V v;
  if constexpr (N > 0) std::memcpy(&v, values.data(), sizeof(float) * N);
  if constexpr (DerivativeFragmentShader<FS, V> && N > 0) {
    // value = P / Q with P (the varying / w) and Q (1 / w) affine on the screen, w = 1 / Q: so
    // d value / dx = (dP/dx - value dQ/dx) w, and the same in y.
    std::array<float, N> ddx, ddy;
    for (int q = 0; q < N; ++q) {
      ddx[q] = (px[q + 1] - values[q] * px[0]) * w;
      ddy[q] = (py[q + 1] - values[q] * py[0]) * w;
    }
    V vx, vy;
    std::memcpy(&vx, ddx.data(), sizeof(float) * N);
    std::memcpy(&vy, ddy.data(), sizeof(float) * N);
    return run_fragment_shader(fs, v, vx, vy, c);
  } else {
    return run_fragment_shader(fs, v, V{}, V{}, c);
  }
}

/// The rows of a record within GL pixels [x0, x1) x [y0, y1): for each, the covered span [lo, hi) depth-tested at
/// once (early z, vectorized), then `pixels(j, image row, lo, hi, d, pass)` with the depth and outcome of each pixel
/// from lo.
template <DepthFunc F, class Pixels>
[[gnu::always_inline]] inline void for_each_tested_span(Framebuffer& fb, const TriangleRecord& r, int x0, int x1,
                                                        int y0, int y1, Pixels&& pixels) {
  TestSpan* const test_span = span_kernels().test[int(F)];
  for (int j = y0; j < y1; ++j) {
    int lo = x0, hi = x1;
    edge_span(r, j, lo, hi);
    if (lo >= hi) continue;
    const int row = fb.height() - 1 - j;
    uint32_t d[kTileSize];
    bool pass[kTileSize];
    test_span(fb.depth().row(row), lo, hi, r.za, r.zdx, r.zdy, float(row), d, pass);
    pixels(j, row, lo, hi, d, pass);
  }
}

/// Rasterizes one record over GL pixels [x0, x1) x [y0, y1) pixel by pixel, with the stencil test (when on), the
/// color write mask and blending: the path of draws that use them (shadow volumes, masks, transparency), not of
/// ordinary shading (out of line: it leaves the ordinary loops' code as it was).
template <int N, class V, class FS, DepthFunc F>
[[gnu::noinline]] void raster_record_masked(Framebuffer& fb, const TriangleRecord& r, const float* data,
                                            const SetupParams& params, bool depth_write, int x0, int x1, int y0, int y1,
                                            const FS& fs) {
  const bool constant = r.constant || N == 0;
  Vec4f constant_color(0);
  bool constant_kept = false;
  if (constant) {
    V v{};
    if constexpr (N > 0) std::memcpy(&v, data, sizeof(float) * N);
    constant_kept = run_fragment_shader(fs, v, V{}, V{}, constant_color);
  }
  const StencilFace& face = params.stencil[r.front];
  // A constant record may come without planes (data null): no arithmetic on that pointer.
  const float* px = constant ? nullptr : data + (N + 1);
  const float* py = constant ? nullptr : data + 2 * (N + 1);
  const auto shade_span = [&](int j, int row, int lo, int hi, const uint32_t* d, const bool* pass) {
    uint32_t* drow = fb.depth().row(row);
    glm::u8vec4* crow = fb.color().row(row);
    uint8_t* srow = fb.stencil().row(row);
    std::array<float, N + 1> base{};
    if (!constant) base = row_planes<N>(r, data, j);
    for (int k = 0; k < hi - lo; ++k) {
      const bool go = params.stencil_test ? stencil_and_depth(face, pass[k], srow[lo + k]) : pass[k];
      if (!go) continue;
      Vec4f c = constant_color;
      if (constant ? !constant_kept
                   : !interpolated_fragment<N, V>(fs, base.data(), px, py, float(lo + k) + 0.5f - r.rx, c))
        continue;
      if (params.color_write) write_color(params, c, crow[lo + k]);
      if (depth_write) drow[lo + k] = d[k];
    }
  };
  for_each_tested_span<F>(fb, r, x0, x1, y0, y1, shade_span);
}

/// Fetches the depth and color rows of GL pixels [x0, x1) x [y0, y1) into the cache for writing: a tile's pixels are
/// read and written all over, and fetching them at once beats missing on each.
inline void prefetch_rows(Framebuffer& fb, int x0, int x1, int y0, int y1) {
  // A depth-only target (a shadow map) has no color rows: null + i would be undefined behaviour (clang's UBSan).
  const bool has_color = fb.has_color();
  const int height = fb.height();
  for (int j = y0; j < y1; ++j)
    for (int i = x0; i < x1; i += 16) {
      __builtin_prefetch(fb.depth().row(height - 1 - j) + i, 1);
      if (has_color) __builtin_prefetch(fb.color().row(height - 1 - j) + i, 1);
    }
}

/// Rasterizes the records binned to `tile` of every chunk of the pass, in submission order.
template <int N, class V, class FS, DepthFunc F>
void raster_tile(Framebuffer& fb, const SetupPass& binned, const SetupParams& params, bool depth_write, int tile,
                 const FS& fs) {
  const int height = fb.height();
  const int tx = tile % params.tiles_x, ty = tile / params.tiles_x;
  const Scissor sc = scissor(params);
  const int tile_x0 = std::max(sc.x0, tx * kTileSize), tile_x1 = std::min(sc.x1, tx * kTileSize + kTileSize);
  const int tile_y0 = std::max(sc.y0, ty * kTileSize), tile_y1 = std::min(sc.y1, ty * kTileSize + kTileSize);
  auto& color = fb.color();
  auto& depth = fb.depth();
  const bool write_depth = depth_write;
  const bool masked = params.stencil_test || !params.color_write || params.blend;  // (raster_record_masked)
  // Small triangles land anywhere in the tile: fetch its depth and color rows at once rather than miss on each.
  // The same for the tile's first records (each spans two cache lines), scattered over the chunks.
  size_t records = 0;
  for (const SetupChunk& chunk : binned)
    for (size_t b = 0; b < chunk.bins[tile].size() && records < 128; ++b, ++records) {
      const char* record = reinterpret_cast<const char*>(&chunk.records[chunk.bins[tile][b]]);
      __builtin_prefetch(record);
      __builtin_prefetch(record + 64);
    }
  if (records == 0) return;
  const SpanKernels& kernels = span_kernels();
  FillSpan* const fill_span = kernels.fill[int(F)][write_depth];
  prefetch_rows(fb, tile_x0, tile_x1, tile_y0, tile_y1);
  for (const SetupChunk& chunk : binned) {
    const std::vector<uint32_t>& bin = chunk.bins[tile];
    for (size_t b = 0; b < bin.size(); ++b) {
      const TriangleRecord& r = chunk.records[bin[b]];
      const float* data = chunk.varyings.data() + r.varyings;
      const int x0 = std::max(tile_x0, r.x0), x1 = std::min(tile_x1, r.x1);
      const int y0 = std::max(tile_y0, r.y0), y1 = std::min(tile_y1, r.y1);
      if (x0 >= x1 || y0 >= y1) continue;
      if (masked) {
        raster_record_masked<N, V, FS, F>(fb, r, data, params, write_depth, x0, x1, y0, y1, fs);
        continue;
      }
      if (r.constant || N == 0) {
        // Constant varyings: the fragment shader's answer is the same at every pixel.
        V v{};
        if constexpr (N > 0) std::memcpy(&v, data, sizeof(float) * N);
        Vec4f c;
        if (!run_fragment_shader(fs, v, V{}, V{}, c)) continue;
        const glm::u8vec4 c8 = to_color8(c);
        uint32_t c32;
        std::memcpy(&c32, &c8, sizeof c32);
        // Large triangles often cover the whole rectangle: no per-row edge divisions then.
        const bool full = x1 - x0 > 8 && covers_rectangle(r, x0, x1, y0, y1);
        for (int j = y0; j < y1; ++j) {
          int lo = x0, hi = x1;
          if (!full) edge_span(r, j, lo, hi);
          if (lo >= hi) continue;
          const int row = height - 1 - j;
          uint32_t* drow = depth.row(row);
          AliasedU32* crow = reinterpret_cast<AliasedU32*>(color.row(row));
          fill_span(drow, crow, lo, hi, r.za, r.zdx, r.zdy, float(row), c32);
        }
        continue;
      }
      if constexpr (std::is_same_v<FS, ColorFragmentShader>) {
        // Gouraud with the built-in pass-through fragment shader: eight pixels at a time.
        if (kernels.gouraud[int(F)] && fits_int32_block(r, x0, x1, y0, y1)) {
          kernels.gouraud[int(F)](r, data, x0, x1, y0, y1, tile_x1, depth, color, write_depth);
          continue;
        }
      }
      const float* px = data + (N + 1);
      const float* py = data + 2 * (N + 1);
      const auto shade_span = [&](int j, int row, int lo, int hi, const uint32_t* d, const bool* pass) {
        uint32_t* drow = depth.row(row);
        glm::u8vec4* crow = color.row(row);
        const auto base = row_planes<N>(r, data, j);
        for (int k = 0; k < hi - lo; ++k) {
          if (!pass[k]) continue;
          Vec4f c;
          if (!interpolated_fragment<N, V>(fs, base.data(), px, py, float(lo + k) + 0.5f - r.rx, c)) continue;
          crow[lo + k] = to_color8(c);
          if (write_depth) drow[lo + k] = d[k];
        }
      };
      for_each_tested_span<F>(fb, r, x0, x1, y0, y1, shade_span);
    }
  }
}

/// Stencil- and depth-tests, shades and writes one fragment (of a line or point: the front stencil state) at GL pixel
/// (i, j) (inside the scissor) with depth d and varyings.
template <int N, class V, class FS, DepthFunc F>
void shade_fragment(Framebuffer& fb, const SetupParams& params, int i, int j, uint32_t d, const float* values,
                    bool depth_write, const FS& fs) {
  const int row = fb.height() - 1 - j;
  uint32_t& stored = fb.depth()(i, row);
  const bool depth_pass = depth_passes<F>(d, stored);
  if (params.stencil_test ? !stencil_and_depth(params.stencil[1], depth_pass, fb.stencil()(i, row)) : !depth_pass)
    return;
  V v{};
  if constexpr (N > 0) std::memcpy(&v, values, sizeof(float) * N);
  Vec4f c;
  if (!run_fragment_shader(fs, v, V{}, V{}, c)) return;
  if (params.color_write) write_color(params, c, fb.color()(i, row));
  if (depth_write) stored = d;
}

/// The state shared by the line and point drawers: depth function and write after the painter/depth-test switches.
struct FragmentState {
  DepthFunc func;
  bool depth_write;
};
FragmentState fragment_state(const RasterState& state);

/// Rasterizes the clipped segment a-b (clip position then N varyings each): one fragment per column (x-major) or
/// row (y-major) whose center lies in [start, end); depth linear in window space, varyings perspective-correct.
template <int N, class V, class FS, DepthFunc F>
void raster_segment(Framebuffer& fb, const SetupParams& params, bool depth_write, const float* a, const float* b,
                    const float* flat_values, const FS& fs) {
  const WindowVertex wa = to_window(params, a), wb = to_window(params, b);
  const Scissor sc = scissor(params);
  const float dx = wb.x - wa.x, dy = wb.y - wa.y;
  if (dx == 0 && dy == 0) return;
  const bool x_major = std::abs(dx) >= std::abs(dy);
  const float start = x_major ? wa.x : wa.y, delta = x_major ? dx : dy;
  // Centers c = k + 0.5 with start <= c < end (or end < c <= start going backward).
  const int k0 = delta > 0 ? int(std::ceil(start - 0.5f)) : int(std::floor(start + delta - 0.5f)) + 1;
  const int k1 = delta > 0 ? int(std::ceil(start + delta - 0.5f)) : int(std::floor(start - 0.5f)) + 1;
  std::array<float, N + 1> values{};
  for (int k = k0; k < k1; ++k) {
    const float t = (float(k) + 0.5f - start) / delta;
    const int i = x_major ? k : int(std::floor(wa.x + t * dx));
    const int j = x_major ? int(std::floor(wa.y + t * dy)) : k;
    if (i < sc.x0 || i >= sc.x1 || j < sc.y0 || j >= sc.y1) continue;
    const uint32_t d = depth_to_unorm24(double(wa.z) + double(t) * double(wb.z - wa.z));
    const float* in = flat_values;
    if (!flat_values) {
      const float inv_w = wa.inv_w + t * (wb.inv_w - wa.inv_w);
      for (int q = 0; q < N; ++q)
        values[q] = (a[4 + q] * wa.inv_w + t * (b[4 + q] * wb.inv_w - a[4 + q] * wa.inv_w)) / inv_w;
      in = values.data();
    }
    shade_fragment<N, V, FS, F>(fb, params, i, j, d, in, depth_write, fs);
  }
}

}  // namespace tessera::raster3d::detail

namespace tessera::raster3d {

template <VertexShader VS, FragmentShader<VaryingsOf<VS>> FS>
DrawStats draw_lines(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                     std::span<const uint32_t> indices, const VS& vs, const FS& fs) {
  using V = VaryingsOf<VS>;
  constexpr int n = varying_count<V>;
  constexpr int stride = 4 + n;
  detail::check_draw(framebuffer, state, indices, vertex_count, 2, "line");
  DrawStats stats;
  stats.primitives = indices.size() / 2;
  if (indices.empty()) return stats;
  detail::RasterScratch& scratch = framebuffer.scratch();
  detail::finish_raster(scratch);  // drawn on this thread, after the triangles before them
  const float* vertices = detail::run_vertex_stage(scratch, vertex_count, vs);
  const detail::SetupParams params = detail::setup_params(framebuffer, state, vertices, n);
  const detail::FragmentState fragment = detail::fragment_state(state);
  detail::dispatch_depth_func(fragment.func, [&](auto f) {
    for (size_t l = 0; l < indices.size(); l += 2) {
      std::array<float, stride> a, b, provoking;
      std::memcpy(a.data(), vertices + size_t(indices[l]) * stride, sizeof a);
      std::memcpy(b.data(), vertices + size_t(indices[l + 1]) * stride, sizeof b);
      provoking = b;
      if (!detail::clip_segment(a.data(), b.data(), n)) continue;
      ++stats.rasterized;
      detail::raster_segment<n, V, FS, decltype(f)::value>(framebuffer, params, fragment.depth_write, a.data(),
                                                           b.data(), state.flat ? provoking.data() + 4 : nullptr, fs);
    }
  });
  return stats;
}

template <VertexShader VS, FragmentShader<VaryingsOf<VS>> FS>
DrawStats draw_points(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                      std::span<const uint32_t> indices, const VS& vs, const FS& fs) {
  using V = VaryingsOf<VS>;
  constexpr int n = varying_count<V>;
  constexpr int stride = 4 + n;
  detail::check_draw(framebuffer, state, indices, vertex_count, 1, "point");
  DrawStats stats;
  stats.primitives = indices.size();
  if (indices.empty()) return stats;
  detail::RasterScratch& scratch = framebuffer.scratch();
  detail::finish_raster(scratch);  // drawn on this thread, after the triangles before them
  const float* vertices = detail::run_vertex_stage(scratch, vertex_count, vs);
  const detail::SetupParams params = detail::setup_params(framebuffer, state, vertices, n);
  const detail::Scissor sc = detail::scissor(params);
  const detail::FragmentState fragment = detail::fragment_state(state);
  detail::dispatch_depth_func(fragment.func, [&](auto f) {
    for (uint32_t index : indices) {
      const float* v = vertices + size_t(index) * stride;
      const float w = v[3];
      if (!(std::isfinite(w) && std::abs(v[0]) <= w && std::abs(v[1]) <= w && std::abs(v[2]) <= w)) continue;
      const detail::WindowVertex wv = detail::to_window(params, v);
      const int i = int(std::floor(wv.x)), j = int(std::floor(wv.y));
      if (i < sc.x0 || i >= sc.x1 || j < sc.y0 || j >= sc.y1) continue;
      ++stats.rasterized;
      detail::shade_fragment<n, V, FS, decltype(f)::value>(framebuffer, params, i, j, depth_to_unorm24(wv.z), v + 4,
                                                           fragment.depth_write, fs);
    }
  });
  return stats;
}

namespace detail {

/// The part of a triangle draw after its vertex stage, whose output (per vertex the clip position, then n varyings)
/// is in the current draw input's vertices: setup parameters, prepared vertices, the painter's order, then each pass
/// of kPassChunks chunks set up, binned and submitted to the raster thread, whose job runs
/// `raster(pass, params, fragment, tile_begin, tile_end)` over the tiles in parallel (pipeline_for). Returns how many
/// triangles were set up on this thread (collect_raster counts the raster jobs'). `raster` is copied into each job.
template <class Raster>
uint64_t submit_triangle_passes(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count, int n,
                                std::span<const uint32_t> indices, const Raster& raster) {
  RasterScratch& scratch = framebuffer.scratch();
  RasterScratch::DrawInput& input = scratch.inputs[size_t(scratch.input)];
  const float* vertices = input.vertices.data();
  SetupParams params = setup_params(framebuffer, state, vertices, n);
  prepare_vertices(scratch, params, vertex_count);
  if (state.painter) indices = painter_order(scratch, vertices, 4 + n, indices);
  input.indices.assign(indices.begin(), indices.end());  // the caller's array may change once this returns
  indices = input.indices;
  const FragmentState fragment = fragment_state(state);
  const size_t triangles = indices.size() / 3;
  const size_t per_pass = size_t(kChunkTriangles) * kPassChunks;
  const int tiles = params.tiles_x * params.tiles_y;
  uint64_t rasterized = 0;
  for (size_t first = 0; first < triangles; first += per_pass) {
    // The other pass's job, if any, is the only one that may be running (submit_raster): this one is free.
    SetupPass& pass = scratch.passes[size_t(scratch.next_pass)];
    scratch.next_pass ^= 1;
    const size_t count = std::min(per_pass, triangles - first);
    const auto chunks = int64_t((count + kChunkTriangles - 1) / kChunkTriangles);
    reset_pass(pass, params);
    int64_t split = 0;
    rasterized += setup_chunks_while_raster_busy(scratch, pass, params, indices, first, count, chunks, split);
    submit_raster(scratch, [&scratch, &pass, params, indices, first, count, split, chunks, fragment, tiles, raster] {
      scratch.job_rasterized += setup_chunks(scratch, pass, params, indices, first, count, split, chunks);
      pipeline_for(scratch, PipelineSide::raster, 0, tiles, 1,
                   [&](int64_t begin, int64_t end) { raster(pass, params, fragment, begin, end); });
    });
  }
  return rasterized;
}

/// draw_triangles, except that it returns before the tile rasterization of its last pass is done (the raster thread
/// goes on with it; finish_raster waits): the caller may collect and set up the next draw meanwhile. `fs`, and what
/// it refers to, must live until then: the raster jobs hold `keep_alive` until they are done.
template <class VS, class FS>
DrawStats draw_triangles_async(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                               std::span<const uint32_t> indices, const VS& vs, const FS& fs,
                               const std::shared_ptr<const void>& keep_alive = nullptr) {
  using V = VaryingsOf<VS>;
  constexpr int n = varying_count<V>;
  check_draw(framebuffer, state, indices, vertex_count, 3, "triangle");
  DrawStats stats;
  stats.primitives = indices.size() / 3;
  if (indices.empty()) return stats;
  RasterScratch& scratch = framebuffer.scratch();
  // The previous draw's last job may still read its input set: this draw fills the other one (the draw before that
  // is done: this draw's first submit_raster waits for the previous draw's last job, which waited for its own).
  scratch.input ^= 1;
  run_vertex_stage(scratch, vertex_count, vs);
  const auto raster = [&framebuffer, &fs, keep_alive](const SetupPass& pass, const SetupParams& params,
                                                      const FragmentState& fragment, int64_t begin, int64_t end) {
    dispatch_depth_func(fragment.func, [&](auto f) {
      for (int64_t t = begin; t < end; ++t)
        raster_tile<n, V, FS, decltype(f)::value>(framebuffer, pass, params, fragment.depth_write, int(t), fs);
    });
  };
  stats.rasterized += submit_triangle_passes(framebuffer, state, vertex_count, n, indices, raster);
  return stats;
}

}  // namespace detail

template <VertexShader VS, FragmentShader<VaryingsOf<VS>> FS>
DrawStats draw_triangles(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                         std::span<const uint32_t> indices, const VS& vs, const FS& fs) {
  DrawStats stats = detail::draw_triangles_async(framebuffer, state, vertex_count, indices, vs, fs);
  stats.rasterized += detail::collect_raster(framebuffer.scratch());
  return stats;
}

}  // namespace tessera::raster3d
