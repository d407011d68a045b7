#pragma once
// raster3d::Context: the state of an OpenGL 1.x-like pipeline, owned by one object (two contexts never interfere):
// projection and model-view matrix stacks, current color/normal/texcoord, lights, material, depth/cull/shading
// state, the hidden-surface method, and the Framebuffer. Immediate mode (begin/vertex/end) buffers vertices into a
// batch that is drawn through the same path as draw(mesh) when the state changes or the frame is read.
//
// Drawing is pipelined as llvmpipe's: the calling thread runs the vertex stage, clipping, setup and binning of a
// batch (or of a draw's pass of triangles) and hands its tile rasterization to the framebuffer's raster thread, then
// returns to collect the next batch while the tiles are drawn. Batches are rasterized one at a time in submission
// order, each with the state it was specified under, so the pixels are those of drawing synchronously. Reading the
// framebuffer, clearing and swapping wait for the raster thread (flush()).
//
// The gt layer (gt.hpp) is a thin set of the notes' functions over the current Context.
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

#include "tessera/math/matrix_stack.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/raster3d/framebuffer.hpp"
#include "tessera/raster3d/lighting.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d {

/// OpenGL's primitive kinds for begin(). Triangles made from strips, fans, quads and polygons keep OpenGL's provoking
/// vertex (the last of each triangle, the last of each quad, the first of a polygon).
enum class Primitive { points, lines, line_strip, line_loop, triangles, triangle_strip, triangle_fan, quads, polygon };

/// Which matrix stack the matrix calls change (glMatrixMode).
enum class MatrixMode { projection, model_view };

/// How hidden surfaces are removed: the z-buffer, or the painter's algorithm (each draw's triangles sorted by
/// average depth and drawn far to near; a batch of immediate-mode shapes is one draw).
enum class HiddenSurface { zbuffer, painter };

/// Float copies of a mesh's arrays, ready for the pipeline (build once, draw many times).
struct VertexArrays {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;     ///< per vertex, or empty (the current normal)
  std::vector<Vec3f> colors;      ///< per vertex, or empty (the current color)
  std::vector<Vec2f> uvs;         ///< per vertex, or empty
  std::vector<uint32_t> indices;  ///< 3 per triangle

  /// The arrays of `mesh` in float. Throws InvalidInput when an attribute array's size differs from the positions'.
  static VertexArrays from_mesh(const TriMesh& mesh);
  /// The attribute pointers the shaders read.
  VertexAttributes attributes() const;
};

/// Reorders the triangles of `arrays` far to near as seen through `model_view` (by their centroids' eye-space z;
/// ties keep their order), so that blending each over what was drawn before gives order-dependent transparency.
/// Exact where the triangles' depth ranges do not interleave, as for the painter's algorithm.
void sort_back_to_front(VertexArrays& arrays, const Mat4& model_view);

/// What a program reads of a context's state: OpenGL binds the compatibility built-ins (gl_ModelViewMatrix,
/// gl_LightSource[i], gl_FrontMaterial, gl_LightModel) and the current attributes from it.
struct ProgramState {
  Mat4f model_view{1.0f}, projection{1.0f};
  Lighting lighting;                        ///< the material, the light model and all lights (eye space)
  std::array<bool, kMaxLights> light_on{};  ///< which lights are on (GL_LIGHTi)
  Vec3f color{1, 1, 1}, normal{0, 0, 1};    ///< the current color and normal
  Vec2f uv{0, 0};                           ///< the current texture coordinates
  float alpha = 1;                          ///< the current color's alpha
};

/// A program a context draws its triangles through instead of its fixed-function shaders (glUseProgram):
/// glsl::Program is one (libs/glsl). raster3d knows only this interface, so that it does not depend on the GLSL
/// compiler.
class ContextProgram {
 public:
  virtual ~ContextProgram() = default;
  /// Draws the triangles `indices` of `attributes` (vertex_count vertices) into `framebuffer` with `state`, the
  /// built-ins bound from `program_state`; done when it returns.
  virtual DrawStats draw_arrays(Framebuffer& framebuffer, const RasterState& state, const ProgramState& program_state,
                                const VertexAttributes& attributes, uint32_t vertex_count,
                                std::span<const uint32_t> indices) = 0;
};

