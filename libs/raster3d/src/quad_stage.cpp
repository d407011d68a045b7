// The quad fragment stage (quad_stage.hpp): the pipeline's setup and binning, then per tile the covered 2 x 2 quads
// gathered into FragmentBatch and shaded a batch at a time.
#include "tessera/raster3d/quad_stage.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "span_kernels.hpp"
#include "tessera/core/error.hpp"

namespace tessera::raster3d {
namespace detail {
namespace {

constexpr int kBatchQuads = FragmentBatch::kLanes / 4;

/// to_unorm8 of v as a 32-bit integer, in operations that vectorize (min, max, a multiply-add, a truncation).
inline uint32_t unorm8_bits(float v) {
  v = v > 0.0f ? v : 0.0f;  // NaN -> 0
  v = v < 1.0f ? v : 1.0f;
  constexpr float kRound = 12582912.0f;  // 1.5 * 2^23: adding it rounds to an integer, as to_unorm8
  return uint32_t(int32_t((v * 255.0f + kRound) - kRound));
}

/// One thread's working state for the tiles it rasterizes: the batch being filled, the shader's scratch, and what
/// the writes at the flush need.
struct QuadTile {
  FragmentBatch batch;
  std::unique_ptr<QuadShaderScratch> scratch;
  int quad_i[kBatchQuads], quad_j[kBatchQuads];  // GL pixel of each quad's lane 0
  uint32_t depth[FragmentBatch::kLanes];         // the 24-bit depth of each lane
  uint64_t waiting[kTileSize];                   // per tile row: the pixels a waiting lane covers (bit x - tile x)
  int origin_x = 0, origin_y = 0;                // the tile's first GL pixel
};

/// Shades the waiting quads and writes the lanes that are covered and kept (color and depth), then empties the batch.
void flush(QuadTile& t, Framebuffer& fb, const SetupParams& params, bool depth_write, const QuadFragmentShader& fs) {
  FragmentBatch& b = t.batch;
  if (b.quads == 0) return;
  std::fill(std::begin(b.kept), std::end(b.kept), ~0u);
  fs.shade(b, *t.scratch);
  // The 8-bit colors of all lanes at once, packed as the framebuffer stores them (RGBA in memory order): a loop of
  // fixed length without branches, which the compiler vectorizes. Blending reads the float colors instead.
  alignas(64) uint32_t packed[FragmentBatch::kLanes];
  if (!params.blend)
    for (int lane = 0; lane < FragmentBatch::kLanes; ++lane)
      packed[lane] = unorm8_bits(b.color[0][lane]) | unorm8_bits(b.color[1][lane]) << 8 |
                     unorm8_bits(b.color[2][lane]) << 16 | unorm8_bits(b.color[3][lane]) << 24;
  // The buffers' addresses in locals: the byte-sized color stores may alias anything, so that members read
  // through fb would be read again after each store.
  const int height = fb.height(), width = fb.width();
  const bool color_write = params.color_write, blend = params.blend;
  glm::u8vec4* const color = color_write ? fb.color().row(0) : nullptr;
  uint32_t* const depth = fb.depth().row(0);
  for (int q = 0; q < b.quads; ++q) {
    const int l0 = 4 * q;
    if (!blend && (b.covered[l0] & b.kept[l0] & b.covered[l0 + 1] & b.kept[l0 + 1] & b.covered[l0 + 2] &
                   b.kept[l0 + 2] & b.covered[l0 + 3] & b.kept[l0 + 3])) {
      // The whole quad (most of a large triangle's): each row's two pixels in one 8-byte store per buffer.
      const size_t row0 = size_t(height - 1 - t.quad_j[q]) * size_t(width) + size_t(t.quad_i[q]);
      const size_t row1 = row0 - size_t(width);  // GL row j + 1 is the image row above
      if (color_write) {
        std::memcpy(&color[row0], &packed[l0], 2 * sizeof(uint32_t));
        std::memcpy(&color[row1], &packed[l0 + 2], 2 * sizeof(uint32_t));
      }
      if (depth_write) {
        std::memcpy(&depth[row0], &t.depth[l0], 2 * sizeof(uint32_t));
        std::memcpy(&depth[row1], &t.depth[l0 + 2], 2 * sizeof(uint32_t));
      }
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      const int lane = l0 + k;
      if (!(b.covered[lane] & b.kept[lane])) continue;
      const size_t pixel =
          size_t(height - 1 - (t.quad_j[q] + (k >> 1))) * size_t(width) + size_t(t.quad_i[q] + (k & 1));
      if (color_write && blend) {
        const Vec4f c(b.color[0][lane], b.color[1][lane], b.color[2][lane], b.color[3][lane]);
        write_color(params, c, color[pixel]);
      } else if (color_write) {
        std::memcpy(&color[pixel], &packed[lane], sizeof(uint32_t));
      }
      if (depth_write) depth[pixel] = t.depth[lane];
    }
  }
  for (int q = 0; q < b.quads; ++q) {
    const int by = t.quad_j[q] - t.origin_y;
    t.waiting[by] = 0;
    if (by + 1 < kTileSize) t.waiting[by + 1] = 0;
  }
  b.quads = 0;
}

/// Four floats, one per lane of a quad: GCC's vector extension (SSE on x86-64, NEON on ARM), so that a quad's
/// arithmetic is one instruction per operation without intrinsics of one instruction set.
using Quad4 = float __attribute__((vector_size(16)));

/// Fills quad `q` of the batch: lanes 4q..4q+3 at GL pixel (i, j) and its neighbours, varyings interpolated as
/// interpolated_fragment does (the same operations, so the C++ shaders' pixels do not change on this stage). The four
/// lanes are contiguous (and 16-byte aligned) in every array: each step is one vector operation.
void fill_quad(FragmentBatch& b, int q, const TriangleRecord& r, const float* data, int n, int i, int j, int height) {
  const int l0 = 4 * q;
  const auto lanes = [l0](float* row) -> Quad4& { return *reinterpret_cast<Quad4*>(row + l0); };
  const Quad4 step_x = {0.0f, 1.0f, 0.0f, 1.0f}, step_y = {0.0f, 0.0f, 1.0f, 1.0f};
  const Quad4 gl_x = float(i) + step_x, gl_y = float(j) + step_y;  // exact: small integers
  const Quad4 px_center = gl_x + 0.5f, py_center = gl_y + 0.5f;
  lanes(b.frag_coord[0]) = px_center;
  lanes(b.frag_coord[1]) = py_center;
  // gl_FragCoord.z without the stored depth's fused multiply-adds (a library call on the baseline x86-64).
  lanes(b.frag_coord[2]) = r.za + r.zdx * gl_x + r.zdy * (float(height - 1 - j) - step_y);
  const uint32_t facing = r.front ? ~0u : 0u;
  for (int k = 0; k < 4; ++k) b.front_facing[l0 + k] = facing;
  if (r.constant) {
    lanes(b.frag_coord[3]) = Quad4{1.0f, 1.0f, 1.0f, 1.0f};
    for (int v = 0; v < n; ++v) lanes(b.varyings[v]) = data[v] + Quad4{};
    return;
  }
  const float* pc = data;
  const float* px = data + (n + 1);
  const float* py = data + ptrdiff_t(2) * (n + 1);
  const Quad4 dx = px_center - r.rx, dy = py_center - r.ry;
  const Quad4 inv_w = (pc[0] + py[0] * dy) + px[0] * dx;
  lanes(b.frag_coord[3]) = inv_w;
  const Quad4 w = 1.0f / inv_w;
  for (int v = 1; v <= n; ++v) lanes(b.varyings[v - 1]) = ((pc[v] + py[v] * dy) + px[v] * dx) * w;
}

/// Gathers the quads of record r over GL pixels [x0, x1) x [y0, y1) (inside the tile) into the batch, flushing it
/// when it is full or before a quad that covers a pixel a waiting lane covers.
template <DepthFunc F>
void gather_record(QuadTile& t, Framebuffer& fb, const SetupParams& params, bool depth_write,
                   const QuadFragmentShader& fs, const TriangleRecord& r, const float* data, int x0, int x1, int y0,
                   int y1) {
  const int height = fb.height();
  const int n = params.varying_count;
  TestSpan* const test_span = span_kernels().test[int(F)];
  for (int j = y0 & ~1; j < y1; j += 2) {
    int lo[2], hi[2];
    for (int k = 0; k < 2; ++k) {
      lo[k] = x0, hi[k] = x1;
      if (j + k < y0 || j + k >= y1)
        hi[k] = lo[k];
      else
        edge_span(r, j + k, lo[k], hi[k]);
    }
    const bool row_empty[2] = {lo[0] >= hi[0], lo[1] >= hi[1]};
    if (row_empty[0] && row_empty[1]) continue;
    const int first = (row_empty[0] ? lo[1] : row_empty[1] ? lo[0] : std::min(lo[0], lo[1])) & ~1;
    const int last = row_empty[0] ? hi[1] : row_empty[1] ? hi[0] : std::max(hi[0], hi[1]);
    // The 24-bit depths of each row's covered pixels (depth[k][i - lo[k]]), by the span kernel of the CPU's
    // instruction set: the depths draw_triangles stores. (Its outcomes are not used: a waiting quad may still change
    // the stored depths; the test below runs after the flush.)
    uint32_t depth[2][kTileSize];
    bool unused[kTileSize];
    for (int k = 0; k < 2; ++k)
      if (!row_empty[k]) {
        const int row = height - 1 - (j + k);
        test_span(fb.depth().row(row), lo[k], hi[k], r.za, r.zdx, r.zdy, float(row), depth[k], unused);
      }
    for (int i = first; i < last; i += 2) {
      uint32_t inside = 0;  // bit k: lane k's pixel center is in the triangle (and the tile)
      for (int k = 0; k < 4; ++k) {
        const int pi = i + (k & 1);
        if (pi >= lo[k >> 1] && pi < hi[k >> 1]) inside |= 1u << k;
      }
      if (!inside) continue;
      const int bx = i - t.origin_x, by = j - t.origin_y;
      const uint64_t row_bits[2] = {uint64_t(inside & 3) << bx, uint64_t((inside >> 2) & 3) << bx};
      if ((t.waiting[by] & row_bits[0]) || (by + 1 < kTileSize && (t.waiting[by + 1] & row_bits[1])))
        flush(t, fb, params, depth_write, fs);
      // The depth test, against depths that every earlier lane over these pixels has written (flushed above), and
      // the stencil test with its operations, applied now, in submission order, before the shader runs (as
      // draw_triangles: a discard does not undo them).
      uint32_t covered = 0;
      for (int k = 0; k < 4; ++k) {
        if (!(inside >> k & 1)) continue;
        const int pi = i + (k & 1), row = height - 1 - (j + (k >> 1));
        const bool depth_pass = depth_passes<F>(depth[k >> 1][pi - lo[k >> 1]], fb.depth()(pi, row));
        if (params.stencil_test ? stencil_and_depth(params.stencil[r.front], depth_pass, fb.stencil()(pi, row))
                                : depth_pass)
          covered |= 1u << k;
      }
      if (!covered) continue;
      if (t.batch.quads == kBatchQuads) flush(t, fb, params, depth_write, fs);
      const int q = t.batch.quads++;
      fill_quad(t.batch, q, r, data, n, i, j, height);
      for (int k = 0; k < 4; ++k) {
        t.batch.covered[4 * q + k] = (covered >> k & 1) ? ~0u : 0u;
        t.depth[4 * q + k] = (covered >> k & 1) ? depth[k >> 1][i + (k & 1) - lo[k >> 1]] : 0;
      }
      t.quad_i[q] = i, t.quad_j[q] = j;
      t.waiting[by] |= uint64_t(covered & 3) << bx;
      if (by + 1 < kTileSize) t.waiting[by + 1] |= uint64_t((covered >> 2) & 3) << bx;
    }
  }
}

/// The quads of every record binned to `tile`, in submission order.
template <DepthFunc F>
void raster_tile_quads(QuadTile& t, Framebuffer& fb, const SetupPass& binned, const SetupParams& params,
                       bool depth_write, int tile, const QuadFragmentShader& fs) {
  const int tx = tile % params.tiles_x, ty = tile / params.tiles_x;
  const Scissor sc = scissor(params);
  const int tile_x0 = std::max(sc.x0, tx * kTileSize), tile_x1 = std::min(sc.x1, tx * kTileSize + kTileSize);
  const int tile_y0 = std::max(sc.y0, ty * kTileSize), tile_y1 = std::min(sc.y1, ty * kTileSize + kTileSize);
  t.origin_x = tx * kTileSize, t.origin_y = ty * kTileSize;
  t.batch.varying_count = params.varying_count;
  std::memset(t.waiting, 0, sizeof t.waiting);
  bool any = false;
  for (const SetupChunk& chunk : binned) any = any || !chunk.bins[tile].empty();
  if (!any) return;
  prefetch_rows(fb, tile_x0, tile_x1, tile_y0, tile_y1);
  for (const SetupChunk& chunk : binned)
    for (const uint32_t index : chunk.bins[tile]) {
      const TriangleRecord& r = chunk.records[index];
      const int x0 = std::max(tile_x0, r.x0), x1 = std::min(tile_x1, r.x1);
      const int y0 = std::max(tile_y0, r.y0), y1 = std::min(tile_y1, r.y1);
      if (x0 >= x1 || y0 >= y1) continue;
      gather_record<F>(t, fb, params, depth_write, fs, r, chunk.varyings.data() + r.varyings, x0, x1, y0, y1);
    }
  flush(t, fb, params, depth_write, fs);
}

}  // namespace
}  // namespace detail

DrawStats draw_triangles_quads(Framebuffer& framebuffer, const RasterState& state, std::span<const float> vertices,
                               int varying_count, std::span<const uint32_t> indices, const QuadFragmentShader& fs) {
  if (varying_count < 0 || varying_count > FragmentBatch::kMaxVaryings)
    throw InvalidInput("the quad stage takes 0 to " + std::to_string(FragmentBatch::kMaxVaryings) + " varyings, not " +
                       std::to_string(varying_count));
  const size_t stride = 4 + size_t(varying_count);
  if (vertices.size() % stride != 0)
    throw InvalidInput("quad stage: " + std::to_string(vertices.size()) + " vertex floats are not a multiple of " +
                       std::to_string(stride) + " (4 + varyings)");
  const auto vertex_count = uint32_t(vertices.size() / stride);
  detail::check_draw(framebuffer, state, indices, vertex_count, 3, "triangle");
  detail::RasterScratch& scratch = framebuffer.scratch();
  scratch.input ^= 1;  // as draw_triangles_async: the previous draw's job may still read the other input set
  scratch.inputs[size_t(scratch.input)].vertices.assign(vertices.begin(), vertices.end());
  // The caller owns fs and this waits for the jobs: a shared pointer that owns nothing.
  DrawStats stats =
      detail::draw_staged_quads_async(framebuffer, state, vertex_count, varying_count, indices,
                                      std::shared_ptr<const QuadFragmentShader>(std::shared_ptr<void>(), &fs));
  stats.rasterized += detail::collect_raster(scratch);
  return stats;
}

namespace detail {

DrawStats draw_staged_quads_async(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                                  int varying_count, std::span<const uint32_t> indices,
                                  std::shared_ptr<const QuadFragmentShader> fs) {
  // varying_count is in range: draw_triangles_quads checks it, and run_vertex_stage asserts it (kMaxVaryings).
  static_assert(FragmentBatch::kMaxVaryings == kMaxVaryings);
  DrawStats stats;
  stats.primitives = indices.size() / 3;
  if (indices.empty()) return stats;
  // What the jobs share: the shader, and each thread's batch and shader scratch, made once per draw (not per range of
  // tiles) and not zeroed: every field is set before use.
  struct Shared {
    std::shared_ptr<const QuadFragmentShader> fs;
    tbb::enumerable_thread_specific<std::unique_ptr<QuadTile>> tiles;
  };
  const auto shared = std::make_shared<Shared>();
  shared->fs = std::move(fs);
  const auto raster = [&framebuffer, shared](const SetupPass& pass, const SetupParams& params,
                                             const FragmentState& fragment, int64_t begin, int64_t end) {
    const QuadFragmentShader& shader = *shared->fs;
    std::unique_ptr<QuadTile>& t = shared->tiles.local();
    if (!t) {
      t = std::make_unique_for_overwrite<QuadTile>();
      t->scratch = shader.begin();
    }
    dispatch_depth_func(fragment.func, [&](auto f) {
      for (int64_t tile = begin; tile < end; ++tile)
        raster_tile_quads<decltype(f)::value>(*t, framebuffer, pass, params, fragment.depth_write, int(tile), shader);
    });
  };
  stats.rasterized += submit_triangle_passes(framebuffer, state, vertex_count, varying_count, indices, raster);
  return stats;
}

}  // namespace detail
}  // namespace tessera::raster3d
