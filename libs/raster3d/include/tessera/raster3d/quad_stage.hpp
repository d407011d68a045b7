#pragma once
// The quad fragment stage: fragments shaded in batches of 2 x 2 quads, structure of arrays, for shaders that run many
// pixels at once (SIMD lanes) and take screen-space derivatives as a GPU does, by differences within a quad (GLSL's
// dFdx, dFdy and the implicit level of detail of texture()). The GLSL executor (libs/glsl) runs on it.
//
// The vertex stage has already run (the caller gives its output: per vertex the clip position, then the varyings);
// clipping, setup, binning and the tie rule are the pipeline's (pipeline.hpp), so coverage and 24-bit depth are the
// same as draw_triangles', pixel for pixel. Each 64 x 64 tile gathers the quads of its triangles, in submission order,
// into batches: a quad joins the batch when one of its pixels is covered and passes the depth test (and the stencil
// test); its other pixels are helper lanes (computed, never written), as on a GPU. A batch is shaded when it is full,
// at the tile's end, or before a quad that touches a pixel a waiting quad covers, so that the depth test, the writes
// and blending see the earlier triangles' results, as in OpenGL's order.
#include <cstdint>
#include <memory>
#include <span>

#include "tessera/raster3d/framebuffer.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d {

/// One batch of quads: what a QuadFragmentShader reads and writes. Lane 4q + k is pixel k of quad q: k = 0 at GL
/// pixel (i, j) (even i and j, y up), 1 at (i + 1, j), 2 at (i, j + 1), 3 at (i + 1, j + 1). So dFdx of a lane is
/// the difference of lanes 4q + 1 - 4q (row j) or 4q + 3 - 4q + 2 (row j + 1), and dFdy of 4q + 2 - 4q or
/// 4q + 3 - 4q + 1.
struct FragmentBatch {
  static constexpr int kLanes = 64;  ///< 16 quads
  static constexpr int kMaxVaryings = 32;

  int quads = 0;          ///< lanes [0, 4 quads) are in use
  int varying_count = 0;  ///< N
  /// Varying k of lane l at varyings[k][l]: interpolated perspective-correctly at the pixel center (helper lanes
  /// too: the planes extended beyond the triangle), or the provoking vertex's for flat shading.
  alignas(64) float varyings[kMaxVaryings][kLanes];
  /// gl_FragCoord: window x and y of the pixel center, window depth z in [0, 1], and 1/w.
  alignas(64) float frag_coord[4][kLanes];
  /// gl_FrontFacing: all-ones on lanes of counterclockwise triangles, 0 otherwise.
  alignas(64) uint32_t front_facing[kLanes];
  /// Whether the lane's pixel is covered and passed the tests (0 or all-ones): helper lanes are 0.
  alignas(64) uint32_t covered[kLanes];
  /// Outputs. The stage sets every lane of `kept` to all-ones before shading; the shader clears the lanes it
  /// discards and writes `color` (RGBA, clamped to [0, 1] when stored) of the lanes it keeps.
  alignas(64) float color[4][kLanes];
  alignas(64) uint32_t kept[kLanes];
};

/// Per-thread working memory of a QuadFragmentShader (its registers, say): made once per tile task by begin().
class QuadShaderScratch {
 public:
  virtual ~QuadShaderScratch() = default;
};

/// A fragment shader of the quad stage. shade() is called from several threads at once, each with its own batch and
/// scratch: it must not change the shader.
class QuadFragmentShader {
 public:
  virtual ~QuadFragmentShader() = default;
  /// Working memory for one thread's batches (prepared with the draw's uniforms).
  virtual std::unique_ptr<QuadShaderScratch> begin() const = 0;
  /// Shades `batch` (see FragmentBatch for what it reads and writes).
  virtual void shade(FragmentBatch& batch, QuadShaderScratch& scratch) const = 0;
};

/// Draws the triangles `indices` (3 per triangle) of the vertices `vertices`, which hold per vertex the clip-space
/// position (4 floats) then `varying_count` floats (at most FragmentBatch::kMaxVaryings), through `fs` on the quad
/// stage. State as draw_triangles (depth, stencil, culling, flat, color mask, blending; the painter's algorithm).
/// Throws InvalidInput as draw_triangles, or when vertices.size() is not a multiple of 4 + varying_count.
DrawStats draw_triangles_quads(Framebuffer& framebuffer, const RasterState& state, std::span<const float> vertices,
                               int varying_count, std::span<const uint32_t> indices, const QuadFragmentShader& fs);

namespace detail {
/// draw_triangles_quads for vertices already in the framebuffer's current draw input (its vertex stage has run, as
/// in draw_triangles; the caller has checked the draw), returning before the raster thread is done with the last
/// pass (as draw_triangles_async; collect_raster waits): the jobs hold `fs` until they are done.
DrawStats draw_staged_quads_async(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                                  int varying_count, std::span<const uint32_t> indices,
                                  std::shared_ptr<const QuadFragmentShader> fs);
}  // namespace detail

}  // namespace tessera::raster3d
