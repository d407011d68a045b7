#pragma once
// The pipeline's implementation: the template parts (vertex stage, per-tile span loops) live here so the shaders
// inline; clipping, triangle setup and binning do not depend on the shaders and live in src/pipeline.cpp.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <immintrin.h>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/raster3d/framebuffer.hpp"
#include "tessera/raster3d/shaders.hpp"

namespace tessera::raster3d::detail {

inline constexpr int kTileSize = 64;          // pixels per side of a binning tile
inline constexpr int kMaxVaryings = 32;       // floats of varyings a shader may pass
inline constexpr int kChunkTriangles = 1024;  // input triangles set up and binned by one task
inline constexpr int kPassChunks = 16;        // chunks set up before the tiles are rasterized (a pass stays in cache)

/// An edge function in 1/256-pixel fixed point: at the center of GL pixel (i, j) it is
/// E = 256 (a i + b j) + c, with the tie rule folded into c (a center on an exclusive edge gives -1). The pixel is
/// inside the edge when E >= 0.
struct Edge {
  int64_t c;
  int32_t a, b;
};

/// A triangle after clipping, viewport, snapping and setup: what the tiles rasterize.
struct TriangleRecord {
  struct Uninitialized {};
  TriangleRecord() = default;  // TriangleRecord{} is zeroed
  /// Setup fills every member: no zeroing first (a 96-byte `rep stos` per triangle).
  explicit TriangleRecord(Uninitialized) {}

  Edge edges[3];
  int32_t x0, y0, x1, y1;  // covered GL pixels lie in [x0, x1) x [y0, y1) (scissored)
  float za, zdx, zdy;      // the depth plane as llvmpipe evaluates it: window z at image pixel (i, row r) is
                           // fragment_depth(za, zdx, zdy, i, r) (see there)
  float rx, ry;            // the varying planes' origin (window position of the first vertex)
  uint32_t varyings;       // offset in the chunk's varyings: constant, N floats; else the planes c[N+1], cx[N+1],
                           // cy[N+1] of 1/w and of each varying / w: value(px, py) = c + cx (px - rx) + cy (py - ry)
  bool constant;           // flat shading, or the three vertices' varyings are equal: no interpolation
  bool front;              // counterclockwise on screen (the stencil state of front faces)
};

/// The triangles one setup task produced, and their per-tile lists (record indices in submission order).
struct SetupChunk {
  std::vector<TriangleRecord> records;
  std::vector<float> varyings;  // [0, varyings_used) hold this pass's values; the rest is kept from pass to pass
  size_t varyings_used = 0;
  std::vector<std::vector<uint32_t>> bins;
  uint64_t rasterized = 0;

  /// Room for `count` more varying values, not initialized (setup writes them in place: no zeroing, no copy).
  float* append_varyings(size_t count) {
    if (varyings_used + count > varyings.size()) [[unlikely]]
      varyings.resize(std::max(2 * varyings.size(), varyings_used + count));
    float* out = varyings.data() + varyings_used;
    varyings_used += count;
    return out;
  }
};

/// A vertex after perspective divide and viewport: window x, y (GL, y up), z in [0, 1], and 1/w.
struct WindowVertex {
  float x, y, z, inv_w;
};

/// A vertex's window position as Gallium (llvmpipe) has it: x, y down from the top row, z.
struct GalliumVertex {
  float x, y, z;
};

/// What triangle setup needs of a vertex, computed once per vertex: the clip planes it is outside of (bit p for
/// plane p, bit 6 for a NaN or infinite position), the window position, 1/w and the snapped 1/256-pixel position (GL
/// y up). Not valid when w <= 0 (only possible on a degenerate clipped polygon).
struct PreparedVertex {
  GalliumVertex g;
  float inv_w;
  int32_t X, Y;
  uint8_t outcode;
  bool valid;
};

/// The kPassChunks chunks of one setup pass: what one raster job reads.
using SetupPass = std::vector<SetupChunk>;

class RasterThread;  // the framebuffer's raster thread (pipeline.cpp)
struct PipelineArenas;  // the oneTBB arenas of pipeline_for (pipeline.cpp)

/// Memory reused from draw to draw, and the raster thread, owned by the Framebuffer.
struct RasterScratch {
  RasterScratch();
  ~RasterScratch();  // waits for the raster thread's job and ends the thread

