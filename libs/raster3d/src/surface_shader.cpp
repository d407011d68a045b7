#include "tessera/raster3d/surface_shader.hpp"

#include <fmt/format.h>

#include <array>
#include <glm/gtc/matrix_access.hpp>

#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"

namespace tessera::raster3d {

UvTangents uv_tangents(std::span<const Vec3f> positions, std::span<const Vec2f> uvs,
                       std::span<const uint32_t> indices) {
  if (uvs.size() != positions.size())
    throw InvalidInput(fmt::format("uv_tangents: {} uvs for {} positions", uvs.size(), positions.size()));
  if (indices.size() % 3 != 0) throw InvalidInput("uv_tangents: the index count is not a multiple of 3");
  for (const uint32_t i : indices)
    if (i >= positions.size())
      throw InvalidInput(fmt::format("uv_tangents: index {} out of range [0, {})", i, positions.size()));
  UvTangents t{std::vector<Vec3f>(positions.size(), Vec3f(0)), std::vector<Vec3f>(positions.size(), Vec3f(0))};
  std::vector<int> count(positions.size(), 0);
  for (size_t k = 0; k < indices.size(); k += 3) {
    const uint32_t a = indices[k], b = indices[k + 1], c = indices[k + 2];
    const Vec3f e1 = positions[b] - positions[a], e2 = positions[c] - positions[a];
    const Vec2f d1 = uvs[b] - uvs[a], d2 = uvs[c] - uvs[a];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 0)) continue;
    // [e1 e2] = [P_s P_t] [d1 d2] (columns), so [P_s P_t] = [e1 e2] [d1 d2]^-1.
    const Vec3f p_s = (e1 * d2.y - e2 * d1.y) / det, p_t = (e2 * d1.x - e1 * d2.x) / det;
    for (const uint32_t v : {a, b, c}) {
      t.u[v] += p_s;
      t.v[v] += p_t;
      ++count[v];
    }
  }
  for (size_t v = 0; v < positions.size(); ++v)
    if (count[v] > 1) {
      t.u[v] /= float(count[v]);
      t.v[v] /= float(count[v]);
    }
  return t;
}

void SurfaceUniforms::set_camera(const Mat4& projection, const Mat4& view, const Mat4& model) {
  const Mat4 model_view_d = view * model;
  model_view = Mat4f(model_view_d);
  model_view_projection = Mat4f(projection * model_view_d);
  normal_matrix = Mat3f(tessera::normal_matrix(model_view_d));
  eye_to_world = Mat4f(glm::inverse(view));
  viewer = viewer_of(projection);
}

Vec4f viewer_of(const Mat4& projection) {
  // The null vector of rows x, y and w: the generalized cross product of the three rows (cofactors along a fourth).
  const glm::dmat3x4 rows(glm::row(projection, 0), glm::row(projection, 1), glm::row(projection, 3));
  glm::dvec4 e;
  for (int k = 0; k < 4; ++k) {
    glm::dmat3 minor;
    for (int r = 0; r < 3; ++r)
      for (int c = 0, col = 0; c < 4; ++c)
        if (c != k) minor[col++][r] = rows[r][c];
    e[k] = (k % 2 ? -1 : 1) * glm::determinant(minor);
  }
  // Scale so that a finite eye has w = 1, and a direction unit length pointing toward the viewer (+z in eye space).
  if (std::abs(e.w) > 1e-12 * glm::length(e)) return Vec4f(e / e.w);
  const glm::dvec3 d = glm::normalize(glm::dvec3(e));
  return Vec4f(Vec3f(d.z < 0 ? -d : d), 0);
}

Vec3f bump_normal(const Vec3f& n, const Vec3f& p_s, const Vec3f& p_t, float b_u, float b_v) {
  const Vec3f cross = glm::cross(p_s, p_t);
  const float area = glm::length(cross);
  if (!(area > 0)) return n;
  // Where the texture is mirrored, P_s x P_t points against n (the parameterization is left-handed there): the
  // displaced surface's normal on n's side then tilts the other way.
  const float side = glm::dot(cross, n) < 0 ? -1.0f : 1.0f;
  return glm::normalize(n + side * (b_u * glm::cross(n, p_t) - b_v * glm::cross(n, p_s)) / area);
}

Vec2f height_gradient(const Texture2D& height, Vec2f uv, float scale) {
  const float du = 1.0f / float(height.width()), dv = 1.0f / float(height.height());
  const auto h = [&](float u, float v) { return height.bilinear({u, v}, 0).x; };
  return {scale * (h(uv.x + du, uv.y) - h(uv.x - du, uv.y)) / (2 * du),
          scale * (h(uv.x, uv.y + dv) - h(uv.x, uv.y - dv)) / (2 * dv)};
}

