#include "tessera/raster3d/shadow_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d {
namespace {

/// The bounding sphere of [lo, hi]: its center and radius. Throws InvalidInput for an empty (inverted) box.
std::pair<Vec3, double> bounding_sphere(const Vec3& lo, const Vec3& hi, const char* what) {
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z))
    throw InvalidInput(fmt::format("ShadowMap::{}: the scene box is empty", what));
  // A point scene still needs a nonzero view volume.
  return {0.5 * (lo + hi), std::max(0.5 * glm::length(hi - lo), 1e-6 * (1 + glm::length(lo)))};
}

/// size, when it is a valid map size.
int checked_size(int size) {
  if (size < 1 || size > ShadowMap::kMaxSize)
    throw InvalidInput(fmt::format("ShadowMap: size {} is outside [1, {}]", size, ShadowMap::kMaxSize));
  return size;
}

/// An up vector not parallel to `direction`.
Vec3 up_for(const Vec3& direction) {
  return std::abs(direction.y) < 0.9 * glm::length(direction) ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
}

/// Pass 1's vertex program: positions to the light's clip space, nothing else.
struct DepthVertexShader {
  const Vec3f* positions;
  Mat4f model_light;

  VertexOut<NoVaryings> operator()(uint32_t i) const { return {model_light * Vec4f(positions[i], 1.0f), {}}; }
};

/// Pass 1's fragment program: only the depth matters.
struct DepthFragmentShader {
  bool operator()(const NoVaryings&, Vec3f& color) const {
    color = Vec3f(0);
    return true;
  }
};

}  // namespace

ShadowMap::ShadowMap(int size, const Mat4& light_view_projection) {
  faces_.push_back(Face{Framebuffer::depth_only(checked_size(size), size), Mat4f(light_view_projection)});
}

Mat4 ShadowMap::directional(const Vec3& to_light, const Vec3& lo, const Vec3& hi) {
  if (glm::length(to_light) == 0) throw InvalidInput("ShadowMap::directional: the light direction is zero");
  const auto [center, radius] = bounding_sphere(lo, hi, "directional");
  const Vec3 eye = center + glm::normalize(to_light) * (2 * radius);
  // The sphere lies between distances radius and 3 radius from that eye; a 1% margin keeps it off the clip planes.
  const double r = 1.01 * radius;
  return ortho(-r, r, -r, r, 2 * radius - r, 2 * radius + r) * look_at(eye, center, up_for(to_light));
}

Mat4 ShadowMap::spot(const Vec3& position, const Vec3& lo, const Vec3& hi) {
  const auto [center, radius] = bounding_sphere(lo, hi, "spot");
  const double distance = glm::length(center - position);
  const double r = 1.01 * radius;
  if (distance <= r)
    throw InvalidInput(
        "ShadowMap::spot: the light is inside the scene's bounding sphere (one map cannot see all "
        "around it; use a directional light or move the light out)");
  return perspective(2 * std::asin(r / distance), 1, distance - r, distance + r) *
         look_at(position, center, up_for(center - position));
}

ShadowMap ShadowMap::point(int size, const Vec3& position, const Vec3& lo, const Vec3& hi) {
  const auto [center, radius] = bounding_sphere(lo, hi, "point");
  if (glm::length(center - position) > 1.01 * radius) return ShadowMap(size, spot(position, lo, hi));
  // Six faces, each a perspective around one axis reaching past the cube's edge by kGuard texels: a point's face is
  // that of its largest coordinate, where it lies at least kGuard texels inside, so its filter taps stay in the map.
  constexpr double kGuard = 4;
  const int face_size = std::max(1, checked_size(size) / 2);
  const double reach = 1 + 2 * kGuard / face_size;
  const double far = glm::length(center - position) + radius;
  const Mat4 projection = perspective(2 * std::atan(reach), 1, 0.01 * radius, 1.01 * far);
  // The faces of an environment cube map, in CubeFace order (the one cube_coord picks in visibility): looking along
  // the face's axis C with up -T, as render_cube_map does.
  ShadowMap map;
  map.center_ = Vec3f(position);
  for (int f = 0; f < 6; ++f) {
    const auto at = [f](float s, float t) { return Vec3(cube_direction({CubeFace(f), {s, t}})); };
    const Mat4 view = look_at(position, position + at(0.5f, 0.5f), at(0.5f, 0) - at(0.5f, 1));
    map.faces_.push_back(Face{Framebuffer::depth_only(face_size, face_size), Mat4f(projection * view)});
  }
  return map;
}

