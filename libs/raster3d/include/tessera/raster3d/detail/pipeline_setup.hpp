#pragma once
// The pipeline's compiled half as its templates (pipeline_impl.hpp) see it: the records triangle setup produces and
// bins, the memory and raster thread a framebuffer keeps from draw to draw, and the functions raster3d's sources
// define for them: clipping, setup, binning and painter's order (src/pipeline_setup.cpp), the raster thread and
// pipeline_for (src/pipeline_schedule.cpp). Included by pipeline.hpp (through pipeline_impl.hpp), after its types.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "tessera/raster3d/framebuffer.hpp"

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
                           // fragment_depth(za, zdx, zdy, i, r) (src/span_kernels.hpp)
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

class RasterThread;     // the framebuffer's raster thread (pipeline_schedule.cpp)
struct PipelineArenas;  // the oneTBB arenas of pipeline_for (pipeline_schedule.cpp)

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
  int input = 0;                            // the current draw's set
  std::vector<uint32_t> order;              // painter's algorithm: the sorted triangle indices
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
  const float* vertices;                     // vertex stage output
  const PreparedVertex* prepared = nullptr;  // per vertex (prepare_vertices)
  int varying_count;                         // N
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

}  // namespace tessera::raster3d::detail