bool SurfaceFragmentShader::operator()(const SurfaceVaryings& in, const SurfaceVaryings& ddx,
                                       const SurfaceVaryings& ddy, Vec3f& color) const {
  const SurfaceUniforms& u = *uniforms;
  const SurfaceMaps& maps = u.maps;
  Vec3f n = glm::normalize(in.normal);
  if (maps.bump) {
    const Vec2f slope = height_gradient(*maps.bump, in.uv, maps.bump_scale);
    n = bump_normal(n, in.tangent_u, in.tangent_v, slope.x, slope.y);
  }
  Vec3f surface = in.color;
  if (maps.texture) surface *= Vec3f(maps.texture->sample(in.uv, ddx.uv, ddy.uv));
  const Mat3f to_world(u.eye_to_world);
  // Each light's visibility: light 0's pass factor (shadow volumes), times what its shadow map says.
  std::array<float, kMaxLights> visible;
  visible.fill(1.0f);
  visible[0] = u.light0;
  size_t used = u.light0 != 1.0f;  // the lights whose visibility shade() reads: none while all are lit
  bool have_plane = false;
  Vec3f world, world_plane;
  for (size_t i = 0; i < size_t(u.lighting.light_count()); ++i) {
    if (!maps.shadows[i] || visible[i] <= 0) continue;
    if (!have_plane) {
      have_plane = true;
      // The shadow test needs the surface's true plane, the facet's, not the interpolated normal: it is the cross
      // product of the position's screen derivatives.
      const Vec3f facet = glm::cross(ddx.position, ddy.position);
      world = Vec3f(u.eye_to_world * Vec4f(in.position, 1.0f));
      world_plane = glm::normalize(to_world * (glm::dot(facet, facet) > 0 ? facet : n));
    }
    visible[i] *= maps.shadows[i]->visibility(world, world_plane, maps.shadow_pcf);
    used = i + 1;
  }
  Vec3f c = u.lighting.shade(n, in.position, surface, std::span<const float>(visible.data(), used));
  if (maps.environment || maps.cube) {
    // The notes: R from N and the view vector, R = 2 (N.E) N - E with E toward the eye; looked up in world space.
    const Vec3f e = glm::normalize(Vec3f(u.viewer) - in.position * u.viewer.w);
    const Vec3f r = to_world * (2 * glm::dot(n, e) * n - e);
    c += maps.reflectivity * Vec3f(maps.cube ? maps.cube->lookup(r) : maps.environment->lookup(r));
  }
  color = glm::clamp(c, 0.0f, 1.0f);
  return true;
}

lanes::vec3 SurfaceLaneShader::operator()(const lanes::Fragment<SurfaceVaryings>& in, lanes::Mask&) const {
  using lanes::kWidth;
  const SurfaceUniforms& u = *uniforms;
  const SurfaceMaps& maps = u.maps;
  const lanes::vec3 position = in(&SurfaceVaryings::position);
  lanes::vec3 n = normalize(in(&SurfaceVaryings::normal));
  if (maps.bump) {
    const lanes::vec2 uv = in(&SurfaceVaryings::uv);
    const lanes::vec3 tangent_u = in(&SurfaceVaryings::tangent_u), tangent_v = in(&SurfaceVaryings::tangent_v);
    for (int k = 0; k < kWidth; ++k) {
      const Vec2f slope = height_gradient(*maps.bump, uv.lane(k), maps.bump_scale);
      n.set_lane(k, bump_normal(n.lane(k), tangent_u.lane(k), tangent_v.lane(k), slope.x, slope.y));
    }
  }
  lanes::vec3 surface = in(&SurfaceVaryings::color);
  if (maps.texture) surface = surface * texture(*maps.texture, in(&SurfaceVaryings::uv)).xyz();
  const Mat3f to_world(u.eye_to_world);
  // Each light's visibility, as SurfaceFragmentShader's.
  std::array<lanes::Float, kMaxLights> visible;
  visible.fill(1.0f);
  visible[0] = u.light0;
  size_t used = u.light0 != 1.0f;
  bool have_plane = false;
  lanes::vec3 facet;
  for (size_t i = 0; i < size_t(u.lighting.light_count()); ++i) {
    if (!maps.shadows[i]) continue;
    if (!have_plane) {
      have_plane = true;
      facet = cross(dFdx(position), dFdy(position));  // the facet's plane (as SurfaceFragmentShader's)
    }
    for (int k = 0; k < kWidth; ++k) {
      if (visible[i].lane(k) <= 0) continue;
      const Vec3f f = facet.lane(k);
      const Vec3f world(u.eye_to_world * Vec4f(position.lane(k), 1.0f));
      const Vec3f world_plane = glm::normalize(to_world * (glm::dot(f, f) > 0 ? f : n.lane(k)));
      visible[i].set_lane(k, visible[i].lane(k) * maps.shadows[i]->visibility(world, world_plane, maps.shadow_pcf));
    }
    used = i + 1;
  }
  lanes::vec3 c = u.lighting.shade(n, position, surface, std::span<const lanes::Float>(visible.data(), used));
  if (maps.environment || maps.cube) {
    const lanes::vec3 e = normalize(lanes::vec3(Vec3f(u.viewer)) - position * u.viewer.w);
    const lanes::vec3 r = to_world * (lanes::Float(2.0f) * dot(n, e) * n - e);
    lanes::vec3 seen;
    for (int k = 0; k < kWidth; ++k)
      seen.set_lane(k, Vec3f(maps.cube ? maps.cube->lookup(r.lane(k)) : maps.environment->lookup(r.lane(k))));
    c = c + lanes::Float(maps.reflectivity) * seen;
  }
  return clamp(c, 0.0f, 1.0f);
}

