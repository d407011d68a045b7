#pragma once
// Surface shading (the notes, "Surface Shading" and "Shiny Surfaces"): materials, lights, the shading equation, and
// the fixed-function pipeline's lighting written as a built-in shader pair.
//
// The equation is OpenGL 1.x's (gl-raster-conventions.md item 8), which contains the notes' combined equation
// C = C_r (C_a + C_L max(0, N.L)) + C_L C_H (H.N)^P as the case ambient = diffuse = C_r, specular = C_H:
//   c = emission + ambient_m * model_ambient
//       + sum over lights of [ ambient_m * ambient_l + max(N.L, 0) diffuse_m * diffuse_l
//                              + [N.L > 0] spec^shininess specular_m * specular_l ]
// with spec = max(H.N, 0) (Blinn, OpenGL's) or max(E.R, 0) (Phong, R = 2N(N.L) - L), E = (0, 0, 1) without a local
// viewer (as OpenGL's default), clamped to [0, 1]. All vectors are in eye space.
#include <array>
#include <cstdint>
#include <span>

#include "tessera/math/types.hpp"
#include "tessera/raster3d/lane_shader.hpp"
#include "tessera/raster3d/lanes.hpp"
#include "tessera/raster3d/shaders.hpp"

namespace tessera::raster3d {

/// Where the shading equation is evaluated (the notes: per polygon, per vertex, per pixel).
enum class ShadingModel {
  unlit,    ///< no lighting: the vertex colors, interpolated
  flat,     ///< per polygon: the lit color of the triangle's last vertex (OpenGL's provoking vertex)
  gouraud,  ///< per vertex, colors interpolated
  phong,    ///< per pixel: normals interpolated, the equation evaluated at every pixel
};

/// The specular term: Phong (E.R)^P or Blinn (H.N)^P (OpenGL's).
enum class SpecularModel { phong, blinn };

/// Surface reflectances (glMaterial). The defaults are OpenGL's.
struct Material {
  Vec3f ambient{0.2f, 0.2f, 0.2f};
  Vec3f diffuse{0.8f, 0.8f, 0.8f};
  Vec3f specular{0, 0, 0};  ///< the notes' highlight color C_H
  Vec3f emission{0, 0, 0};
  float shininess = 0;  ///< the specular exponent P

  /// The notes' plastic: C_r = color (ambient and diffuse), white highlights (C_H = (1, 1, 1) * specular).
  static Material plastic(const Vec3f& color, float shininess, float specular = 1.0f);
  /// The notes' metal: the highlight takes the surface color (C_H = C_r).
  static Material metal(const Vec3f& color, float shininess);
};

/// A light (glLight): `position` is in eye space; w = 0 makes it directional (xyz points toward the light), w = 1 a
/// point light at xyz. No attenuation or spot cone (OpenGL's defaults). The defaults are OpenGL's GL_LIGHT0.
struct Light {
  Vec4f position{0, 0, 1, 0};
  Vec3f ambient{0, 0, 0};
  Vec3f diffuse{1, 1, 1};
  Vec3f specular{1, 1, 1};
};

/// The most lights a Lighting holds (OpenGL's minimum GL_MAX_LIGHTS).
inline constexpr int kMaxLights = 8;

/// Everything the shading equation reads besides the surface point.
struct Lighting {
  Material material;
  std::array<Light, kMaxLights> lights{};
  int light_count = 1;                    ///< lights[0, light_count) are on
  Vec3f model_ambient{0.2f, 0.2f, 0.2f};  ///< GL_LIGHT_MODEL_AMBIENT
  SpecularModel specular_model = SpecularModel::blinn;
  bool local_viewer = false;    ///< E = normalize(-p) instead of (0, 0, 1) (GL_LIGHT_MODEL_LOCAL_VIEWER)
  bool color_material = false;  ///< the vertex color replaces ambient and diffuse (GL_COLOR_MATERIAL)
};

/// Lighting that shows the surface color as it is: no lights, model ambient 1, color material (for the surface
/// shaders, OpenGL's GL_REPLACE: a texture's texels unchanged).
Lighting unlit_lighting();

/// The shading equation above at eye-space point p with unit normal n; `color` is the vertex color used when
/// lighting.color_material is set. Returns the color clamped to [0, 1].
Vec3f shade(const Lighting& lighting, const Vec3f& n, const Vec3f& p, const Vec3f& color);

/// The shading equation with what does not depend on the surface point worked out once (the summed ambient, the
/// material x light products, each directional light's L and Blinn half vector): what the shaders call per vertex
/// or per pixel. shade(lighting, ...) is PreparedLighting(lighting).shade(...).
class PreparedLighting {
 public:
  PreparedLighting() : PreparedLighting(Lighting()) {}
  explicit PreparedLighting(const Lighting& lighting);

  /// The shading equation at eye-space point p with unit normal n (vertex color `color`), clamped to [0, 1].
  /// visibility[i] scales light i's diffuse and specular terms: the notes' visible(P, L), 0 in its shadow (see
  /// ShadowMap), fractions at a filtered shadow's edge; the lights past the span's end are fully visible.
  Vec3f shade(const Vec3f& n, const Vec3f& p, const Vec3f& color, std::span<const float> visibility = {}) const;
  /// The same on eight lanes (lanes.hpp), for lane shaders: lane k's result is the scalar shade's of lane k's values.
  lanes::vec3 shade(const lanes::vec3& n, const lanes::vec3& p, const lanes::vec3& color,
                    std::span<const lanes::Float> visibility = {}) const;
  /// The lights that are on: lights[0, light_count()).
  int light_count() const { return light_count_; }

