#pragma once
// The OpenGL 1.x fixed-function pipeline of Mesa (OSMesa, llvmpipe on Debian 12) as a reference renderer for the
// raster3d tests and benchmarks. Never used by the library: the algorithms are Tessera's own, this is the peer they
// are compared with (docs/raster3d.md, /work/shared/spec/gl-raster-conventions.md).
//
// Images come back top-row-first like every Tessera image (GL's row 0 is the bottom: rows are flipped on read).
#include <cstdint>
#include <memory>
#include <vector>

#include "tessera/math/types.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera::reference {

/// How the triangles reach OpenGL.
enum class GlSubmit {
  immediate,      ///< glBegin(GL_TRIANGLES) / glNormal / glColor / glVertex / glEnd
  vertex_arrays,  ///< glVertexPointer / glNormalPointer / glColorPointer + glDrawElements
};

/// GL_LIGHT0's parameters (glLightfv). position.w = 0: a directional light toward position.xyz; w = 1: a point light.
/// The position is given in eye space (it is loaded with an identity model-view).
struct GlLight {
  Vec4f position{0, 0, 1, 0};
  Vec4f ambient{0, 0, 0, 1};
  Vec4f diffuse{1, 1, 1, 1};
  Vec4f specular{1, 1, 1, 1};
};

/// glMaterialfv(GL_FRONT_AND_BACK, ...): the defaults are OpenGL's.
struct GlMaterial {
  Vec4f ambient{0.2f, 0.2f, 0.2f, 1};
  Vec4f diffuse{0.8f, 0.8f, 0.8f, 1};
  Vec4f specular{0, 0, 0, 1};
  Vec4f emission{0, 0, 0, 1};
  float shininess = 0;
};

/// GL_TEXTURE_2D's filters (GL_TEXTURE_MIN_FILTER; magnification is GL_NEAREST for nearest, else GL_LINEAR).
enum class GlFilter { nearest, linear, linear_mipmap_linear };

/// An RGBA8 texture (rows bottom first, as glTexImage2D takes them), drawn with GL_REPLACE and GL_REPEAT; mipmaps
/// are built by OpenGL (GL_GENERATE_MIPMAP) for linear_mipmap_linear.
struct GlTexture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  ///< 4 bytes per texel
  GlFilter filter = GlFilter::nearest;
};

/// A comparison (glDepthFunc, glStencilFuncSeparate): raster3d::DepthFunc's values, in its order.
enum class GlCompare { never, less, equal, lequal, greater, notequal, gequal, always };

/// What a stencil test outcome does to the stored value (glStencilOpSeparate): raster3d::StencilOp's values, in its
/// order.
enum class GlStencilOp { keep, zero, replace, incr, incr_wrap, decr, decr_wrap, invert };

/// The stencil state of one face orientation (glStencilFuncSeparate + glStencilOpSeparate + glStencilMaskSeparate):
/// raster3d::StencilFace's fields, OpenGL's defaults.
struct GlStencilFace {
  GlCompare func = GlCompare::always;
  uint8_t ref = 0, mask = 0xff, write_mask = 0xff;
  GlStencilOp fail = GlStencilOp::keep, zfail = GlStencilOp::keep, zpass = GlStencilOp::keep;
};