  // What setup reads of a draw, double buffered by draw: a raster job sets up the last chunks of its pass, so it reads
  // them while the caller runs the next draw's vertex stage into the other set.
  struct DrawInput {
    std::vector<float> vertices;  // vertex stage output: per vertex, clip position (4 floats) then the varyings
    std::vector<PreparedVertex> prepared;  // per vertex, for the triangles that need no clipping
    std::vector<uint32_t> indices;         // the triangles' indices, in drawing order
  };
  std::array<DrawInput, 2> inputs;
  int input = 0;                   // the current draw's set
  std::vector<uint32_t> order;     // painter's algorithm: the sorted triangle indices
  std::atomic<uint64_t> job_rasterized{0};  // triangles set up by raster jobs, until the caller collects them
  // Double buffered: setup fills passes[next_pass] while the raster thread reads the other one.
  std::array<SetupPass, 2> passes;
  int next_pass = 0;
  std::unique_ptr<PipelineArenas> arenas;       // each side's, made by pipeline_for on that side's thread
  std::unique_ptr<RasterThread> raster_thread;  // started by the first submit_raster; last, so it ends first
};

/// The two sides of the pipeline: the calling thread (vertex stage, setup) and the raster job.
enum class PipelineSide { caller, raster };

/// parallel_for for one side of the pipeline, counting the other side's thread among the ThreadLimit's N while it
/// is busy: the raster job's loops run on up to N - 1 threads (N while the caller waits for the job), and the
/// caller's on N - 1 while a raster job runs, else on N. So with N = 2 (and on two cores) a side's loop runs on its
/// own thread while the other side works, and no oneTBB worker takes a core from the other side's thread, then spins
/// once its part is done (it did: a tenth more CPU time per frame). The chunks are the same for any thread count.
void pipeline_for(RasterScratch& scratch, PipelineSide side, int64_t first, int64_t last, int64_t grain,
                  const std::function<void(int64_t, int64_t)>& body);

/// Runs `job` on the scratch's raster thread (started on first use), after every job submitted before it: waits for
/// the previous job to finish, then hands this one over and returns. So at most one job runs at a time, in
/// submission order, and on return only this job may still be running.
void submit_raster(RasterScratch& scratch, std::function<void()> job);

/// Waits until the submitted raster jobs are done; rethrows the exception a job ended with, if any.
void finish_raster(RasterScratch& scratch);

/// finish_raster, returning how many triangles the finished jobs set up since the last collect_raster (counted
/// before a job's exception leaves, so the stats stay whole).
uint64_t collect_raster(RasterScratch& scratch);

/// Waits until the submitted raster jobs are done, keeping a job's exception for finish_raster (for destructors
/// and moves).
void wait_raster(RasterScratch& scratch) noexcept;

/// Whether the raster thread has no job (a hint, read without waiting: a job may end just after it answers false).
bool raster_idle(const RasterScratch& scratch) noexcept;

/// What setup needs to know about a draw.
struct SetupParams {
  const float* vertices;  // vertex stage output
  const PreparedVertex* prepared = nullptr;  // per vertex (prepare_vertices)
  int varying_count;      // N
  bool flat, painter;
  int cull;  // 0 none, 1 back, 2 front
  bool color_write, stencil_test, blend;
  StencilFace stencil[2];  // back, front (indexed by TriangleRecord::front)
  BlendFunction blend_function;
  int fb_width, fb_height;
  int vx, vy, vw, vh;  // the viewport
  int tiles_x, tiles_y;
};

/// Empties the kPassChunks chunks of `pass` for a new pass.
void reset_pass(SetupPass& pass, const SetupParams& params);

/// Clips, culls, snaps and sets up chunks [chunk_begin, chunk_end) of the pass of `triangle_count` triangles of
/// `indices` starting at triangle `first`, into `pass` (chunk c: kChunkTriangles from first + c kChunkTriangles, in
/// parallel on the raster job's side), binning each record to the tiles it touches. Returns how many triangles they
/// hold.
uint64_t setup_chunks(RasterScratch& scratch, SetupPass& pass, const SetupParams& params,
                      std::span<const uint32_t> indices, size_t first, size_t triangle_count, int64_t chunk_begin,
                      int64_t chunk_end);

/// setup_chunks from chunk 0 on (in parallel on the caller's side) until the raster thread has no job: the chunks are
/// set up on this thread while the raster thread is busy, and the rest by the raster job once it is free, so neither
/// waits for the other (the split adapts to which side is slower; a chunk is set up identically on either). Sets
/// `taken` to the number of chunks set up here, [0, taken), and returns how many triangles they hold.
uint64_t setup_chunks_while_raster_busy(RasterScratch& scratch, SetupPass& pass, const SetupParams& params,
                                        std::span<const uint32_t> indices, size_t first, size_t triangle_count,
                                        int64_t chunks, int64_t& taken);

/// The triangle indices reordered far to near by the window depth of each triangle's centroid (stable), into
/// scratch.order.
std::span<const uint32_t> painter_order(RasterScratch& scratch, const float* vertices, int stride,
                                        std::span<const uint32_t> indices);

/// Clips the segment a-b (clip position then `varying_count` floats each) to the clip volume. Returns false when
/// nothing is left; otherwise a and b are replaced by the clipped end points.
bool clip_segment(float* a, float* b, int varying_count);

/// Throws InvalidInput unless indices.size() is a multiple of `arity`, every index is < vertex_count, and the
/// framebuffer has the buffers the state uses (a stencil test needs a stencil buffer: not a depth_only one's).
void check_draw(const Framebuffer& fb, const RasterState& state, std::span<const uint32_t> indices,
                uint32_t vertex_count, int arity, const char* what);

/// The setup parameters of a draw.
SetupParams setup_params(const Framebuffer& fb, const RasterState& state, const float* vertices, int varying_count);

/// The perspective divide and viewport transform of a clip-space position (float32, as OpenGL).
WindowVertex to_window(const SetupParams& params, const float* clip);

/// The window positions of the vertex stage's `count` vertices (PreparedVertex), in parallel, into the current draw
/// input's prepared vertices and params.prepared.
void prepare_vertices(RasterScratch& scratch, SetupParams& params, uint32_t count);

/// The scissor rectangle in GL window pixels: viewport intersected with the framebuffer.
struct Scissor {
  int x0, y0, x1, y1;
};
Scissor scissor(const SetupParams& params);

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

/// The window z of the fragment at image pixel (i, row r) from the triangle's float depth plane, in llvmpipe's
/// arithmetic (Mesa 22.3, lp_bld_interp.c): a0 + dadx i, then + dady r, each a fused multiply-add.
[[gnu::always_inline]] inline float fragment_depth(float za, float zdx, float zdy, float i, float r) {
  return __builtin_fmaf(zdy, r, __builtin_fmaf(zdx, i, za));
}

/// A fragment's window z to the stored 24-bit value as llvmpipe converts it (lp_build_clamped_float_to_unsigned_norm
/// for 24 bits): clamped to [0, 1] (NaN to 0), times 2^24 - 1 in float, rounded to nearest with ties to even.
[[gnu::always_inline]] inline uint32_t depth24(float z) {
  z = z > 0.0f ? z : 0.0f;
  z = z < 1.0f ? z : 1.0f;
  return uint32_t(int32_t(__builtin_rintf(z * float(kDepthMax))));
}

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

/// One constant color over image-row pixels [lo, hi) of image row r with the depth plane (za, zdx, zdy): depth test,
/// depth and color writes, branch-free (the loop vectorizes; restrict lets the compiler keep the rows apart).
template <DepthFunc F, bool WriteDepth>
[[gnu::always_inline]] inline void fill_span_loop(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo,
                                                  int hi, float za, float zdx, float zdy, float r, uint32_t c32) {
  for (int i = lo; i < hi; ++i) {
    const uint32_t d = depth24(fragment_depth(za, zdx, zdy, float(i), r));
    const uint32_t stored = depth[i];
    const uint32_t old_color = color[i];
    const bool pass = depth_passes<F>(d, stored);
    if constexpr (WriteDepth) depth[i] = pass ? d : stored;
    color[i] = pass ? c32 : old_color;
  }
}

/// The depth test of image-row pixels [lo, hi) of row r (early z): their depths into d[i - lo], the outcome into
/// pass[i - lo].
template <DepthFunc F>
[[gnu::always_inline]] inline void test_span_loop(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx,
                                                  float zdy, float r, uint32_t* __restrict d, bool* __restrict pass) {
  for (int i = lo; i < hi; ++i) {
    d[i - lo] = depth24(fragment_depth(za, zdx, zdy, float(i), r));
    pass[i - lo] = depth_passes<F>(d[i - lo], depth[i]);
  }
}

// The same loops compiled for AVX-512 and for AVX2 (with FMA): sixteen or eight floats per instruction instead of
// SSE2's four. The same IEEE operations (the multiply-adds are explicit fmaf calls, a library call in the baseline;
// no other contraction: CMakeLists.txt passes -ffp-contract=off), so the same pixels.
#define TESSERA_AVX512 gnu::target("avx512f,avx512vl,avx512bw,avx512dq,fma")
#define TESSERA_AVX2 gnu::target("avx2,fma")
template <DepthFunc F, bool WriteDepth>
[[TESSERA_AVX512]] void fill_span_avx512(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi,
                                         float za, float zdx, float zdy, float r, uint32_t c32) {
  fill_span_loop<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
}
template <DepthFunc F, bool WriteDepth>
[[TESSERA_AVX2]] void fill_span_avx2(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi,
                                     float za, float zdx, float zdy, float r, uint32_t c32) {
  fill_span_loop<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
}
template <DepthFunc F>
[[TESSERA_AVX512]] void test_span_avx512(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx,
                                         float zdy, float r, uint32_t* __restrict d, bool* __restrict pass) {
  test_span_loop<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
}
template <DepthFunc F>
[[TESSERA_AVX2]] void test_span_avx2(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx,
                                     float zdy, float r, uint32_t* __restrict d, bool* __restrict pass) {
  test_span_loop<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
}
#undef TESSERA_AVX512
#undef TESSERA_AVX2

/// A cap on the instruction set the span loops use (tests set it to 0 to compare with the baseline; -1: none).
inline int& span_isa_cap() {
  static int cap = -1;
  return cap;
}

/// The widest instruction set the CPU has (under span_isa_cap): 2 AVX-512, 1 AVX2 with FMA, 0 the baseline.
inline int span_isa() {
  static const int isa = [] {
    if (!__builtin_cpu_supports("fma")) return 0;
    if (__builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"))
      return 2;
    return __builtin_cpu_supports("avx2") ? 1 : 0;
  }();
  return span_isa_cap() < 0 ? isa : std::min(isa, span_isa_cap());
}

/// fill_span_loop in the widest instruction set the CPU has.
template <DepthFunc F, bool WriteDepth>
inline void fill_span(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                      float zdy, float r, uint32_t c32) {
  switch (span_isa()) {
    case 2:
      return fill_span_avx512<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
    case 1:
      return fill_span_avx2<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
    default:
      return fill_span_loop<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
  }
}

/// test_span_loop in the widest instruction set the CPU has.
template <DepthFunc F>
inline void test_span(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                      uint32_t* __restrict d, bool* __restrict pass) {
  switch (span_isa()) {
    case 2:
      return test_span_avx512<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
    case 1:
      return test_span_avx2<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
    default:
      return test_span_loop<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
  }
}

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

/// A depth comparison of eight lanes (values below 2^24, so signed compares are exact): all ones where it passes.
template <DepthFunc F>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline __m256i depth_passes8(__m256i d, __m256i s) {
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
[[gnu::target("avx2,fma")]] void gouraud_rect_avx2(const TriangleRecord& r, const float* planes, int x0, int x1,
                                                     int y0, int y1, int x_owned, Image<uint32_t>& depth,
                                                     ImageRGBA8& color, bool write_depth) {
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
      const __m256i cover = _mm256_andnot_si256(_mm256_srai_epi32(outside, 31),
                                                _mm256_cmpgt_epi32(_mm256_set1_epi32(x1 - x), lane));
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
[[gnu::target("avx512f,avx512vl,avx512bw,avx512dq,fma"), gnu::always_inline]] inline __mmask16 depth_passes16(
    __mmask16 lanes, __m512i d, __m512i s) {
  if constexpr (F == DepthFunc::never)
    return 0;
  else if constexpr (F == DepthFunc::always)
    return lanes;
  else
    return _mm512_mask_cmp_epi32_mask(lanes, d, s, kDepthCmpInt<F>);
}

// GCC 12's AVX-512 intrinsics start from _mm512_undefined_*(), which -Wmaybe-uninitialized reports once inlined.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
/// gouraud_rect_avx2 for AVX-512: sixteen lanes, eight pixels of two rows, with mask registers for the masked
/// loads and stores. The same operations per pixel, so the same pixels.
template <DepthFunc F>
[[gnu::target("avx512f,avx512vl,avx512bw,avx512dq,fma")]] void gouraud_rect_avx512(
    const TriangleRecord& r, const float* planes, int x0, int x1, int y0, int y1, int x_owned, Image<uint32_t>& depth,
    ImageRGBA8& color, bool write_depth) {
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
#pragma GCC diagnostic pop

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
  for (int j = y0; j < y1; ++j) {
    int lo = x0, hi = x1;
    edge_span(r, j, lo, hi);
    if (lo >= hi) continue;
    const int row = fb.height() - 1 - j;
    uint32_t d[kTileSize];
    bool pass[kTileSize];
    test_span<F>(fb.depth().row(row), lo, hi, r.za, r.zdx, r.zdy, float(row), d, pass);
    pixels(j, row, lo, hi, d, pass);
  }
}

/// Rasterizes one record over GL pixels [x0, x1) x [y0, y1) pixel by pixel, with the stencil test (when on), the
/// color write mask and blending: the path of draws that use them (shadow volumes, masks, transparency), not of
/// ordinary shading (out of line: it leaves the ordinary loops' code as it was).
template <int N, class V, class FS, DepthFunc F>
[[gnu::noinline]] void raster_record_masked(Framebuffer& fb, const TriangleRecord& r, const float* data,
                                            const SetupParams& params, bool depth_write, int x0, int x1, int y0,
                                            int y1, const FS& fs) {
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
  const int isa = span_isa();
  // A depth-only target (a shadow map) has no color rows: null + i would be undefined behaviour (clang's UBSan).
  const bool has_color = fb.has_color();
  for (int j = tile_y0; j < tile_y1; ++j)
    for (int i = tile_x0; i < tile_x1; i += 16) {
      __builtin_prefetch(depth.row(height - 1 - j) + i, 1);
      if (has_color) __builtin_prefetch(color.row(height - 1 - j) + i, 1);
    }
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
          if (write_depth)
            fill_span<F, true>(drow, crow, lo, hi, r.za, r.zdx, r.zdy, float(row), c32);
          else
            fill_span<F, false>(drow, crow, lo, hi, r.za, r.zdx, r.zdy, float(row), c32);
        }
        continue;
      }
      if constexpr (std::is_same_v<FS, ColorFragmentShader>) {
        // Gouraud with the built-in pass-through fragment shader: eight pixels at a time.
        if (isa >= 1 && fits_int32_block(r, x0, x1, y0, y1)) {
          if (isa == 2)
            gouraud_rect_avx512<F>(r, data, x0, x1, y0, y1, tile_x1, depth, color, write_depth);
          else
            gouraud_rect_avx2<F>(r, data, x0, x1, y0, y1, tile_x1, depth, color, write_depth);
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
  RasterScratch::DrawInput& input = scratch.inputs[size_t(scratch.input)];
  const float* vertices = run_vertex_stage(scratch, vertex_count, vs);
  SetupParams params = setup_params(framebuffer, state, vertices, n);
  prepare_vertices(scratch, params, vertex_count);
  if (state.painter) indices = painter_order(scratch, vertices, 4 + n, indices);
  input.indices.assign(indices.begin(), indices.end());  // the caller's array may change once this returns
  indices = input.indices;
  const FragmentState fragment = fragment_state(state);
  const size_t triangles = indices.size() / 3;
  const size_t per_pass = size_t(kChunkTriangles) * kPassChunks;
  const int tiles = params.tiles_x * params.tiles_y;
  for (size_t first = 0; first < triangles; first += per_pass) {
    // The other pass's job, if any, is the only one that may be running (submit_raster): this one is free.
    SetupPass& pass = scratch.passes[size_t(scratch.next_pass)];
    scratch.next_pass ^= 1;
    const size_t count = std::min(per_pass, triangles - first);
    const auto chunks = int64_t((count + kChunkTriangles - 1) / kChunkTriangles);
    reset_pass(pass, params);
    int64_t split = 0;
    stats.rasterized += setup_chunks_while_raster_busy(scratch, pass, params, indices, first, count, chunks, split);
    submit_raster(scratch, [&framebuffer, &scratch, &pass, params, indices, first, count, split, chunks, fragment, &fs,
                            tiles, keep_alive] {
      scratch.job_rasterized += setup_chunks(scratch, pass, params, indices, first, count, split, chunks);
      dispatch_depth_func(fragment.func, [&](auto f) {
        pipeline_for(scratch, PipelineSide::raster, 0, tiles, 1, [&](int64_t begin, int64_t end) {
          for (int64_t t = begin; t < end; ++t)
            raster_tile<n, V, FS, decltype(f)::value>(framebuffer, pass, params, fragment.depth_write, int(t), fs);
        });
      });
    });
  }
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
