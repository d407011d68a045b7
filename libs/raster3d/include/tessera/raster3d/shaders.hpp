#pragma once
// The programmable stages' contract, and the notes' example shaders as C++ callables (the notes, "GPUs and GLSL").
//
// A vertex shader is any callable `VertexOut<V> vs(uint32_t vertex_index)`: it reads the vertex's attributes from
// arrays it captures (positions, normals, ...), uses its uniforms (members) and returns the clip-space position
// (gl_Position) and a struct V of varyings. A fragment shader is any callable `bool fs(const V& in, Vec3f& color)`:
// it gets the varyings interpolated perspective-correctly at the pixel center and writes gl_FragColor; returning
// false discards the fragment. A shader that writes `Vec4f& color` also gives the fragment's alpha (opacity, which
// blending reads: RasterState::blend); the Vec3f form's alpha is 1. Both are template parameters of the pipeline
// (pipeline.hpp), so they inline: no virtual call per vertex or fragment. GLSL's built-ins are GLM's (dot, normalize,
// reflect, clamp, mix, length).
//
// Varyings are a plain struct of floats and float vectors (glm::vec2/3/4): trivially copyable, standard layout, no
// padding. The pipeline interpolates it as an array of sizeof(V) / 4 floats; NoVaryings interpolates nothing.
#include <cmath>
#include <concepts>
#include <cstdint>
#include <glm/glm.hpp>
#include <type_traits>

#include "tessera/math/types.hpp"

namespace tessera::raster3d {

/// What a vertex shader returns: gl_Position (clip space) and the varyings handed to the rasterizer.
template <class V>
struct VertexOut {
  Vec4f position;
  V varyings;
};

/// The empty varyings struct, for shaders that pass nothing to the fragment stage.
struct NoVaryings {};

/// A valid varyings struct: floats only (checked by size), trivially copyable, standard layout.
template <class V>
concept VaryingStruct = std::is_trivially_copyable_v<V> && std::is_standard_layout_v<V> &&
    (std::is_empty_v<V> || sizeof(V) % sizeof(float) == 0);

/// The number of floats the pipeline interpolates for V.
template <VaryingStruct V>
inline constexpr int varying_count = std::is_empty_v<V> ? 0 : int(sizeof(V) / sizeof(float));

/// A vertex shader producing varyings V.
template <class VS>
concept VertexShader = requires(const VS& vs, uint32_t i) {
  { vs(i).position } -> std::convertible_to<Vec4f>;
  requires VaryingStruct<decltype(vs(i).varyings)>;
};

/// The varyings type a vertex shader produces.
template <class VS>
using VaryingsOf = decltype(std::declval<const VS&>()(uint32_t{}).varyings);

/// A plain fragment shader writing color type C (Vec3f: RGB; Vec4f: RGBA): `bool fs(const V& in, C& color)`.
template <class FS, class V, class C>
concept PlainFragmentShaderWriting = requires(const FS& fs, const V& v, C& color) {
  { fs(v, color) } -> std::convertible_to<bool>;
};

/// A fragment shader that reads the varyings' screen-space derivatives (GLSL's dFdx and dFdy), writing color type C:
/// `bool fs(const V& in, const V& ddx, const V& ddy, C& color)`.
template <class FS, class V, class C>
concept DerivativeFragmentShaderWriting = requires(const FS& fs, const V& v, C& color) {
  { fs(v, v, v, color) } -> std::convertible_to<bool>;
};

/// A fragment shader that reads the varyings' screen-space derivatives (GLSL's dFdx and dFdy): `bool fs(const V& in,
/// const V& ddx, const V& ddy, Vec3f& color)` (or `Vec4f& color`, RGBA). ddx and ddy are the exact derivatives of the
/// perspective-correct interpolation at the pixel center, per window pixel to the right and up (not 2 x 2 finite
/// differences, as GPUs take them): what a texture's level of detail needs. They are zero for lines, points and
/// flat-shaded triangles.
template <class FS, class V>
concept DerivativeFragmentShader =
    DerivativeFragmentShaderWriting<FS, V, Vec3f> || DerivativeFragmentShaderWriting<FS, V, Vec4f>;

/// A fragment shader consuming varyings V: `bool fs(const V& in, Vec3f& color)`, `bool fs(const V& in, Vec4f&
/// color)` (RGBA), or a DerivativeFragmentShader.
template <class FS, class V>
concept FragmentShader = DerivativeFragmentShader<FS, V> || PlainFragmentShaderWriting<FS, V, Vec3f> ||
    PlainFragmentShaderWriting<FS, V, Vec4f>;

/// Calls fs in whichever form it has (the derivatives are ignored by the plain forms); an RGB shader's alpha is 1.
/// A shader callable with both Vec3f and Vec4f is called with Vec3f.
template <class V, FragmentShader<V> FS>
bool run_fragment_shader(const FS& fs, const V& in, const V& ddx, const V& ddy, Vec4f& color) {
  if constexpr (DerivativeFragmentShaderWriting<FS, V, Vec3f> || PlainFragmentShaderWriting<FS, V, Vec3f>) {
    Vec3f rgb;
    bool kept;
    if constexpr (DerivativeFragmentShaderWriting<FS, V, Vec3f>)
      kept = fs(in, ddx, ddy, rgb);
    else
      kept = fs(in, rgb);
    color = Vec4f(rgb, 1.0f);
    return kept;
  } else if constexpr (DerivativeFragmentShaderWriting<FS, V, Vec4f>) {
    return fs(in, ddx, ddy, color);
  } else {
    return fs(in, color);
  }
}

/// Fragment shader FS made translucent: FS's color with its alpha (1 for an RGB shader) multiplied by `alpha`, the
/// opacity that blending reads (RasterState::blend). The derivatives reach FS when it reads them.
template <class FS>
struct Translucent {
  FS shader;
  float alpha = 1;