 private:
  /// Both shades, on float and Vec3f or on lanes::Float and lanes::vec3 (lighting.cpp).
  template <class F, class V3>
  V3 shade_any(const V3& n, const V3& p, const V3& color, std::span<const F> visibility) const;

  struct PreparedLight {
    Vec4f position;
    Vec3f direction;  // directional lights: normalized L
    Vec3f half;       // directional lights without a local viewer: normalize(L + (0, 0, 1))
    Vec3f diffuse;    // diffuse_l (times diffuse_m unless color material)
    Vec3f specular;   // specular_m * specular_l
    bool directional;
    bool has_specular;
  };
  std::array<PreparedLight, kMaxLights> lights_{};
  int light_count_ = 0;
  Vec3f emission_{0}, ambient_m_{0}, ambient_sum_{0};  // ambient_sum = model ambient + the lights' ambients
  float shininess_ = 0;
  bool color_material_ = false, local_viewer_ = false, blinn_ = true;
};

// ---- The fixed-function pipeline as a shader pair ------------------------------------------------------------------

/// m v through a float32 matrix the way OpenGL on Mesa does it (the fixed-function vertex program's MUL and MADs):
/// m[0] x + m[1] y + m[2] z + m[3] w, summed left to right. glm's operator* adds the terms in pairs, which rounds
/// differently and moves depth by a unit of 2^-24 on many pixels.
inline Vec4f gl_transform(const Mat4f& m, const Vec4f& v) {
  return ((m[0] * v.x + m[1] * v.y) + m[2] * v.z) + m[3] * v.w;
}

/// An object position (w = 1) through m: the same sum (m[3] * 1 is exact).
inline Vec4f gl_transform(const Mat4f& m, const Vec3f& p) { return gl_transform(m, Vec4f(p, 1.0f)); }

/// The float32 product a b as Mesa forms P * MV (m_matrix.c): each column of b through a.
inline Mat4f gl_matrix_product(const Mat4f& a, const Mat4f& b) {
  Mat4f p;
  for (int j = 0; j < 4; ++j) p[j] = gl_transform(a, b[j]);
  return p;
}

/// Uniforms of the fixed-function shaders: the matrices (float32, as OpenGL), lighting, and the constant attributes.
struct FixedFunctionUniforms {
  Mat4f model_view_projection{1.0f};  ///< P * MV, one float32 matrix for positions (gl_matrix_product)
  Mat4f model_view{1.0f};
  Mat3f normal_matrix{1.0f};  ///< inverse transpose of MV's upper 3x3
  PreparedLighting lighting;
  bool lit = false;       ///< lighting on (flat, gouraud, phong) or off (unlit)
  Vec3f color{1, 1, 1};   ///< the current color (for vertices without one)
  Vec3f normal{0, 0, 1};  ///< the current normal (for vertices without one)
};

/// Unlit, flat and Gouraud: each vertex's color is computed (lit in eye space, or its color) and interpolated.
struct FixedFunctionVertexShader {
  VertexAttributes attributes;
  const FixedFunctionUniforms* uniforms = nullptr;

  VertexOut<ColorVaryings> operator()(uint32_t i) const {
    const FixedFunctionUniforms& u = *uniforms;
    const Vec3f color = attributes.color_or(i, u.color);
    const Vec4f clip = gl_transform(u.model_view_projection, attributes.positions[i]);
    if (!u.lit) return {clip, {color}};
    const Vec3f n = glm::normalize(u.normal_matrix * attributes.normal_or(i, u.normal));
    return {clip, {u.lighting.shade(n, Vec3f(u.model_view * Vec4f(attributes.positions[i], 1.0f)), color)}};
  }
};

/// Phong interpolation's varyings: eye-space normal and position, and the vertex color.
struct PhongVaryings {
  Vec3f normal;
  Vec3f position;
  Vec3f color;
};

/// Phong interpolation (per pixel), vertex part: passes eye-space normal, position and color.
struct PhongVertexShader {
  VertexAttributes attributes;
  const FixedFunctionUniforms* uniforms = nullptr;

  VertexOut<PhongVaryings> operator()(uint32_t i) const {
    const FixedFunctionUniforms& u = *uniforms;
    const Vec4f object(attributes.positions[i], 1.0f);
    return {gl_transform(u.model_view_projection, attributes.positions[i]),
            {u.normal_matrix * attributes.normal_or(i, u.normal), Vec3f(u.model_view * object),
             attributes.color_or(i, u.color)}};
  }
};

/// Phong interpolation, fragment part: renormalizes the interpolated normal and evaluates the equation per pixel.
struct PhongFragmentShader {
  const FixedFunctionUniforms* uniforms = nullptr;

  bool operator()(const PhongVaryings& in, Vec3f& color) const {
    color = uniforms->lighting.shade(glm::normalize(in.normal), in.position, in.color);
    return true;
  }
};

/// PhongFragmentShader as a lane shader (lane_shader.hpp), the same colors bit for bit, with an opacity for
/// blending: what Context draws Phong-shaded triangles with.
struct PhongLaneShader {
  const FixedFunctionUniforms* uniforms = nullptr;
  float alpha = 1;  ///< the fragments' alpha (Context::alpha)

  lanes::vec4 operator()(const lanes::Fragment<PhongVaryings>& in, lanes::Mask&) const {
    const lanes::vec3 n = normalize(in(&PhongVaryings::normal));
    return {uniforms->lighting.shade(n, in(&PhongVaryings::position), in(&PhongVaryings::color)), alpha};
  }
};

}  // namespace tessera::raster3d
