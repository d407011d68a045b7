#pragma once
// The notes' mapping techniques as one per-pixel shader pair: texture mapping (the texture colors the surface,
// C_r = color x texture(s, t), filtered with MIPmaps at the level of detail of the pixel's footprint), bump mapping
// (Blinn 1978: the normal tilted by the height map's slopes), environment mapping (Blinn and Newell 1976: the
// reflected view direction looks up a lat-long image) and shadow mapping (ShadowMap, one per light: a light is
// blocked where it saw something nearer). Lighting is PreparedLighting's equation, evaluated at every pixel (Phong
// interpolation). Each map is optional.
//
// Texture coordinates are interpolated perspective-correctly by the pipeline (the notes: s/|z|, t/|z| and 1/|z|
// linearly, then divided per pixel), and the fragment program gets their exact screen derivatives, from which the
// MIPmap level of detail follows (Texture2D::lod).
#include <functional>
#include <span>
#include <vector>

#include "tessera/image/texture.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/lane_shader.hpp"
#include "tessera/raster3d/lighting.hpp"
#include "tessera/raster3d/pipeline.hpp"
#include "tessera/raster3d/shaders.hpp"
#include "tessera/raster3d/shadow_map.hpp"

namespace tessera::raster3d {

/// Per-vertex tangents P_s = dP/du and P_t = dP/dv (the notes' bump-mapping tangents; u, v the texture coordinates).
struct UvTangents {
  std::vector<Vec3f> u, v;
};

/// The tangents of an indexed triangle mesh with texture coordinates: each triangle's dP/du and dP/dv solve
/// [e1 e2] = [P_s P_t] [du1 du2; dv1 dv2] for its edges e1, e2 and their uv differences; a vertex takes the mean
/// over its triangles (triangles with a degenerate uv triangle are skipped; a vertex with none gets zero tangents,
/// which leave its normal unbumped). Throws InvalidInput when uvs and positions differ in size or an index is out of
/// range.
UvTangents uv_tangents(std::span<const Vec3f> positions, std::span<const Vec2f> uvs, std::span<const uint32_t> indices);

/// Blinn's bump-mapped normal for the surface P(u, v) displaced by B(u, v) along its unit normal n:
/// N' = N + (B_u (N x P_t) - B_v (N x P_s)) / |N| with N = P_s x P_t, written with the unit n as
/// normalize(n + (B_u (n x P_t) - B_v (n x P_s)) / |P_s x P_t|). It is the exact normal of the displaced surface
/// where n does not vary (a plane), and its first-order approximation elsewhere. (The notes' N - (B_u P_s + B_v P_t)
/// is the case of orthonormal tangents.) Where P_s x P_t points against n (a mirrored texture), the tilt is negated
/// so that the result is still the displaced surface's normal on n's side. Returns n when P_s x P_t is zero.
Vec3f bump_normal(const Vec3f& n, const Vec3f& p_s, const Vec3f& p_t, float b_u, float b_v);

/// The slopes (B_u, B_v) = (dB/du, dB/dv) of the height B = scale x (red channel of `height`) at uv: central
/// differences one texel apart on the bilinear level 0.
Vec2f height_gradient(const Texture2D& height, Vec2f uv, float scale);

/// The eye (center of projection) of a projection matrix in eye space, as a homogeneous point: the vector e with
/// (P e).x = (P e).y = (P e).w = 0, which every point on the line of sight through a pixel shares. (0, 0, 0, 1) for a
/// perspective (the origin), (0, 0, 1, 0) for an orthographic projection (a point at infinity: all lines of sight
/// are parallel to z). The direction toward the eye from eye-space p is then e.xyz - p e.w.
Vec4f viewer_of(const Mat4& projection);

/// The optional maps of a surface. Pointers not owned; null = off.
struct SurfaceMaps {
  const Texture2D* texture = nullptr;  ///< multiplies the surface color (the sampler's filter; trilinear uses lod)
  const Texture2D* bump = nullptr;     ///< height map (red channel), needs the vertex shader's tangents
  float bump_scale = 0.02f;            ///< height of a texel value 1, in object units (negative: bright is low)
  const EnvironmentMap* environment = nullptr;         ///< lat-long radiance around the scene (world space)
  const CubeMap* cube = nullptr;                       ///< or a cube map (render_cube_map); used when set
  float reflectivity = 0;                              ///< adds reflectivity x environment(R)
  std::array<const ShadowMap*, kMaxLights> shadows{};  ///< light i's shadow map (world space), or null (unshadowed)
  int shadow_pcf = 1;                                  ///< their filter radius in texels
};

/// The uniforms of the surface shaders.
struct SurfaceUniforms {
  Mat4f model_view_projection{1.0f};
  Mat4f model_view{1.0f};
  Mat3f normal_matrix{1.0f};
  Mat4f eye_to_world{1.0f};   ///< the inverse view matrix: environment and shadow lookups are in world space
  Vec4f viewer{0, 0, 0, 1};   ///< the eye in eye space, homogeneous (see viewer_of): E = viewer.xyz - p viewer.w
  PreparedLighting lighting;  ///< prepare with color_material on, so that the textured color is C_r
  Vec3f color{1, 1, 1};       ///< the surface color for vertices without one
  float light0 = 1;           ///< light 0's visibility before the shadow map's (0: the dark pass of shadow volumes)
  SurfaceMaps maps;