  template <class V>
  requires(FragmentShader<FS, V> && !DerivativeFragmentShader<FS, V>) bool operator()(const V& in, Vec4f& color) const {
    return run_fragment_shader(shader, in, in, in, color) && (color.w *= alpha, true);
  }
  template <class V>
  requires DerivativeFragmentShader<FS, V>
  bool operator()(const V& in, const V& ddx, const V& ddy, Vec4f& color) const {
    return run_fragment_shader(shader, in, ddx, ddy, color) && (color.w *= alpha, true);
  }
};

// ---- Vertex attribute arrays
// -----------------------------------------------------------------------------------------

/// Float vertex attributes the shaders read by index: positions are required; an empty normals/colors/uvs array
/// means "use the constant" given to the shader (the context's current normal, color, texcoord).
struct VertexAttributes {
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;  ///< or null
  const Vec3f* colors = nullptr;   ///< or null
  const Vec2f* uvs = nullptr;      ///< or null

  /// Vertex i's normal, or `fallback` without a normals array.
  Vec3f normal_or(uint32_t i, const Vec3f& fallback) const { return normals ? normals[i] : fallback; }
  /// Vertex i's color, or `fallback` without a colors array.
  Vec3f color_or(uint32_t i, const Vec3f& fallback) const { return colors ? colors[i] : fallback; }
};

// ---- Shipped shaders: the notes' examples --------------------------------------------------------------------------

/// A single interpolated color: the varyings of unlit and Gouraud shading.
struct ColorVaryings {
  Vec3f color;
};

/// Passes the interpolated color through (gl_FragColor = gl_Color).
struct ColorFragmentShader {
  bool operator()(const ColorVaryings& in, Vec3f& color) const {
    color = in.color;
    return true;
  }
};

/// The notes' diffuse shader's varyings: the eye-space normal and the vector from the vertex to the light.
struct DiffuseVaryings {
  Vec3f normal;
  Vec3f vertex_to_light;
};

/// The notes' diffuse vertex program: gl_Position = MVP * gl_Vertex, normal = NormalMatrix * gl_Normal,
/// vertex_to_light = light position (eye space) - ModelView * gl_Vertex.
struct DiffuseVertexShader {
  VertexAttributes attributes;  ///< positions and normals (normals required)
  Mat4f model_view_projection{1.0f};
  Mat4f model_view{1.0f};
  Mat3f normal_matrix{1.0f};
  Vec3f light_position{0, 0, 0};  ///< gl_LightSource[0].position in eye space

  VertexOut<DiffuseVaryings> operator()(uint32_t i) const {
    const Vec4f vertex(attributes.positions[i], 1.0f);
    const Vec4f vertex_modelview = model_view * vertex;
    return {model_view_projection * vertex,
            {normal_matrix * attributes.normals[i], light_position - Vec3f(vertex_modelview)}};
  }
};

/// The notes' diffuse fragment program: gl_FragColor = clamp(dot(normalize(normal), normalize(vertex_to_light)),
/// 0, 1) * diffuseColor (red by default, as the notes).
struct DiffuseFragmentShader {
  Vec3f diffuse_color{1, 0, 0};

  bool operator()(const DiffuseVaryings& in, Vec3f& color) const {
    const float diffuse = glm::clamp(glm::dot(glm::normalize(in.normal), glm::normalize(in.vertex_to_light)), 0.f, 1.f);
    color = diffuse * diffuse_color;
    return true;
  }
};

/// The notes' twisting vertex program: pos = MVP * gl_Vertex; angle = twist * length(pos.xy - center); pos.xy is
/// rotated counterclockwise by angle; the color is copied. The notes' center (512, 512) is the middle of a 1024 x 1024
/// pixel space; here `center` is in clip coordinates, (0, 0) being the middle of the screen.
struct TwistVertexShader {
  VertexAttributes attributes;  ///< positions, and colors (or `color` for all)
  Mat4f model_view_projection{1.0f};
  float twist = 1.0f;  ///< radians of rotation per clip-space unit of distance from the center
  Vec2f center{0, 0};
  Vec3f color{1, 1, 1};

  VertexOut<ColorVaryings> operator()(uint32_t i) const {
    const Vec4f pos = model_view_projection * Vec4f(attributes.positions[i], 1.0f);
    const float angle = twist * glm::length(Vec2f(pos.x - center.x, pos.y - center.y));
    const float c = std::cos(angle), s = std::sin(angle);
    return {{c * pos.x - s * pos.y, s * pos.x + c * pos.y, pos.z, pos.w}, {attributes.color_or(i, color)}};
  }
};

}  // namespace tessera::raster3d
