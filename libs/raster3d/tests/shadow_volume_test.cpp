// Shadow volumes against independent references: the silhouette of a cube worked by hand, the volume's closedness,
// and the shadows on a floor against rays cast from each visible floor point to the light (brute-force
// Moller-Trumbore in double precision).
#include "tessera/raster3d/shadow_volume.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "test_util.hpp"

using namespace tessera;
using namespace tessera::raster3d;
using raster3d::testing::FlatFragmentShader;
using raster3d::testing::FlatVertexShader;

namespace {

/// A triangle mesh in world space, as the volumes and the ray casts see it.
struct Caster {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;
};

/// mesh scaled by s and moved to center.
Caster place(const PolyMesh& mesh, double s, const Vec3& center) {
  const TriMesh tri = to_tri_mesh(mesh);
  Caster c;
  for (const Vec3& p : tri.positions) c.positions.push_back(Vec3f(center + s * p));
  c.indices = tri.indices;
  return c;
}

/// A floor square at y = 0, [-r, r] in x and z, facing up.
Caster floor_square(float r) { return {{{-r, 0, -r}, {-r, 0, r}, {r, 0, r}, {r, 0, -r}}, {0, 1, 2, 0, 2, 3}}; }

/// Whether the segment from p to the light crosses a caster triangle (double precision, t in (1e-6, 1)).
bool ray_blocked(const Vec3& p, const Vec3& light, const std::vector<Caster>& casters) {
  const Vec3 d = light - p;
  for (const Caster& c : casters)
    for (size_t k = 0; k < c.indices.size(); k += 3) {
      const Vec3 a(c.positions[c.indices[k]]), b(c.positions[c.indices[k + 1]]), q(c.positions[c.indices[k + 2]]);
      const Vec3 e1 = b - a, e2 = q - a, pv = glm::cross(d, e2);
      const double det = glm::dot(e1, pv);
      if (std::abs(det) < 1e-14) continue;
      const Vec3 tv = p - a;
      const double u = glm::dot(tv, pv) / det;
      const Vec3 qv = glm::cross(tv, e1);
      const double v = glm::dot(d, qv) / det, t = glm::dot(e2, qv) / det;
      if (u >= 0 && v >= 0 && u + v <= 1 && t > 1e-6 && t < 1) return true;
    }
  return false;
}

constexpr int kWidth = 200, kHeight = 150;
const Vec3f kFloorColor(0, 0, 1), kCasterColor(1, 0, 0);

/// Casters over a floor, seen from an eye: what the pictures draw and the reference casts rays through.
struct Scene {
  std::vector<Caster> casters = {place(make_cube(), 0.9, {0, 1.2, 0}),
                                 place(make_uv_sphere(24, 12), 0.6, {-1.3, 0.8, 0.6})};
  Caster floor = floor_square(6);
  Mat4 vp;

  Scene(const Vec3& eye, const Vec3& center, ShadowCount count) {
    const Mat4 projection = count == ShadowCount::zfail
                                ? infinite_perspective(radians(60), double(kWidth) / kHeight, 0.05)
                                : perspective(radians(60), double(kWidth) / kHeight, 0.05, 100);
    vp = projection * look_at(eye, center, {0, 1, 0});
  }

  /// The casters' shadow volumes for a point light.
  std::vector<ShadowVolume> volumes(const Vec3& light) const {
    std::vector<ShadowVolume> out;
    for (const Caster& c : casters) out.push_back(shadow_volume(c.positions, c.indices, Vec4f(Vec3f(light), 1)));
    return out;
  }