void ShadowMap::draw(const VertexArrays& arrays, const Mat4& model) {
  for (Face& face : faces_) {
    const DepthVertexShader vs{arrays.positions.data(), Mat4f(Mat4(face.light) * model)};
    draw_triangles(face.depth, RasterState{}, uint32_t(arrays.positions.size()), arrays.indices, vs,
                   DepthFragmentShader{});
  }
}

void ShadowMap::clear() {
  for (Face& face : faces_) face.depth.clear_depth();
}

float ShadowMap::visibility(const Vec3f& p, const Vec3f& n, int pcf) const {
  if (pcf < 0) throw InvalidInput(fmt::format("ShadowMap::visibility: negative filter radius {}", pcf));
  if (faces_.size() == 1) return visibility(faces_[0], p, n, pcf);
  return visibility(faces_[size_t(cube_coord(p - center_).face)], p, n, pcf);
}

float ShadowMap::visibility(const Face& face, const Vec3f& p, const Vec3f& n, int pcf) {
  const Mat4f& light = face.light;
  const Vec4f q = light * Vec4f(p, 1.0f);
  if (!(q.w > 0)) return 1;  // behind a spot light
  const float inv_w = 1 / q.w;
  const Vec3f ndc = Vec3f(q) * inv_w;
  // Outside the light's view, or nearer to it than its near plane: nothing the map holds can block the light.
  if (!(std::abs(ndc.x) <= 1 && std::abs(ndc.y) <= 1 && ndc.z >= -1)) return 1;
  const int size = face.depth.width();
  const float half = 0.5f * float(size);
  const int ci = int(std::floor((ndc.x + 1) * half)), cj = int(std::floor((ndc.y + 1) * half));
  // The fraction of the (2 pcf + 1)^2 texels around P' that let the light through: texels outside the map or
  // holding nothing (the cleared depth) do, the others when `passes(i, j, stored depth)` says so.
  const auto& depth = face.depth.depth();
  const auto filtered = [&](auto passes) {
    int lit = 0, taps = 0;
    for (int j = cj - pcf; j <= cj + pcf; ++j)
      for (int i = ci - pcf; i <= ci + pcf; ++i, ++taps) {
        if (i < 0 || j < 0 || i >= size || j >= size) {
          ++lit;
          continue;
        }
        const uint32_t stored = depth(i, size - 1 - j);  // row 0 is the top
        lit += stored == kDepthMax || passes(i, j, float(stored) * (1.0f / float(kDepthMax)));
      }
    return float(lit) / float(taps);
  };
  // Beyond the far plane (a map fitted to the casters only): behind everything the map holds.
  if (ndc.z > 1) return filtered([](int, int, float) { return false; });
  const Vec3f window((ndc.x + 1) * half, (ndc.y + 1) * half, 0.5f * ndc.z + 0.5f);

  // The tangent plane's depth gradient in the light's window space: two tangents through the derivative of the
  // projective map, d window = (d q.xyz - ndc d q.w) / q.w (scaled to texels in x, y and by 1/2 in z).
  const Vec3f a = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0)));
  const Vec3f b = glm::cross(n, a);
  const auto window_step = [&](const Vec3f& t) {
    const Vec4f dq = light * Vec4f(t, 0.0f);
    const Vec3f d = (Vec3f(dq) - ndc * dq.w) * inv_w;
    return Vec3f(d.x * half, d.y * half, 0.5f * d.z);
  };
  const Vec3f da = window_step(a), db = window_step(b);
  const float det = da.x * db.y - da.y * db.x;
  // Seen edge-on, the surface is in its own (attached) shadow.
  if (!(std::abs(det) > 1e-6f * (da.x * da.x + da.y * da.y + db.x * db.x + db.y * db.y))) return 0;
  const float gx = (da.z * db.y - db.z * da.y) / det, gy = (db.z * da.x - da.z * db.x) / det;
  // What the plane's prediction leaves: the map's rounding (2^-24) and a mesh's facets turning within the filter's
  // reach (concave edges came out as thin dark lines with a sixty-fourth of a texel's slope; one texel's, as
  // glPolygonOffset(1, 1) gives a caster, leaves none on the bunny).
  const float epsilon = 0x1p-16f + (std::abs(gx) + std::abs(gy));

  // The receiver's depth predicted at each texel's center, against what the light saw there.
  return filtered([&](int i, int j, float stored) {
    const float predicted = window.z + gx * (float(i) + 0.5f - window.x) + gy * (float(j) + 0.5f - window.y);
    return predicted - epsilon <= stored;
  });
}

}  // namespace tessera::raster3d