  /// Sets the matrices, eye_to_world and viewer for a camera (projection, view) and an object's model matrix.
  void set_camera(const Mat4& projection, const Mat4& view, const Mat4& model = Mat4(1.0));
};

/// Eye-space normal and position, color, texture coordinates and eye-space tangents.
struct SurfaceVaryings {
  Vec3f normal;
  Vec3f position;
  Vec3f color;
  Vec2f uv;
  Vec3f tangent_u, tangent_v;
};

/// The vertex program: clip position, and the varyings in eye space. Normals are required; uvs when a texture or
/// bump map is used, tangents (uv_tangents) when a bump map is.
struct SurfaceVertexShader {
  VertexAttributes attributes;
  const Vec3f* tangents_u = nullptr;  ///< or null (no bump mapping)
  const Vec3f* tangents_v = nullptr;
  const SurfaceUniforms* uniforms = nullptr;

  VertexOut<SurfaceVaryings> operator()(uint32_t i) const {
    const SurfaceUniforms& u = *uniforms;
    const Vec4f object(attributes.positions[i], 1.0f);
    const Mat3f linear(u.model_view);  // tangents are directions on the surface: the model-view's linear part
    return {gl_transform(u.model_view_projection, attributes.positions[i]),
            {u.normal_matrix * attributes.normals[i], Vec3f(u.model_view * object), attributes.color_or(i, u.color),
             attributes.uvs ? attributes.uvs[i] : Vec2f(0), tangents_u ? linear * tangents_u[i] : Vec3f(0),
             tangents_v ? linear * tangents_v[i] : Vec3f(0)}};
  }
};

/// The fragment program: bump, texture, shadow, lighting, environment, in that order.
struct SurfaceFragmentShader {
  const SurfaceUniforms* uniforms = nullptr;

  bool operator()(const SurfaceVaryings& in, const SurfaceVaryings& ddx, const SurfaceVaryings& ddy,
                  Vec3f& color) const;
};

/// The fragment program as a lane shader (lane_shader.hpp), eight fragments at a time, what draw_surface runs: the same
/// steps, with the texture's level of detail from each quad's differences (as OpenGL's) and the shadow test's facet
/// plane from the position's quad differences. Bump mapping, shadow maps and environment lookups run lane by lane.
struct SurfaceLaneShader {
  const SurfaceUniforms* uniforms = nullptr;

  lanes::vec3 operator()(const lanes::Fragment<SurfaceVaryings>& in, lanes::Mask& kept) const;
};

/// Draws the triangles of `arrays` with the surface shaders (SurfaceLaneShader on the quad stage) and uniforms `u`
/// (normals required; uvs for a texture or
/// bump map; `tangents`, uv_tangents of the same arrays, for a bump map, else null). Throws InvalidInput when the
/// normals, the uvs a map needs, or the tangents do not match the positions in number, or a bump map has no tangents.
DrawStats draw_surface(Framebuffer& framebuffer, const RasterState& state, const VertexArrays& arrays,
                       const SurfaceUniforms& u, const UvTangents* tangents = nullptr);

/// The notes' cube mapping ("render scene 6 times, eye at center of cube"): `draw(framebuffer, projection, view)`
/// renders the scene once per face into a size x size framebuffer cleared to black, and the six pictures become a
/// CubeMap whose lookup(d) is what is seen from `center` in direction d (world space): a dynamic environment map,
/// reflecting the objects near a mirror. Each face is a 90-degree perspective (near, far) from `center` in OpenGL's
/// face layout, which mirrors x: draw without culling. Throws InvalidInput for size < 1 or not 0 < near < far.
CubeMap render_cube_map(const Vec3& center, int size,
                        const std::function<void(Framebuffer&, const Mat4& projection, const Mat4& view)>& draw,
                        double near = 0.01, double far = 1000, Filter filter = Filter::bilinear);

/// Paints every pixel that nothing was drawn on (depth still 1) with the environment seen along its line of sight
/// through the camera `view_projection` (world to clip space): the background of an environment-mapped scene.
/// Throws InvalidInput for a depth-only framebuffer.
void fill_background(Framebuffer& framebuffer, const EnvironmentMap& environment, const Mat4& view_projection);

}  // namespace tessera::raster3d
