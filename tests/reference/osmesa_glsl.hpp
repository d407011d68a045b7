#pragma once
// GLSL programs on Mesa (OSMesa, llvmpipe on Debian 12) as the reference renderer of the GLSL tests and benchmarks.
// Never used by the library: the glsl module compiles and runs shaders itself; this is the peer it is compared with.
//
// The context is a compatibility profile (Mesa 22.3 gives OpenGL 4.5 compatibility, GLSL 4.50), so both the notes'
// dialect (no #version or #version 110/120: gl_Vertex, gl_ModelViewProjectionMatrix, gl_LightSource[i], ftransform,
// texture2D, gl_TexCoord[], gl_FragColor) and modern GLSL (#version 330 and later: in/out, layout(location),
// texture(), a user `out vec4`) compile. Vertex data is drawn from client arrays with glDrawElements. llvmpipe's
// thread count is its own (LP_NUM_THREADS, read once per process; this file never sets it).
//
// Images come back top-row-first like every Tessera image (GL's row 0 is the bottom: rows are flipped on read).
// Errors (a compile or link error with GL's info log, bad sizes, an OpenGL error) throw tessera::Error, a
// std::runtime_error.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "osmesa_renderer.hpp"  // GlLight, GlMaterial, GlFilter
#include "tessera/math/types.hpp"

namespace tessera::reference {

/// GL_TEXTURE_WRAP_S and _T.
enum class GlslWrap {
  repeat,         ///< GL_REPEAT
  clamp_to_edge,  ///< GL_CLAMP_TO_EDGE
};

/// A GL_TEXTURE_2D in RGBA8.
struct GlslTexture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  ///< 4 bytes per texel, rows bottom first (as glTexImage2D takes them)
  GlFilter filter = GlFilter::linear;
  GlslWrap wrap = GlslWrap::repeat;
};

/// A GL_TEXTURE_CUBE_MAP in RGBA8, clamped to the edges (GL_CLAMP_TO_EDGE on s, t and r).
struct GlslCubeMap {
  int size = 0;  ///< width and height of every face
  /// +X, -X, +Y, -Y, +Z, -Z (GL_TEXTURE_CUBE_MAP_POSITIVE_X + i): size * size * 4 bytes each, rows as glTexImage2D
  /// takes them (OpenGL's face orientation).
  std::array<std::vector<uint8_t>, 6> faces;
  GlFilter filter = GlFilter::linear;  ///< linear_mipmap_linear builds the levels with glGenerateMipmap
};

/// A uniform's value. `floats` go to glUniform{1,2,3,4}fv or glUniformMatrix{2,3,4}fv (column-major, not transposed)
/// by the active uniform's type (glGetActiveUniform); `ints` to glUniform{1,2,3,4}iv (ints, bools, samplers: the
/// texture unit). Either fills `size() / components` elements from the named one on ("weights" or "weights[0]" is
/// the whole array, "weights[2]" from element 2 on). A name that is not an active uniform is ignored, as OpenGL's
/// location -1; a count that is not a multiple of the type's components throws.
struct GlslUniform {
  std::string name;
  std::vector<float> floats;
  std::vector<int> ints;
};

/// A user vertex attribute (`attribute` / `in` variable), found with glGetAttribLocation; not active: skipped.
struct GlslAttribute {
  std::string name;
  int components = 0;       ///< 1 to 4 floats per vertex (missing components read 0, w reads 1)
  std::vector<float> data;  ///< components * vertex count
};