  /// Draws the casters and the floor, flat colored.
  void draw(Framebuffer& fb, const RasterState& state, const Vec3f& caster_color, const Vec3f& floor_color) const {
    for (const Caster& c : casters)
      draw_triangles(fb, state, uint32_t(c.positions.size()), c.indices,
                     FlatVertexShader{c.positions.data(), Mat4f(vp)}, FlatFragmentShader{caster_color});
    draw_triangles(fb, state, 4, floor.indices, FlatVertexShader{floor.positions.data(), Mat4f(vp)},
                   FlatFragmentShader{floor_color});
  }
};

/// A picture's shadow of one light against the reference shadow of every visible floor pixel.
struct ShadowCheck {
  int floor_pixels = 0, shadowed = 0, mismatches = 0, off_edge = 0;
};

/// Compares the floor pixels of fb (those with blue; the casters have none) that `lit` calls lit with rays cast from
/// each one's point, from its depth, to the light.
template <class Lit>
ShadowCheck check_shadow(const Framebuffer& fb, const Scene& scene, const Vec3& light, Lit lit) {
  const Mat4 to_world = glm::inverse(scene.vp);
  std::vector<int> reference(size_t(kWidth) * kHeight, -1);  // -1 not floor, 0 lit, 1 shadowed
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (fb.color()(x, y).z == 0) continue;
      const double z = 2.0 * fb.depth()(x, y) / kDepthMax - 1;
      const Vec4 ndc((x + 0.5) / kWidth * 2 - 1, 1 - (y + 0.5) / kHeight * 2, z, 1);
      const Vec4 w = to_world * ndc;
      Vec3 p = Vec3(w) / w.w;
      p.y = 0;  // on the floor (the depth's rounding moves it by a little)
      reference[size_t(y) * kWidth + x] = ray_blocked(p, light, scene.casters) ? 1 : 0;
    }
  ShadowCheck check;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int ref = reference[size_t(y) * kWidth + x];
      if (ref < 0) continue;
      ++check.floor_pixels;
      check.shadowed += ref;
      if (lit(fb.color()(x, y)) == (ref == 0)) continue;
      ++check.mismatches;
      // A pixel whose center lies within a pixel of the shadow's outline may go either way.
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= kWidth || yy >= kHeight) continue;
          const int other = reference[size_t(yy) * kWidth + xx];
          edge = edge || (other >= 0 && other != ref) || other < 0;
        }
      if (!edge) ++check.off_edge;
    }
  return check;
}

/// The casters and floor with shadow volumes for one light (the floor blue, 40% dark in shadow), checked.
ShadowCheck render(const Vec3& eye, const Vec3& center, const Vec3& light, ShadowCount count) {
  const Scene scene(eye, center, count);
  Framebuffer fb(kWidth, kHeight);
  fb.clear({0, 0, 0});
  draw_with_shadow_volumes(fb, scene.volumes(light), Mat4f(scene.vp), count,
                           [&](const RasterState& state, float light0) {
                             const float k = 0.4f + 0.6f * light0;
                             scene.draw(fb, state, k * kCasterColor, k * kFloorColor);
                           });
  return check_shadow(fb, scene, light, [](const glm::u8vec4& c) { return c.z >= 200; });
}

/// Whether every directed edge of the volume's triangles has its reverse: a closed, consistently oriented surface.
bool closed(const ShadowVolume& v) {
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (const auto* list : {&v.sides, &v.caps})
    for (size_t k = 0; k < list->size(); k += 3)
      for (int e = 0; e < 3; ++e) {
        const uint32_t a = (*list)[k + e], b = (*list)[k + (e + 1) % 3];
        ++edges[{a, b}];
        --edges[{b, a}];
      }
  for (const auto& [edge, balance] : edges)
    if (balance != 0) return false;
  return true;
}

}  // namespace

