#pragma once
// GLSL programs on the CPU: a vertex and a fragment shader in the notes' dialect (GLSL 1.10/1.20 with the
// compatibility built-ins: gl_Vertex, gl_ModelViewProjectionMatrix, gl_LightSource[i], texture2D, ftransform(), ...)
// or in modern GLSL (3.30 and later: in/out, layout(location), texture). glslang, the Khronos reference compiler,
// parses and type-checks them; Tessera compiles glslang's typed syntax tree to a register program that runs over SIMD
// lanes: the vertex stage a batch of vertices at a time, the fragment stage on raster3d's quad stage
// (quad_stage.hpp), 2 x 2 quads at a time, so that dFdx, dFdy and texture()'s level of detail are quad differences as
// on a GPU. docs/shaders.md explains the dialects, the built-in state and how the executor runs a program.
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/types.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/framebuffer.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::glsl {

/// A shader's source text and the name its messages give (the file path, or "vertex shader").
struct ShaderSource {
  std::string text;
  std::string name;
};

/// Reads a shader file into a ShaderSource named by its path. Throws IoError when it cannot be read.
ShaderSource read_shader(const std::string& path);

/// A compile or link error: what() is "<name>:<line>: <message>" per error, one per line, as glslang reports them.
class CompileError : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

/// The basic types a uniform, attribute or varying may have (after arrays and structs are flattened to members).
enum class BasicType {
  floating,  ///< float
  vec2,
  vec3,
  vec4,
  integer,  ///< int
  ivec2,
  ivec3,
  ivec4,
  boolean,  ///< bool
  bvec2,
  bvec3,
  bvec4,
  mat2,
  mat3,
  mat4,
  sampler_2d,
  sampler_cube
};

/// One active uniform: its full name as GLSL spells it ("light.color", "weights[2]", "gl_LightSource[0].position"),
/// its type and where its value lives.
struct UniformInfo {
  std::string name;
  BasicType type;
  int components;  ///< floats or ints of its value (a mat4: 16, column-major)
};

/// The fixed-function state the compatibility built-ins read (OpenGL binds them from the context's current state):
/// gl_ModelViewMatrix, gl_ProjectionMatrix and what follows from them (gl_ModelViewProjectionMatrix,
/// gl_NormalMatrix, the inverses and transposes), gl_LightSource[i], gl_FrontMaterial, gl_LightModel and the current
/// vertex attributes for arrays a draw does not give.
struct FixedFunctionState {
  Mat4f model_view{1.0f};
  Mat4f projection{1.0f};
  struct Light {
    Vec4f ambient{0, 0, 0, 1}, diffuse{1, 1, 1, 1}, specular{1, 1, 1, 1};
    Vec4f position{0, 0, 1, 0};  ///< in eye space (as glLightfv stores it)
    Vec3f spot_direction{0, 0, -1};
    float spot_exponent = 0, spot_cutoff = 180;
    float constant_attenuation = 1, linear_attenuation = 0, quadratic_attenuation = 0;
  };
  Light lights[8];  ///< OpenGL's defaults: light 0 white, the others' diffuse and specular black
  struct Material {
    Vec4f ambient{0.2f, 0.2f, 0.2f, 1}, diffuse{0.8f, 0.8f, 0.8f, 1}, specular{0, 0, 0, 1}, emission{0, 0, 0, 1};
    float shininess = 0;
  };
  Material front_material, back_material;
  Vec4f light_model_ambient{0.2f, 0.2f, 0.2f, 1};
  Vec4f color{1, 1, 1, 1};      ///< gl_Color where no colors array is given
  Vec3f normal{0, 0, 1};        ///< gl_Normal where no normals array is given
  Vec4f tex_coord{0, 0, 0, 1};  ///< gl_MultiTexCoord0 where no texture coordinates are given

  FixedFunctionState();
};

/// The vertex arrays of a draw. The compatibility attributes come from the named arrays (each may be empty: the
/// state's current value); user attributes (`attribute` / `in` variables) by name from `attributes`, `components`
/// floats per vertex (missing components read 0, w reads 1, as OpenGL). A user attribute that `attributes` does not
/// name reads the array of its usual name: position or vertex, normal, color, uv, texcoord or tex_coord.
struct ProgramInputs {
  std::span<const Vec3f> positions;  ///< gl_Vertex (w = 1), and the vertex count
  std::span<const Vec3f> normals;    ///< gl_Normal
  std::span<const Vec3f> colors;     ///< gl_Color
  std::span<const Vec2f> uvs;        ///< gl_MultiTexCoord0
  struct Attribute {
    const float* data = nullptr;
    int components = 0;
  };
  std::map<std::string, Attribute, std::less<>> attributes;
};

struct ProgramModule;  // the compiled register programs (src/)

/// A linked vertex + fragment program, its uniform values and its texture units. A Context draws through one after
/// use_program (raster3d::ContextProgram), binding the built-ins from its state.
class Program : public raster3d::ContextProgram {
 public:
  /// Compiles and links (a source without a #version line is GLSL 1.10, the notes' dialect). The built-ins start
  /// with FixedFunctionState's defaults. Throws CompileError with glslang's messages (source name, line, message),
  /// or naming what Tessera does not run.
  static Program compile(const ShaderSource& vertex, const ShaderSource& fragment);

  Program(Program&&) noexcept;
  Program& operator=(Program&&) noexcept;
  ~Program() override;

  /// The active uniforms a user may set (samplers included; the gl_ built-ins are set by set_fixed_function).
  const std::vector<UniformInfo>& uniforms() const;
  /// Whether the program has an active uniform of that name.
  bool has_uniform(std::string_view name) const;

  /// Sets a float uniform (float, vecN, matN column-major, or an array of them: `values` fills it from the named
  /// element on). A uniform the sources declare but the program does not use takes any value and keeps none (OpenGL's
  /// location -1). Throws InvalidInput for a name the sources do not declare, a type mismatch or too many values.
  void set_uniform(std::string_view name, std::span<const float> values);
  /// Sets an int, bool (0 or 1) or sampler (texture unit) uniform.
  void set_uniform(std::string_view name, std::span<const int> values);
  /// Sets a uniform from text: "0.5,1,0" (floats) or "2" (ints), as the command line's --uniform name=values.
  void set_uniform_text(std::string_view name, std::string_view values);
  /// Sets a uniform from "name=v1,v2,..." (the command line's --uniform). Throws InvalidInput without the '='.
  void set_uniform_assignment(std::string_view assignment);

  /// Binds a 2D texture to texture unit `unit` (0 to 15), shared with the caller; null unbinds. A sampler reading
  /// an unbound unit reads (0, 0, 0, 1), as OpenGL's incomplete texture.
  void bind_texture(int unit, std::shared_ptr<const Texture2D> texture);
  /// Binds a cube map to texture unit `unit`.
  void bind_cube_map(int unit, std::shared_ptr<const CubeMap> cube_map);

  /// Sets the compatibility built-ins' values (gl_ModelViewMatrix, gl_LightSource[], ...).
  void set_fixed_function(const FixedFunctionState& state);

  /// Whether the fragment shader may discard.
  bool discards() const;

  /// Draws the triangles `indices` of `inputs` through the program. Throws InvalidInput when an attribute the
  /// vertex shader reads is missing, as draw_triangles, or when a loop runs past its iteration limit.
  raster3d::DrawStats draw_triangles(raster3d::Framebuffer& framebuffer, const raster3d::RasterState& state,
                                     const ProgramInputs& inputs, std::span<const uint32_t> indices) const;

  /// The Context's draw (raster3d::ContextProgram): set_fixed_function from the context's state, then
  /// draw_triangles of its arrays.
  raster3d::DrawStats draw_arrays(raster3d::Framebuffer& framebuffer, const raster3d::RasterState& state,
                                  const raster3d::ProgramState& program_state,
                                  const raster3d::VertexAttributes& attributes, uint32_t vertex_count,
                                  std::span<const uint32_t> indices) override;

 private:
  Program();
  std::unique_ptr<ProgramModule> module_;
};

}  // namespace tessera::glsl