/// An OpenGL 1.x-style rendering context with its own framebuffer.
class Context {
  struct DrawShaders;

 public:
  /// A context drawing into a width x height framebuffer (cleared black, depth 1), identity matrices, GL defaults:
  /// depth test on with `less`, no culling, Gouraud shading with lighting off (unlit), GL_LIGHT0 on.
  Context(int width, int height);
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Resizes (a new cleared framebuffer) and resets all state to the defaults.
  void initialize(int width, int height);

  /// The framebuffer, after drawing everything pending (flush()). Read it before the next drawing call: later
  /// drawing goes on on the raster thread.
  Framebuffer& framebuffer();
  /// Draws everything pending and waits until it is in the framebuffer (glFinish): the immediate-mode batch, and the
  /// rasterization still running on the raster thread. (State changes hand the batch over without waiting.)
  void flush();
  /// flush(), then presents the back buffer (Framebuffer::swap).
  void swap_buffers();
  /// Clears the color buffer to `color` and the depth buffer to 1.0 (after flush()).
  void clear(const Vec3f& color);

  // ---- Matrices (CTM = CTM * T: the call written last acts first) ----
  /// Selects the stack the matrix calls below change.
  void matrix_mode(MatrixMode mode);
  /// Duplicates the top of the current stack (glPushMatrix).
  void push_matrix();
  /// Discards the top of the current stack (glPopMatrix). Throws InvalidInput on underflow.
  void pop_matrix();
  /// Replaces the current matrix with the identity, with m, or with current * m.
  void load_identity();
  void load_matrix(const Mat4& m);
  void mult_matrix(const Mat4& m);
  /// current = current * translate(x, y, z) (math/transform.hpp), and likewise for scale and the rotations.
  void translate(double x, double y, double z);
  void scale(double x, double y, double z);
  /// Rotations in radians, counterclockwise looking down the axis toward the origin.
  void rotate_x(double angle);
  void rotate_y(double angle);
  void rotate_z(double angle);
  void rotate(double angle, const Vec3& axis);
  /// Multiplies the model-view matrix by the view matrix look_at(eye, center, up) (the notes' camera()).
  void look_at(const Vec3& eye, const Vec3& center, const Vec3& up);
  /// Replaces the projection matrix with ortho(l, r, b, t, n, f).
  void ortho(double l, double r, double b, double t, double n, double f);
  /// Replaces the projection matrix with perspective(fovy, aspect, n, f); aspect <= 0 uses the viewport's.
  void perspective(double fovy, double n, double f, double aspect = 0);
  /// The top of the projection and model-view stacks.
  const Mat4& projection() const { return projection_.top(); }
  const Mat4& model_view() const { return model_view_.top(); }

  // ---- Current attributes (glColor, glNormal, glTexCoord): given to the vertices that follow ----
  void color(const Vec3f& c) {
    if (std::memcmp(&c, &current_color_, sizeof c) != 0) new_cache_epoch();
    current_color_ = c;
  }
  void normal(const Vec3f& n) { current_normal_ = n; }
  void texcoord(const Vec2f& uv) {
    if (std::memcmp(&uv, &current_uv_, sizeof uv) != 0) new_cache_epoch();
    current_uv_ = uv;
  }