TEST(ShadowVolume, CubeSilhouetteIsTheOutlineSeenFromTheLight) {
  const Caster cube = place(make_cube(), 1, {0, 0, 0});
  // Seen along a diagonal, three faces face the light and the outline is a hexagon: six edges.
  const ShadowVolume diagonal = shadow_volume(cube.positions, cube.indices, Vec4f(1, 1, 1, 0));
  EXPECT_EQ(diagonal.sides.size(), 6u * 6);
  EXPECT_EQ(diagonal.caps.size(), 6u * 6);  // six facing triangles, near and far
  EXPECT_TRUE(closed(diagonal));
  // Straight above: the top face alone faces the light (the sides are edge-on), its square outline.
  const ShadowVolume above = shadow_volume(cube.positions, cube.indices, Vec4f(0, 1, 0, 0));
  EXPECT_EQ(above.sides.size(), 4u * 6);
  EXPECT_TRUE(closed(above));
  // A point light: the far vertices lie away from it, at infinity.
  const ShadowVolume point = shadow_volume(cube.positions, cube.indices, Vec4f(0, 5, 0, 1));
  ASSERT_EQ(point.positions.size(), 2 * cube.positions.size());
  for (size_t i = 0; i < cube.positions.size(); ++i) {
    const Vec4f far = point.positions[cube.positions.size() + i];
    EXPECT_EQ(far.w, 0);
    EXPECT_LT(glm::length(glm::normalize(Vec3f(far)) - glm::normalize(cube.positions[i] - Vec3f(0, 5, 0))), 1e-6f);
  }
  EXPECT_EQ(point.sides.size(), 4u * 6);
  EXPECT_TRUE(closed(point));
}

TEST(ShadowVolume, OpenAndNonManifoldMeshesGiveClosedVolumes) {
  // A single square: its boundary is the silhouette.
  const Caster square = floor_square(1);
  const ShadowVolume v = shadow_volume(square.positions, square.indices, Vec4f(0.3f, 4, 0.2f, 1));
  EXPECT_EQ(v.sides.size(), 4u * 6);
  EXPECT_TRUE(closed(v));
  // Facing away from the light: nothing.
  EXPECT_TRUE(shadow_volume(square.positions, square.indices, Vec4f(0, -4, 0, 1)).sides.empty());
  // Three triangles on one edge (a non-manifold fan), all facing up: the edge is walked twice one way and once the
  // other, so it is extruded once.
  const Caster fan = {{{0, 0, 0}, {1, 0, 0}, {0.5f, 0, -1}, {0.5f, 0, 1}, {0.4f, 0, 2}}, {0, 1, 2, 1, 0, 3, 1, 0, 4}};
  const ShadowVolume f = shadow_volume(fan.positions, fan.indices, Vec4f(0, 1, 0, 0));
  EXPECT_TRUE(closed(f));
}

TEST(ShadowVolume, ShadowsAreTheRayCastShadows) {
  for (const ShadowCount count : {ShadowCount::zpass, ShadowCount::zfail}) {
    const ShadowCheck pic = render({1.5, 3.5, 4}, {-0.5, 0, -0.5}, {3, 3, 2}, count);
    EXPECT_GT(pic.floor_pixels, 10000);
    EXPECT_GT(pic.shadowed, 1500);
    // Only pixels on the outline may differ, and few do.
    EXPECT_EQ(pic.off_edge, 0);
    EXPECT_LT(pic.mismatches, pic.floor_pixels / 200);
  }
}

TEST(ShadowVolume, ZFailIsRightWithTheEyeInShadowAndZPassIsNot) {
  // The eye low, in the cube's shadow (light straight above it), looking across the floor.
  const Vec3 eye(0.1, 0.3, 0.2), center(3, 0, 2), light(0, 8, 0);
  const ShadowCheck zfail = render(eye, center, light, ShadowCount::zfail);
  EXPECT_GT(zfail.floor_pixels, 10000);
  EXPECT_GT(zfail.shadowed, 1000);
  EXPECT_EQ(zfail.off_edge, 0);
  EXPECT_LT(zfail.mismatches, zfail.floor_pixels / 200);
  // z-pass misses the volume's faces cut off by the near plane: its counts are off by one over most of the floor.
  const ShadowCheck zpass = render(eye, center, light, ShadowCount::zpass);
  EXPECT_GT(zpass.mismatches, zpass.floor_pixels / 4);
}