DrawStats draw_surface(Framebuffer& framebuffer, const RasterState& state, const VertexArrays& arrays,
                       const SurfaceUniforms& u, const UvTangents* tangents) {
  if (arrays.normals.size() != arrays.positions.size())
    throw InvalidInput("draw_surface: the surface shaders need a normal per vertex");
  if ((u.maps.texture || u.maps.bump) && arrays.uvs.size() != arrays.positions.size())
    throw InvalidInput("draw_surface: texture and bump mapping need texture coordinates per vertex");
  if (u.maps.bump && !tangents) throw InvalidInput("draw_surface: bump mapping needs the tangents (uv_tangents)");
  if (tangents && (tangents->u.size() != arrays.positions.size() || tangents->v.size() != arrays.positions.size()))
    throw InvalidInput("draw_surface: the tangents are not those of these arrays (one per vertex)");
  const SurfaceVertexShader vs{arrays.attributes(), tangents ? tangents->u.data() : nullptr,
                               tangents ? tangents->v.data() : nullptr, &u};
  return draw_triangles(framebuffer, state, uint32_t(arrays.positions.size()), arrays.indices, vs,
                        SurfaceLaneShader{&u});
}

CubeMap render_cube_map(const Vec3& center, int size,
                        const std::function<void(Framebuffer&, const Mat4& projection, const Mat4& view)>& draw,
                        double near, double far, Filter filter) {
  if (size < 1) throw InvalidInput(fmt::format("render_cube_map: size {} must be at least 1", size));
  if (!(near > 0 && near < far))
    throw InvalidInput(fmt::format("render_cube_map: expected 0 < near < far, got {} and {}", near, far));
  std::array<ImageRGBA, 6> faces;
  Framebuffer framebuffer(size, size);
  for (int f = 0; f < 6; ++f) {
    // The face's axis C and its s and t directions S, T (cube_direction: C + (2s - 1) S + (2t - 1) T).
    const auto at = [f](float s, float t) { return Vec3(cube_direction({CubeFace(f), {s, t}})); };
    const Vec3 c = at(0.5f, 0.5f), s = 0.5 * (at(1, 0.5f) - at(0, 0.5f)), t = 0.5 * (at(0.5f, 1) - at(0.5f, 0));
    // Looking along C with up -T, window x is along T x C and window y along -T. Face pixel (x, y) sits at
    // s = (x + 1/2) / size and t = (y + 1/2) / size, with row 0 at the top: x must run along S (so the projection
    // mirrors x where T x C = -S) and rows down along +T (window y along -T: as it is).
    const double mirror = glm::dot(glm::cross(t, c), s) > 0 ? 1 : -1;
    const Mat4 projection = scale(mirror, 1, 1) * perspective(kPi / 2, 1, near, far);
    framebuffer.clear(Vec3f(0));
    draw(framebuffer, projection, look_at(center, center + c, -t));
    const ImageRGB picture = framebuffer.color_rgb();
    faces[size_t(f)] = ImageRGBA(size, size);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) faces[size_t(f)](x, y) = glm::vec4(picture(x, y), 1.0f);
  }
  return CubeMap(std::move(faces), filter);
}

void fill_background(Framebuffer& framebuffer, const EnvironmentMap& environment, const Mat4& view_projection) {
  if (!framebuffer.has_color()) throw InvalidInput("fill_background: a depth-only framebuffer has no color");
  const Mat4 to_world = glm::inverse(view_projection);
  const int width = framebuffer.width(), height = framebuffer.height();
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (framebuffer.depth()(x, y) < kDepthMax) continue;
      // The line of sight: the pixel center's points on the near and far planes (row 0 is the top).
      const double nx = 2 * (x + 0.5) / width - 1, ny = 1 - 2 * (y + 0.5) / height;
      const glm::dvec4 near = to_world * glm::dvec4(nx, ny, -1, 1), far = to_world * glm::dvec4(nx, ny, 1, 1);
      const Vec3 direction = Vec3(far) / far.w - Vec3(near) / near.w;
      framebuffer.color()(x, y) = to_color8(Vec3f(environment.lookup(Vec3f(direction))));
    }
}

}  // namespace tessera::raster3d
