#include "tessera/raster3d/shadow_volume.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/raster3d/lighting.hpp"

namespace tessera::raster3d {
namespace {

/// The volume's vertex program: homogeneous world positions to clip space, pushed back by kDepthOffset in NDC depth
/// (as glPolygonOffset): the near cap lies on the lit surface itself, whose depth another vertex program computed
/// with other roundings; pushed back, it fails the depth test there (z-fail counts it behind the surface) instead of
/// speckling the lit side with shadow. Points at infinity (w = 0) stay on the far plane.
struct VolumeVertexShader {
  static constexpr float kDepthOffset = 1e-5f;  // 2^24 x 1e-5 / 2: about 84 units of the 24-bit depth buffer
  const Vec4f* positions;
  Mat4f view_projection;

  VertexOut<NoVaryings> operator()(uint32_t i) const {
    Vec4f clip = gl_transform(view_projection, positions[i]);
    if (positions[i].w != 0) clip.z += kDepthOffset * clip.w;
    return {clip, {}};
  }
};

/// The volumes write no color: any fragment program will do.
struct NoColor {
  bool operator()(const NoVaryings&, Vec3f& color) const {
    color = Vec3f(0);
    return true;
  }
};

/// An undirected edge (lo < hi) and the direction a facing triangle walks it: +1 lo -> hi, -1 hi -> lo.
struct EdgeUse {
  uint32_t lo, hi;
  int sign;
};

}  // namespace

ShadowVolume shadow_volume(std::span<const Vec3f> positions, std::span<const uint32_t> indices, const Vec4f& light) {
  if (!(std::isfinite(light.x) && std::isfinite(light.y) && std::isfinite(light.z) && std::isfinite(light.w)) ||
      light == Vec4f(0))
    throw InvalidInput("shadow_volume: the light must be finite and not (0, 0, 0, 0)");
  if (indices.size() % 3 != 0)
    throw InvalidInput(fmt::format("shadow_volume: {} indices are not whole triangles", indices.size()));
  const auto n = uint32_t(positions.size());
  for (size_t k = 0; k < indices.size(); ++k)
    if (indices[k] >= n)
      throw InvalidInput(
          fmt::format("shadow_volume: index {} (triangle {}) is out of range for {} vertices", indices[k], k / 3, n));
  ShadowVolume volume;
  volume.positions.resize(2 * size_t(n));
  const Vec3f l(light);
  for (uint32_t i = 0; i < n; ++i) {
    volume.positions[i] = Vec4f(positions[i], 1.0f);
    volume.positions[n + i] = Vec4f(light.w * positions[i] - l, 0.0f);  // away from the light, at infinity
  }
  std::vector<EdgeUse> uses;
  for (size_t k = 0; k < indices.size(); k += 3) {
    const uint32_t t[3] = {indices[k], indices[k + 1], indices[k + 2]};
    const Vec3f a = positions[t[0]], b = positions[t[1]], c = positions[t[2]];
    if (!(glm::dot(glm::cross(b - a, c - a), l - light.w * a) > 0)) continue;
    volume.caps.insert(volume.caps.end(), {t[0], t[1], t[2], n + t[0], n + t[2], n + t[1]});
    for (int e = 0; e < 3; ++e) {
      const uint32_t from = t[e], to = t[(e + 1) % 3];
      uses.push_back(from < to ? EdgeUse{from, to, 1} : EdgeUse{to, from, -1});
    }
  }
  // Sum each edge's uses: interior edges of the facing region cancel, its boundary remains (with multiplicity on
  // non-manifold edges).
  std::sort(uses.begin(), uses.end(),
            [](const EdgeUse& x, const EdgeUse& y) { return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi; });
  for (size_t k = 0; k < uses.size();) {
    int m = 0;
    size_t end = k;
    for (; end < uses.size() && uses[end].lo == uses[k].lo && uses[end].hi == uses[k].hi; ++end) m += uses[end].sign;
    const uint32_t from = m > 0 ? uses[k].lo : uses[k].hi, to = m > 0 ? uses[k].hi : uses[k].lo;
    for (int r = 0; r < std::abs(m); ++r)
      volume.sides.insert(volume.sides.end(), {from, n + from, to, to, n + from, n + to});
    k = end;
  }
  return volume;
}

DrawStats draw_shadow_volume(Framebuffer& framebuffer, const RasterState& state, const ShadowVolume& volume,
                             const Mat4f& view_projection, ShadowCount count) {
  if (count == ShadowCount::zfail) {
    // Points at infinity must land on the far plane (clip z = w), not beyond it: rows 2 and 3 equal in x, y, z.
    for (int c = 0; c < 3; ++c)
      if (view_projection[c][2] != view_projection[c][3])
        throw InvalidInput(
            "draw_shadow_volume: z-fail needs a projection with the far plane at infinity (infinite_perspective)");
  }
  RasterState s = state;
  s.depth_test = true;
  s.depth_func = DepthFunc::less;
  s.depth_write = false;
  s.color_write = false;
  s.cull = CullMode::none;
  s.painter = false;
  s.stencil_test = true;
  s.stencil_front = s.stencil_back = StencilFace{};
  if (count == ShadowCount::zpass) {
    s.stencil_front.zpass = StencilOp::incr_wrap;
    s.stencil_back.zpass = StencilOp::decr_wrap;
  } else {
    s.stencil_back.zfail = StencilOp::incr_wrap;
    s.stencil_front.zfail = StencilOp::decr_wrap;
  }
  const VolumeVertexShader vs{volume.positions.data(), view_projection};
  const auto vertices = uint32_t(volume.positions.size());
  DrawStats stats = draw_triangles(framebuffer, s, vertices, volume.sides, vs, NoColor{});
  if (count == ShadowCount::zfail) {
    const DrawStats caps = draw_triangles(framebuffer, s, vertices, volume.caps, vs, NoColor{});
    stats.primitives += caps.primitives;
    stats.rasterized += caps.rasterized;
  }
  return stats;
}

namespace {

/// Counts `volumes` into the stencil buffer, cleared to 0 first.
void count_volumes(Framebuffer& framebuffer, const RasterState& state, std::span<const ShadowVolume> volumes,
                   const Mat4f& view_projection, ShadowCount count) {
  framebuffer.clear_stencil(0);
  for (const ShadowVolume& volume : volumes) draw_shadow_volume(framebuffer, state, volume, view_projection, count);
}

/// The state of a lit pass: exactly the visible surface drawn again (depth func equal), where no volume holds it
/// (stencil equal to ref 0).
RasterState unshadowed(const RasterState& base) {
  RasterState lit = base;
  lit.depth_func = DepthFunc::equal;
  lit.stencil_test = true;
  lit.stencil_front.func = lit.stencil_back.func = DepthFunc::equal;
  return lit;
}

}  // namespace

void draw_with_shadow_volumes(Framebuffer& framebuffer, std::span<const ShadowVolume> volumes,
                              const Mat4f& view_projection, ShadowCount count,
                              const std::function<void(const RasterState& state, float light0)>& draw) {
  const RasterState base;
  draw(base, 0.0f);
  count_volumes(framebuffer, base, volumes, view_projection, count);
  draw(unshadowed(base), 1.0f);
}

void draw_lights_with_shadow_volumes(Framebuffer& framebuffer, std::span<const std::vector<ShadowVolume>> volumes,
                                     const Mat4f& view_projection, ShadowCount count,
                                     const std::function<void(const RasterState& state, int light)>& draw) {
  const RasterState base;
  draw(base, -1);
  RasterState add = unshadowed(base);
  add.blend = true;
  add.blend_function = {BlendFactor::one, BlendFactor::one};
  for (size_t i = 0; i < volumes.size(); ++i) {
    count_volumes(framebuffer, base, volumes[i], view_projection, count);
    draw(add, int(i));
  }
}

}  // namespace tessera::raster3d