TEST(ShadowVolume, SeveralLightsAddTheirPassesWhereEachIsUnshadowed) {
  // Two lights, one red and one green, over a floor and casters that reflect each fully: a floor pixel has red
  // exactly where the ray to the red light is free, and green where the ray to the green light is.
  const Vec3 eye(1.5, 3.5, 4), center(-0.5, 0, -0.5);
  const std::array<Vec3, 2> lights = {Vec3(3, 3, 2), Vec3(-2, 4, -1)};
  const std::array<Vec3f, 2> light_colors = {Vec3f(0.8f, 0, 0), Vec3f(0, 0.8f, 0)};
  for (const ShadowCount count : {ShadowCount::zpass, ShadowCount::zfail}) {
    const Scene scene(eye, center, count);
    const std::vector<std::vector<ShadowVolume>> volumes = {scene.volumes(lights[0]), scene.volumes(lights[1])};
    Framebuffer fb(kWidth, kHeight);
    fb.clear({0, 0, 0});
    std::vector<int> passes;
    draw_lights_with_shadow_volumes(fb, volumes, Mat4f(scene.vp), count, [&](const RasterState& state, int light) {
      passes.push_back(light);
      if (light < 0)
        scene.draw(fb, state, {0.1f, 0.1f, 0}, {0.1f, 0.1f, 0.5f});  // the ambient pass
      else
        scene.draw(fb, state, light_colors[size_t(light)], light_colors[size_t(light)]);
    });
    EXPECT_EQ(passes, (std::vector<int>{-1, 0, 1}));
    for (int i = 0; i < 2; ++i) {
      const ShadowCheck check =
          check_shadow(fb, scene, lights[size_t(i)], [i](const glm::u8vec4& c) { return c[i] > 128; });
      EXPECT_GT(check.floor_pixels, 10000);
      EXPECT_GT(check.shadowed, 1000) << "light " << i;
      EXPECT_EQ(check.off_edge, 0) << "light " << i;
      EXPECT_LT(check.mismatches, check.floor_pixels / 200) << "light " << i;
    }
    // The passes sum, exactly: a floor pixel's red and green are the ambient's 0.1 (26 of 255) or that plus the
    // light's 0.8 (204), its blue the ambient's 0.5. Each combination of lit and shadowed occurs.
    std::map<std::pair<int, int>, int> classes;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const glm::u8vec4 c = fb.color()(x, y);
        if (c.z == 0) continue;  // a caster
        ASSERT_EQ(c.z, 128);
        ASSERT_TRUE(c.x == 26 || c.x == 230) << int(c.x);
        ASSERT_TRUE(c.y == 26 || c.y == 230) << int(c.y);
        ++classes[{c.x, c.y}];
      }
    EXPECT_GT((classes[{230, 230}]), 5000);
    EXPECT_GT((classes[{26, 230}]), 500);
    EXPECT_GT((classes[{230, 26}]), 500);
  }
}

TEST(ShadowVolume, BadInputIsReported) {
  const Caster square = floor_square(1);
  EXPECT_THROW(shadow_volume(square.positions, square.indices, Vec4f(0)), InvalidInput);
  EXPECT_THROW(shadow_volume(square.positions, square.indices, Vec4f(NAN, 1, 0, 1)), InvalidInput);
  const std::vector<uint32_t> bad = {0, 1, 9};
  EXPECT_THROW(shadow_volume(square.positions, bad, Vec4f(0, 1, 0, 0)), InvalidInput);
  const std::vector<uint32_t> partial = {0, 1};
  EXPECT_THROW(shadow_volume(square.positions, partial, Vec4f(0, 1, 0, 0)), InvalidInput);
  // z-fail loses the far cap beyond a finite far plane: refused.
  Framebuffer fb(8, 8);
  const ShadowVolume v = shadow_volume(square.positions, square.indices, Vec4f(0, 1, 0, 0));
  const Mat4f finite(perspective(1.0, 1.0, 0.1, 10) * look_at({0, 3, 3}, {0, 0, 0}, {0, 1, 0}));
  EXPECT_THROW(draw_shadow_volume(fb, RasterState{}, v, finite, ShadowCount::zfail), InvalidInput);
  EXPECT_NO_THROW(draw_shadow_volume(fb, RasterState{}, v, finite, ShadowCount::zpass));
}