  // ---- State ----
  /// glViewport, in window coordinates (origin bottom-left); a zero size is the whole framebuffer.
  void viewport(int x, int y, int width, int height);
  /// GL_DEPTH_TEST, glDepthFunc, glDepthMask, glCullFace (RasterState).
  void depth_test(bool on);
  void depth_func(DepthFunc func);
  void depth_write(bool on);
  void cull(CullMode mode);
  /// glColorMask (all channels), GL_STENCIL_TEST, and the stencil state of front and back faces
  /// (glStencilFuncSeparate, glStencilOpSeparate, glStencilMaskSeparate; RasterState).
  void color_write(bool on);
  void stencil_test(bool on);
  void stencil(const StencilFace& front, const StencilFace& back);
  /// Clears the stencil buffer to `value` (after flush()).
  void clear_stencil(uint8_t value = 0);
  /// GL_BLEND, and glBlendFunc + glBlendEquation (RasterState::blend_function).
  void blend(bool on);
  void blend_function(const BlendFunction& f);
  /// The alpha of what the context draws (1, opaque, by default): glColor4's alpha when unlit, the diffuse material's
  /// alpha when lit; the opacity that blending reads.
  void alpha(float a);
  /// Where lighting is evaluated (unlit = lighting off); flat also selects OpenGL's flat shade model.
  void shading(ShadingModel model);
  ShadingModel shading() const { return shading_; }
  /// The z-buffer or the painter's algorithm.
  void hidden_surface(HiddenSurface method);
  /// Draws the triangles that follow (meshes and immediate mode) through `program`, or again through the
  /// fixed-function shaders when it is null (glUseProgram). Lines and points keep the fixed-function shaders.
  void use_program(std::shared_ptr<ContextProgram> program);
  /// glMaterial (front and back), the specular term, GL_LIGHT_MODEL_AMBIENT, GL_COLOR_MATERIAL.
  void material(const Material& m);
  void specular_model(SpecularModel model);
  void light_model_ambient(const Vec3f& ambient);
  void color_material(bool on);
  /// Sets light i (0..7); its position is transformed by the current model-view matrix, as glLight. Throws
  /// InvalidInput for i outside [0, kMaxLights).
  void light(int i, const Light& light);
  /// Turns light i on or off (GL_LIGHTi). Light 0 is on by default.
  void enable_light(int i, bool on);

  // ---- Immediate mode ----
  /// glBegin. Throws InvalidInput when a primitive is already open.
  void begin(Primitive kind);
  /// glVertex: a vertex with the current normal, color and texcoord. Throws InvalidInput outside begin/end.
  /// Inline: the common case appends to the open shape; a full batch or misuse takes the out-of-line path.
  void vertex(double x, double y, double z) {
    if (!in_shape_ || batch_references_ >= kBatchVertices) [[unlikely]] {
      vertex_slow_path(x, y, z);
      return;
    }
    shape_target_->push_back(batch_vertex(Vec3f(x, y, z)));
    ++batch_references_;
  }
  /// glEnd: assembles the primitive (an incomplete last triangle/line is dropped). Throws InvalidInput without begin.
  void end();

  // ---- Batched ----
  /// Draws the mesh's triangles with the current matrices, material, lights and state (normals/colors absent in the
  /// mesh are the current ones).
  void draw(const TriMesh& mesh);
  /// The same from float arrays prepared once.
  void draw(const VertexArrays& arrays);
  /// Draws line segments between vertices of `arrays`, two indices into them a segment (glDrawElements with
  /// GL_LINES; `arrays.indices` is not read), in the current state. Throws InvalidInput for an odd count or an index
  /// out of range.
  void draw_lines(const VertexArrays& arrays, std::span<const uint32_t> lines);
  /// Draws the edges of the mesh's triangles as lines (each shared edge once).
  void draw_wireframe(const TriMesh& mesh);

  /// Totals since the last initialize(); `rasterized` is complete once flush() or framebuffer() has returned.
  const DrawStats& stats() const { return stats_; }

 private:
  void draw_triangle_arrays(const VertexAttributes& attributes, uint32_t vertex_count,
                            std::span<const uint32_t> indices);
  void draw_line_arrays(const VertexAttributes& attributes, uint32_t vertex_count, std::span<const uint32_t> indices);
  void draw_point_arrays(const VertexAttributes& attributes, uint32_t vertex_count, std::span<const uint32_t> indices);
  FixedFunctionUniforms uniforms() const;
  RasterState raster_state() const;
  MatrixStack3& current_stack();
  void assemble_shape();
  void submit_batch();
  void draw_batch();
  void vertex_slow_path(double x, double y, double z);
  void new_cache_epoch();
  uint32_t add_batch_vertex(const Vec3f& position, uint32_t slot);

  // Immediate-mode batches are drawn once they hold this many vertex references (or on any state change): one
  // setup pass of independent triangles, small enough to stay in cache.
  static constexpr size_t kBatchVertices = 3 * size_t(detail::kChunkTriangles) * detail::kPassChunks;
  // Slots of the direct-mapped cache of recent immediate-mode vertices (a power of two): enough to hold two rows of
  // a finely tessellated grid, small enough to stay in L2.
  static constexpr int kVertexCacheBits = 13;

