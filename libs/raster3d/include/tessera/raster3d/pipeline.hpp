#pragma once
// The 3D pipeline as free function templates over a vertex shader and a fragment shader (shaders.hpp):
// vertex stage -> primitive assembly -> clipping in homogeneous clip space (all six planes, Sutherland-Hodgman) ->
// perspective divide -> viewport -> 1/256-pixel snapping -> integer edge functions with the tie rule -> stencil test
// (when on) -> depth test -> fragment shader -> blending (when on) -> 8-bit color write. The stencil operations are
// applied by the tests' outcome, before the fragment shader (as GLSL's early_fragment_tests): a discard does not undo
// them. The rules are gl-raster-conventions.md's (Mesa's), so the output compares with OpenGL pixel for pixel.
//
// Triangles are binned to 64 x 64 screen tiles and the tiles rasterized in parallel (oneTBB), each in submission order,
// so the output is identical for any thread count. The shaders are called from several threads at once: they must be
// callable concurrently through a const reference (uniforms are read-only members).
#include <cstdint>
#include <span>

#include "tessera/raster3d/framebuffer.hpp"
#include "tessera/raster3d/shaders.hpp"

namespace tessera::raster3d {

/// The depth comparison (glDepthFunc): a fragment passes when `fragment OP stored` holds.
enum class DepthFunc { never, less, equal, lequal, greater, notequal, gequal, always };

/// Which faces are discarded before rasterization (glCullFace); the front face is counterclockwise on screen.
enum class CullMode { none, back, front };

/// What a stencil test outcome does to the stored stencil value (glStencilOp). The wrapping forms go 255 -> 0 and
/// 0 -> 255; incr and decr clamp.
enum class StencilOp { keep, zero, replace, incr, incr_wrap, decr, decr_wrap, invert };

/// The stencil state of one face orientation (glStencilFuncSeparate + glStencilOpSeparate + glStencilMaskSeparate).
/// The test passes when `(ref & mask) func (stored & mask)`; a fragment that fails it is dropped after `fail`; one
/// that passes it is then depth-tested: `zfail` when the depth test fails, `zpass` when it passes (or is off). The new
/// value is written where `write_mask` has bits.
struct StencilFace {
  DepthFunc func = DepthFunc::always;
  uint8_t ref = 0, mask = 0xff, write_mask = 0xff;
  StencilOp fail = StencilOp::keep, zfail = StencilOp::keep, zpass = StencilOp::keep;
};

/// A blend factor (glBlendFunc): what the source (the fragment's color, clamped to [0, 1]) or the destination (the
/// stored color) is multiplied by, channel by channel.
enum class BlendFactor {
  zero,
  one,
  src_color,
  one_minus_src_color,
  dst_color,
  one_minus_dst_color,
  src_alpha,
  one_minus_src_alpha,
  dst_alpha,
  one_minus_dst_alpha,
};

/// How the weighted source and destination combine (glBlendEquation); min and max ignore the factors.
enum class BlendEquation { add, subtract, reverse_subtract, min, max };

/// The blend function (glBlendFunc + glBlendEquation), for color and alpha alike: with source S and destination D in
/// [0, 1], add stores S src + D dst, subtract S src - D dst, reverse_subtract D dst - S src, clamped to [0, 1] and
/// rounded to 8 bits. The default (one, zero, add) stores the source, as with blending off. Transparency "over" what
/// was drawn before is (src_alpha, one_minus_src_alpha); adding light is (one, one).
struct BlendFunction {
  BlendFactor src = BlendFactor::one, dst = BlendFactor::zero;
  BlendEquation equation = BlendEquation::add;
};

/// The viewport (glViewport) in OpenGL window coordinates: origin at the bottom-left pixel, y up.
/// A zero width or height means the whole framebuffer.
struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;
};

/// Per-draw fixed state of the rasterizer.
struct RasterState {
  Viewport viewport;
  bool depth_test = true;  ///< compare with the depth buffer (GL_DEPTH_TEST)
  DepthFunc depth_func = DepthFunc::less;
  bool depth_write = true;  ///< store the depth of passing fragments (glDepthMask)
  CullMode cull = CullMode::none;
  bool flat = false;          ///< varyings are the last vertex's, not interpolated (GL_FLAT)
  bool painter = false;       ///< the painter's algorithm: sort by average depth, draw far to near, no
                              ///< depth test or write (the notes' alternative to the z-buffer)
  bool color_write = true;    ///< store the fragment shader's color (glColorMask)
  bool stencil_test = false;  ///< the stencil test and its operations (GL_STENCIL_TEST)
  StencilFace stencil_front;  ///< for front faces (counterclockwise on screen), lines and points
  StencilFace stencil_back;   ///< for back faces
  bool blend = false;         ///< combine the fragment's color with the stored one by `blend_function` (GL_BLEND)
  BlendFunction blend_function;
};

/// What a draw did, for statistics.
struct DrawStats {
  uint64_t primitives = 0;  ///< triangles (lines, points) submitted
  uint64_t rasterized = 0;  ///< after culling and clipping (a clipped triangle can become several)
};

/// Draws the triangles `indices` (3 per triangle, counterclockwise = front) of vertices [0, vertex_count), each
/// vertex shaded once by `vs`, each covered pixel center by `fs` (after the depth test). The last vertex of each
/// triangle is the provoking vertex for state.flat. Throws InvalidInput when indices.size() is not a multiple of 3 or
/// an index is >= vertex_count.
template <VertexShader VS, FragmentShader<VaryingsOf<VS>> FS>
DrawStats draw_triangles(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                         std::span<const uint32_t> indices, const VS& vs, const FS& fs);

/// Draws the line segments `indices` (2 per line, 1 pixel wide; OpenGL's diamond-exit rule, approximately: x-major
/// lines cover one pixel per column whose center lies in [start, end), y-major lines one per row). Clipped against
/// all six planes; the depth is interpolated linearly in window space, varyings perspective-correctly; flat takes
/// the second vertex. Lines are drawn in order on the calling thread.
template <VertexShader VS, FragmentShader<VaryingsOf<VS>> FS>
DrawStats draw_lines(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                     std::span<const uint32_t> indices, const VS& vs, const FS& fs);

/// Draws each index as a 1-pixel point: the pixel containing its window position (points outside the clip volume
/// are dropped).
template <VertexShader VS, FragmentShader<VaryingsOf<VS>> FS>
DrawStats draw_points(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                      std::span<const uint32_t> indices, const VS& vs, const FS& fs);

}  // namespace tessera::raster3d

#include "tessera/raster3d/detail/pipeline_impl.hpp"