/// A blend factor (glBlendFunc): raster3d::BlendFactor's values, in its order.
enum class GlBlendFactor {
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

/// glBlendEquation: raster3d::BlendEquation's values, in its order.
enum class GlBlendEquation { add, subtract, reverse_subtract, min, max };

/// The fixed-function state of one drawing.
struct GlState {
  Mat4f projection{1.0f};  ///< loaded with glMatrixMode(GL_PROJECTION) + glLoadMatrixf
  Mat4f modelview{1.0f};   ///< loaded with glMatrixMode(GL_MODELVIEW) + glLoadMatrixf
  bool lighting = false;   ///< GL_LIGHTING with GL_LIGHT0; off: the flat color (or per-vertex colors) unlit
  GlLight light;
  GlMaterial material;
  bool smooth = true;      ///< glShadeModel(GL_SMOOTH), else GL_FLAT (the last vertex of a triangle colors it)
  bool cull_back = false;  ///< glEnable(GL_CULL_FACE) with glCullFace(GL_BACK), front faces counterclockwise
  bool depth_test = true;  ///< GL_DEPTH_TEST with glDepthFunc(depth_func)
  GlCompare depth_func = GlCompare::less;
  bool depth_write = true;      ///< glDepthMask
  bool color_write = true;      ///< glColorMask (all four channels on or off)
  bool stencil_test = false;    ///< GL_STENCIL_TEST
  GlStencilFace stencil_front;  ///< GL_FRONT's stencil state (counterclockwise faces, lines, points)
  GlStencilFace stencil_back;   ///< GL_BACK's
  Vec3f color{1, 1, 1};         ///< glColor4f(color, alpha) when unlit and the mesh has no colors
  float alpha = 1;
  bool blend = false;  ///< GL_BLEND with glBlendFunc(blend_src, blend_dst), glBlendEquation(blend_equation)
  GlBlendFactor blend_src = GlBlendFactor::one, blend_dst = GlBlendFactor::zero;
  GlBlendEquation blend_equation = GlBlendEquation::add;
  Vec3f background{0, 0, 0};
  uint8_t clear_stencil = 0;  ///< glClearStencil
  bool clear = true;  ///< clear color, depth (to 1.0) and stencil (to clear_stencil) before drawing, all write masks on
  const GlTexture* texture = nullptr;  ///< GL_TEXTURE_2D with GL_REPLACE (the texel is the color), or off
};

/// A mesh in OpenGL's float arrays (converted once from a TriMesh, so that drawing measures only OpenGL).
struct GlMesh {
  std::vector<float> positions;  ///< 3 per vertex
  std::vector<float> normals;    ///< 3 per vertex, or empty
  std::vector<float> colors;     ///< color_size per vertex, or empty
  int color_size = 3;            ///< 3 (RGB) or 4 (RGBA)
  std::vector<float> texcoords;  ///< 2 per vertex, or empty
  std::vector<uint32_t> indices;

  /// The mesh's positions, and its normals, colors and texture coordinates when it has them, as float32 arrays.
  explicit GlMesh(const TriMesh& mesh);
  size_t triangle_count() const { return indices.size() / 3; }
};

/// What OpenGL drew, top row first.
struct GlFrame {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;      ///< 3 bytes per pixel
  std::vector<uint8_t> alpha;    ///< 1 byte per pixel
  std::vector<uint32_t> depth;   ///< 24-bit depth per pixel (2^24 - 1 = cleared / far)
  std::vector<uint8_t> stencil;  ///< 8-bit stencil value per pixel

  uint8_t channel(int x, int y, int c) const { return rgb[(size_t(y) * size_t(width) + size_t(x)) * 3 + size_t(c)]; }
  uint8_t alpha_at(int x, int y) const { return alpha[size_t(y) * size_t(width) + size_t(x)]; }
  uint32_t depth_at(int x, int y) const { return depth[size_t(y) * size_t(width) + size_t(x)]; }
  uint8_t stencil_at(int x, int y) const { return stencil[size_t(y) * size_t(width) + size_t(x)]; }
};

/// An OSMesa context with an RGBA color buffer, a 24-bit depth buffer and an 8-bit stencil buffer, current on the
/// calling thread while it lives. llvmpipe reads LP_NUM_THREADS once per process, when the first context is created:
/// `rasterizer_threads` (>= 0; 0 rasterizes on the calling thread) is only honoured by the process's first context,
/// later ones keep that first value (rasterizer_threads() says which). Throws tessera::Error when OSMesa cannot create
/// the context.
class OsmesaContext {
 public:
  OsmesaContext(int width, int height, int rasterizer_threads = -1);  ///< -1: leave LP_NUM_THREADS as it is
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  /// The LP_NUM_THREADS value in force when the process's first context was created (-1: unset, llvmpipe's default).
  static int rasterizer_threads();

  /// Sets the fixed-function state (matrices, lighting, material, shade model, culling, depth and stencil tests,
  /// write masks) and clears when state.clear is set. A later begin with clear off draws over the same buffers.
  void begin(const GlState& state);
  /// Draws the mesh's triangles with the current state.
  void draw(const GlMesh& mesh, GlSubmit submit);
  /// glFinish: returns when every drawing has reached the framebuffer.
  void finish();
  /// Reads color, depth and stencil back (after glFinish), flipped to top-row-first.
  GlFrame read() const;

 private:
  int width_, height_;
  std::vector<uint8_t> buffer_;  // OSMesa's RGBA color buffer
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Convenience: one drawing in a fresh context. Throws tessera::Error when OSMesa fails.
GlFrame render_osmesa(const TriMesh& mesh, int width, int height, const GlState& state,
                      GlSubmit submit = GlSubmit::vertex_arrays);

}  // namespace tessera::reference