  // A cached vertex: its batch index and the epoch it was stored in (4 bytes, so the 8192-slot table fits in L1: at
  // 8 bytes its lookup was a sixth of the per-vertex samples). The key, the position and normal bits, is compared
  // in the batch arrays, where a recent vertex is still in cache. Within an epoch the batch is not drawn and the
  // current color and texcoord do not change, so equal keys of the same epoch mean bit-identical attributes.
  // Vertices past index 65535 (a long strip or fan, the only shapes a batch does not cut) are not cached.
  struct CachedVertex {
    uint16_t index = 0, epoch = 0;
  };
  static_assert(kBatchVertices <= 0x10000, "a batch of independent primitives is indexed by CachedVertex::index");

  // Fibonacci hashing of a vertex's position and normal (the attributes that tell vertices of a mesh apart), as two
  // independent multiply chains joined at the end: the top bits index the cache.
  static uint32_t attribute_hash(const Vec3f& position, const Vec3f& normal) {
    uint32_t p[3], n[3];
    std::memcpy(p, &position, sizeof p);
    std::memcpy(n, &normal, sizeof n);
    uint32_t hp = 0, hn = 0x7F4A7C15u;
    for (int k = 0; k < 3; ++k) {
      hp = (hp ^ p[k]) * 0x9E3779B1u;
      hn = (hn ^ n[k]) * 0x85EBCA77u;
    }
    return ((hp ^ (hn >> 7) ^ (hn << 25)) * 0xC2B2AE3Du) >> (32 - kVertexCacheBits);
  }

  // The batch index of a vertex with these attributes: a recent equal one (bit for bit, so the vertex shader, a pure
  // function of them, gives the same output) or a new one.
  uint32_t batch_vertex(const Vec3f& position) {
    const uint32_t slot = attribute_hash(position, current_normal_);
    const CachedVertex c = vertex_cache_[slot];
    if (c.epoch == cache_epoch_ && std::memcmp(&batch_.positions[c.index], &position, sizeof position) == 0 &&
        std::memcmp(&batch_.normals[c.index], &current_normal_, sizeof current_normal_) == 0)
      return c.index;
    return add_batch_vertex(position, slot);
  }

  Framebuffer framebuffer_;
  MatrixStack3 projection_, model_view_;
  MatrixMode matrix_mode_ = MatrixMode::model_view;
  Vec3f current_color_{1, 1, 1}, current_normal_{0, 0, 1};
  Vec2f current_uv_{0, 0};
  RasterState state_;
  ShadingModel shading_ = ShadingModel::unlit;
  float alpha_ = 1;
  std::shared_ptr<ContextProgram> program_;  // use_program's, or null
  HiddenSurface hidden_surface_ = HiddenSurface::zbuffer;
  Lighting lighting_;
  std::array<Light, kMaxLights> lights_{};
  std::array<bool, kMaxLights> light_on_{};
  DrawStats stats_;

  // Immediate mode: the open shape's vertices, and the batch of assembled primitives waiting to be drawn.
  bool in_shape_ = false;
  Primitive shape_kind_ = Primitive::triangles;
  // The open shape's vertices, as indices into batch_, are appended to *shape_target_ from shape_begin_ on:
  // shape_vertices_, or for GT_TRIANGLES directly the batch's triangle indices.
  std::vector<uint32_t> shape_vertices_;
  std::vector<uint32_t>* shape_target_ = &shape_vertices_;
  size_t shape_begin_ = 0;
  size_t batch_references_ = 0;  // vertex() calls since the batch was last drawn
  VertexArrays batch_;
  std::vector<uint32_t> batch_lines_, batch_points_;
  // Recent vertices by hash of their attributes: a repeated vertex (a mesh sent as independent triangles) is stored
  // and shaded once per batch. Entries of an older epoch are stale.
  std::vector<CachedVertex> vertex_cache_;
  uint16_t cache_epoch_ = 1;
};

}  // namespace tessera::raster3d