/// One draw: a program, its vertex arrays, the compatibility state its built-ins read, uniforms and textures.
struct GlslDraw {
  std::string vertex_source;    ///< the vertex shader's text
  std::string fragment_source;  ///< the fragment shader's text
  /// gl_Vertex, gl_Normal, gl_Color, gl_MultiTexCoord0 from client arrays (glVertexPointer, ...). Empty: the array is
  /// not enabled and the built-in reads the current value (normal (0, 0, 1), current_color, texture coordinate
  /// (0, 0, 0, 1)). The vertex count is positions.size(), or the first attribute's when positions is empty.
  std::vector<Vec3f> positions, normals, colors;
  std::vector<Vec2f> uvs;
  std::vector<GlslAttribute> attributes;  ///< user attributes by name (glVertexAttribPointer)
  std::vector<uint32_t> indices;          ///< triangles (GL_TRIANGLES), 3 per triangle
  Mat4f model_view{1.0f};                 ///< glMatrixMode(GL_MODELVIEW) + glLoadMatrixf (column-major)
  Mat4f projection{1.0f};                 ///< glMatrixMode(GL_PROJECTION) + glLoadMatrixf
  /// GL_LIGHT0 + i (at most 8; the others keep OpenGL's defaults: light 0 white, the rest black). They are set with
  /// glLightfv and not enabled: shaders read gl_LightSource[i] either way.
  std::vector<GlLight> lights;
  GlMaterial material;
  Vec4f current_color{1, 1, 1, 1};  ///< glColor4f: gl_Color when `colors` is empty
  std::vector<GlslUniform> uniforms;
  std::vector<std::pair<int, GlslTexture>> textures;   ///< (unit, texture): GL_TEXTURE_2D on GL_TEXTURE0 + unit
  std::vector<std::pair<int, GlslCubeMap>> cube_maps;  ///< (unit, cube map): GL_TEXTURE_CUBE_MAP on GL_TEXTURE0 + unit
  bool seamless_cube_maps = false;  ///< GL_TEXTURE_CUBE_MAP_SEAMLESS (off by default in a compatibility context)
  bool depth_test = true;           ///< GL_DEPTH_TEST with GL_LESS, cleared to 1.0
  bool cull_back = false;           ///< GL_CULL_FACE with GL_BACK, front faces counterclockwise
  Vec4f clear_color{0, 0, 0, 0};    ///< glClearColor
};

/// A draw set up once in its own OSMesa context (RGBA, 24-bit depth, 8-bit stencil, compatibility profile): the
/// program compiled and linked, uniforms set, textures uploaded, the arrays and the fixed-function state bound. Each
/// render() or timed draw then only clears and calls glDrawElements. The context is made current on the calling
/// thread by every call (another OSMesa context may be used in between).
class GlslRenderer {
 public:
  /// Copies `draw` and sets it up at width x height. Throws tessera::Error with GL's info log when a shader does
  /// not compile or the program does not link, and for bad sizes (arrays, indices, textures), a uniform of the
  /// wrong kind or count, or when OSMesa cannot create the context.
  GlslRenderer(const GlslDraw& draw, int width, int height);
  ~GlslRenderer();
  GlslRenderer(GlslRenderer&&) noexcept;
  GlslRenderer& operator=(GlslRenderer&&) noexcept;

  int width() const;
  int height() const;
  /// The program's active uniforms as glGetActiveUniform names them ("light_dir[0]" for an array,
  /// "gl_LightSource[0].position" for a built-in it reads).
  const std::vector<std::string>& active_uniforms() const;

  /// Clears (color to draw.clear_color, depth to 1), draws, glFinish, and reads the color buffer: RGBA8,
  /// width * height * 4 bytes, top row first. Throws tessera::Error on an OpenGL error.
  std::vector<uint8_t> render();
  /// The depth buffer of the last render(), top row first: 1.0 where nothing was drawn (coverage that does not
  /// depend on the program's alpha).
  std::vector<float> depth();
  /// Milliseconds (steady clock) of `repeat` frames of clear + draw + glFinish, after one untimed warm-up frame.
  double time_draws(int repeat);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Convenience: renders `draw` at width x height in a fresh context; RGBA8 top row first. Throws as GlslRenderer.
std::vector<uint8_t> render_glsl(const GlslDraw& draw, int width, int height);

/// Convenience: the milliseconds of `repeat` draws of `draw` (clear + draw + glFinish each) after one warm-up, set-up
/// excluded (GlslRenderer::time_draws).
double time_glsl(const GlslDraw& draw, int width, int height, int repeat);

}  // namespace tessera::reference
