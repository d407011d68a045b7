// The renderer against analytic answers: a sphere's image area, a furnace (a uniform white background seen through
// mirrors, glossy reflectors and glass under motion blur and depth of field), the visible fraction of a disk light
// behind an edge, motion-blur coverage, the thin lens, and identical images for any thread count.
#include "tessera/raytrace/render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/math/transform.hpp"

namespace tessera {
namespace {

RayScene camera_on_z(double distance, double fovy_deg) {
  RayScene scene;
  scene.camera.eye = {0, 0, distance};
  scene.camera.center = {0, 0, 0};
  scene.camera.fovy = radians(fovy_deg);
  return scene;
}

TEST(Render, SphereImageArea) {
  // A unit sphere seen from distance 5 subtends the half-angle asin(1/5); on the view plane (v in [-1, 1] over the
  // image height, focal length d = 1/tan(fovy/2)) its outline is the circle of radius tan(asin(1/5)) d.
  RayScene scene = camera_on_z(5, 40);
  Material white;
  white.diffuse = Vec3f(1.0f);
  scene.materials = {white};
  scene.ambient = Vec3f(1.0f);
  scene.world.add_shape(Sphere{{0, 0, 0}, 1}, Mat4(1.0), 0);
  scene.world.build();
  RenderSettings s;
  s.width = s.height = 201;
  s.progress = false;
  const double radius_px = std::tan(std::asin(0.2)) / std::tan(radians(20)) * s.height / 2;
  const double area = kPi * radius_px * radius_px, perimeter = 2 * kPi * radius_px;

  const ImageRGB one = render(scene, s);
  double covered = 0;
  for (const Vec3f& p : one.pixels()) covered += p.x > 0.5f ? 1 : 0;
  EXPECT_NEAR(covered, area, 0.1 * perimeter);

  s.samples = 64;  // antialiased: each pixel's value is its covered fraction
  const ImageRGB aa = render(scene, s);
  double coverage = 0;
  for (const Vec3f& p : aa.pixels()) coverage += p.x;
  EXPECT_NEAR(coverage, area, 0.01 * perimeter);
}

TEST(Render, FurnaceThroughMirrorsGlossAndGlass) {
  // Inside a uniform white background, surfaces that only reflect or transmit (weights summing to one) are
  // invisible: every pixel equals the background, whatever the sampling (glossy lobes, lens, time).
  RayScene scene = camera_on_z(6, 50);
  scene.background = Vec3f(1.0f);
  scene.ambient = Vec3f(0.0f);
  scene.aperture = 0.2f;
  Material glossy;
  glossy.diffuse = Vec3f(0.0f);
  glossy.reflection = Vec3f(1.0f);
  glossy.glossiness = 0.3f;
  Material glass;
  glass.diffuse = Vec3f(0.0f);
  glass.transmission = Vec3f(1.0f);
  scene.materials = {glossy, glass};
  Motion moving;
  moving.velocity = {0.5f, 0, 0};
  scene.world.add_shape(Sphere{{-1.2f, 0, 0}, 1}, Mat4(1.0), 0, moving);
  scene.world.add_shape(Sphere{{1.2f, 0, 0}, 1}, Mat4(1.0), 1);
  scene.world.build();
  RenderSettings s;
  s.width = 64;
  s.height = 48;
  s.samples = 9;
  s.max_depth = 8;
  s.progress = false;
  const ImageRGB img = render(scene, s);
  for (const Vec3f& p : img.pixels()) {
    ASSERT_NEAR(p.x, 1.0f, 1e-4);
    ASSERT_NEAR(p.z, 1.0f, 1e-4);
  }
  // With Fresnel a glass sphere alone splits each ray into reflected and refracted parts whose weights still sum to
  // one. The chain of internal reflections ends at a node whose weight is below min_contribution (the depth limit
  // is out of reach), dropping its two branches: each eye ray loses less than 2 min_contribution.
  RayScene alone = camera_on_z(6, 50);
  alone.background = Vec3f(1.0f);
  alone.ambient = Vec3f(0.0f);
  glass.fresnel = true;
  alone.materials = {glass};
  alone.world.add_shape(Sphere{{0, 0, 0}, 1.5f}, Mat4(1.0), 0, moving);
  alone.world.build();
  s.max_depth = RenderSettings::kMaxDepth;
  const ImageRGB fresnel = render(alone, s);
  for (const Vec3f& p : fresnel.pixels()) {
    ASSERT_LE(p.y, 1.0f + 1e-5f);
    ASSERT_GE(p.y, 1.0f - 2 * s.min_contribution);
  }
}

/// Area of the part x > a of the disk of radius r centered at the origin.
double disk_part_beyond(double a, double r) { return r * r * std::acos(a / r) - a * std::sqrt(r * r - a * a); }

TEST(Render, SoftShadowVisibleFractionOfADiskLight) {
  // A disk light of radius 1 at height 4 shining down; a thin blocker fills x < edge at height 3.9. From the origin
  // the blocker's edge projects onto the light at x = edge * 4 / 3.9, so the visible fraction is the disk's part
  // beyond that line over pi r^2. n stratified shadow rays estimate it within the binomial 4-sigma bound.
  RayScene scene;
  Light light;
  light.type = LightType::disk;
  light.position = {0, 4, 0};
  light.direction = {0, -1, 0};
  light.radius = 1;
  scene.lights = {light};
  scene.materials = {Material{}};
  for (double edge : {-0.5, 0.0, 0.3, 0.8}) {
    RayScene s;
    s.lights = scene.lights;
    s.materials = scene.materials;
    s.world.add_shape(Box{{-20, 3.85f, -20}, {float(edge), 3.9f, 20}}, Mat4(1.0), 0);
    s.world.build();
    const double a = edge * 4 / 3.9;
    const double expected = a >= 1 ? 0 : disk_part_beyond(a, 1) / kPi;
    const int n = 400;
    for (uint32_t pattern : {1u, 2u, 3u}) {
      const float f = visible_fraction(s, {0, 0, 0}, light, n, pattern);
      EXPECT_NEAR(f, expected, 4 * std::sqrt(expected * (1 - expected) / n) + 1.0 / n) << edge;
    }
  }
  // Umbra and full light: a point light is either visible or not.
  Light point;
  point.position = {0, 4, 0};
  RayScene blocked;
  blocked.materials = scene.materials;
  blocked.world.add_shape(Box{{-20, 3.85f, -20}, {0.5f, 3.9f, 20}}, Mat4(1.0), 0);
  blocked.world.build();
  EXPECT_EQ(visible_fraction(blocked, {0, 0, 0}, point, 1, 0), 0.0f);
  EXPECT_EQ(visible_fraction(blocked, {30, 0, 0}, point, 1, 0), 1.0f);  // passes the edge at x = 0.75
}

TEST(Render, ShadedPointFollowsTheNotesSum) {
  // One point light straight above a white floor: C = C_r (C_a + C_L (N . L)) with N . L = 1, plus the Phong
  // highlight (E . R)^P = 1 seen from straight above.
  RayScene scene = camera_on_z(1, 10);
  scene.camera.eye = {0, 3, 0};
  scene.camera.up = {0, 0, -1};
  scene.ambient = Vec3f(0.1f);
  Material m;
  m.diffuse = {0.5f, 0.25f, 1.0f};
  m.specular = Vec3f(0.2f);
  m.shininess = 10;
  scene.materials = {m};
  Light light;
  light.position = {0, 5, 0};
  light.color = Vec3f(0.5f);
  scene.lights = {light};
  scene.world.add_shape(Plane{{0, 0, 0}, {0, 1, 0}}, Mat4(1.0), 0);
  scene.world.build();
  RenderSettings s;
  Ray ray;
  ray.origin = {0, 3, 0};
  ray.dir = {0, -1, 0};
  const Vec3f c = trace_ray(scene, s, ray);
  const Vec3f expected = m.diffuse * (0.1f + 0.5f * 1.0f) + 0.5f * m.specular;
  EXPECT_NEAR(c.x, expected.x, 1e-5);
  EXPECT_NEAR(c.y, expected.y, 1e-5);
  EXPECT_NEAR(c.z, expected.z, 1e-5);
  // A blocker between the point and the light leaves only the ambient term (visible(P, L) = 0).
  scene.world.add_shape(Sphere{{0, 4, 0}, 0.5f}, Mat4(1.0), 0);
  scene.world.build();
  const Vec3f shadowed = trace_ray(scene, s, ray);
  EXPECT_NEAR(shadowed.x, m.diffuse.x * 0.1f, 1e-5);

  // A blocker that moves across the light casts its shadow where it is at the ray's time: between the point and the
  // light at mid-shutter only.
  RayScene moving = std::move(scene);
  moving.world = World();
  moving.world.add_shape(Plane{{0, 0, 0}, {0, 1, 0}}, Mat4(1.0), 0);
  Motion sweep;
  sweep.velocity = {8, 0, 0};
  moving.world.add_shape(Sphere{{-4, 4, 0}, 0.5f}, Mat4(1.0), 0, sweep);
  moving.world.build();
  for (const float time : {0.0f, 0.5f, 0.9f}) {
    ray.time = time;
    EXPECT_NEAR(trace_ray(moving, s, ray).x, time == 0.5f ? m.diffuse.x * 0.1f : expected.x, 1e-5) << time;
  }
}

TEST(Render, MirrorSeesWhatReflectsAndDepthStopsIt) {
  // A perfect mirror floor below an emissive ceiling: the eye ray sees K_refl times the ceiling's emission, and with
  // max_depth 1 (no secondary rays) only the mirror's own terms.
  RayScene scene;
  Material mirror;
  mirror.diffuse = Vec3f(0.0f);
  mirror.reflection = Vec3f(0.9f);
  Material glow;
  glow.diffuse = Vec3f(0.0f);
  glow.emission = {0.2f, 0.4f, 0.6f};
  scene.materials = {mirror, glow};
  scene.world.add_shape(Plane{{0, 0, 0}, {0, 1, 0}}, Mat4(1.0), 0);
  scene.world.add_shape(Plane{{0, 10, 0}, {0, -1, 0}}, Mat4(1.0), 1);
  scene.world.build();
  RenderSettings s;
  Ray ray;
  ray.origin = {0, 5, 0};
  ray.dir = glm::normalize(Vec3f(1, -1, 0));
  EXPECT_NEAR(trace_ray(scene, s, ray).z, 0.9f * 0.6f, 1e-6);
  s.max_depth = 1;
  EXPECT_EQ(trace_ray(scene, s, ray), Vec3f(0.0f));
  // The vanishing-contribution rule: a weight below min_contribution is not traced.
  s.max_depth = 5;
  scene.materials[0].reflection = Vec3f(1e-4f);
  EXPECT_EQ(trace_ray(scene, s, ray), Vec3f(0.0f));
}

TEST(Render, MotionBlurCoverageIsTheTimeFraction) {
  // A wall whose right edge moves from x = -0.5 to x = +0.5 over the shutter covers the center ray (x = 0) for half
  // the time; a 1-pixel image with a tiny field of view averages stratified times.
  RayScene scene = camera_on_z(10, 0.01);
  scene.ambient = Vec3f(1.0f);
  Material white;
  white.diffuse = Vec3f(1.0f);
  scene.materials = {white};
  Motion m;
  m.velocity = {1, 0, 0};
  scene.world.add_shape(Box{{-10.5f, -5, -1}, {-0.5f, 5, 0}}, Mat4(1.0), 0, m);
  scene.world.build();
  RenderSettings s;
  s.width = s.height = 1;
  s.progress = false;
  for (int n : {4, 9, 16, 64, 100}) {  // up to 16 the Rng-drawn patterns, beyond the hashed ones
    s.samples = n;
    EXPECT_NEAR(render(scene, s)(0, 0).x, 0.5f, 1.0f / float(n) + 1e-5f) << n;
  }
  // Two transforms instead of a velocity: the same sweep.
  RayScene two = camera_on_z(10, 0.01);
  two.ambient = Vec3f(1.0f);
  two.materials = {white};
  Motion ends;
  ends.has_end = true;
  ends.end_transform = translate(1, 0, 0);
  two.world.add_shape(Box{{-10.5f, -5, -1}, {-0.5f, 5, 0}}, Mat4(1.0), 0, ends);
  two.world.build();
  s.samples = 64;
  EXPECT_NEAR(render(two, s)(0, 0).x, 0.5f, 1.0f / 64 + 1e-5f);
}

TEST(Render, ThinLensRaysMeetOnTheFocalPlane) {
  RayScene scene = camera_on_z(5, 45);
  scene.aperture = 0.5f;
  scene.focal_distance = 3.0f;
  Camera cam = scene.camera;
  const EyeRays rays(cam, 32, 32);
  const Ray pin = rays.ray(20, 7, 0.5, 0.5);
  const Vec3f focus = pin.origin + (3.0f / -pin.dir.z) * pin.dir;  // the focal plane is z = 5 - 3
  for (Vec2f lens : {Vec2f(0.1f, 0.2f), Vec2f(0.9f, 0.5f), Vec2f(0.5f, 0.99f)}) {
    const Ray r = eye_ray(scene, 32, 32, 20, 7, Vec2f(0.5f), lens, 0.0f);
    EXPECT_NEAR(r.origin.z, 5.0f, 1e-6);
    EXPECT_LE(glm::length(r.origin - pin.origin), 0.5f + 1e-6f);
    const Vec3f at = r.origin + ((r.origin.z - 2.0f) / -r.dir.z) * r.dir;
    EXPECT_NEAR(glm::length(at - focus), 0.0f, 1e-5);
  }
}

TEST(Render, PinholeEyeRaysAreTheNotesEyeRays) {
  // The renderer's float eye rays against the math module's double EyeRays (u = (2 (i + dx) / w - 1) aspect, ...).
  RayScene scene;
  scene.camera.eye = {0, 1.6, 6.5};
  scene.camera.center = {0, 0.9, 0};
  scene.camera.fovy = radians(40.0);
  Camera cam = scene.camera;
  cam.aspect = 640.0 / 480.0;
  const EyeRays rays(cam, 640, 480);
  for (const auto& [x, y, dx, dy] : {std::tuple{0, 0, 0.0f, 0.0f}, std::tuple{639, 479, 0.99f, 0.99f},
                                     std::tuple{320, 17, 0.25f, 0.75f}, std::tuple{5, 400, 0.5f, 0.5f}}) {
    const Ray want = rays.ray(x, y, dx, dy);
    const Ray got = eye_ray(scene, 640, 480, x, y, {dx, dy}, Vec2f(0.5f), 0.0f);
    EXPECT_EQ(got.origin, want.origin);
    EXPECT_NEAR(glm::length(got.dir - want.dir), 0.0f, 1e-6f) << x << " " << y;
  }
}

TEST(Render, OrthographicEyeRaysAreTheNotesEyeRays) {
  // An orthographic camera: every ray along the gaze, from eye + (h/2)(u u + v v), as EyeRays has it; the corner
  // pixel's origin by hand (h = 3, aspect 2: u spans [-3, 3] and v [-1.5, 1.5] about the eye).
  RayScene scene;
  scene.camera.eye = {1, 2, 5};
  scene.camera.center = {1, 2, 0};
  scene.camera.orthographic = true;
  scene.camera.ortho_height = 3;
  Camera cam = scene.camera;
  cam.aspect = 2;
  const EyeRays rays(cam, 64, 32);
  for (const auto& [x, y, dx, dy] :
       {std::tuple{0, 0, 0.0f, 0.0f}, std::tuple{63, 31, 0.99f, 0.99f}, std::tuple{20, 17, 0.25f, 0.75f}}) {
    const Ray want = rays.ray(x, y, dx, dy);
    const Ray got = eye_ray(scene, 64, 32, x, y, {dx, dy}, Vec2f(0.5f), 0.0f);
    EXPECT_NEAR(glm::length(got.origin - want.origin), 0.0f, 1e-5f) << x << " " << y;
    EXPECT_EQ(got.dir, Vec3f(0, 0, -1));
  }
  EXPECT_NEAR(glm::length(eye_ray(scene, 64, 32, 0, 0, Vec2f(0.0f), Vec2f(0.5f), 0.0f).origin - Vec3f(-2, 3.5f, 5)),
              0.0f, 1e-5f);
}

RayScene busy_scene() {
  RayScene scene = camera_on_z(7, 45);
  scene.aperture = 0.1f;
  Material floor;
  floor.checker = 1.0f;
  floor.diffuse = Vec3f(0.9f);
  Material glossy;
  glossy.reflection = Vec3f(0.8f);
  glossy.glossiness = 0.2f;
  glossy.specular = Vec3f(0.5f);
  Material glass;
  glass.diffuse = Vec3f(0.0f);
  glass.transmission = Vec3f(0.9f);
  glass.fresnel = true;
  scene.materials = {floor, glossy, glass};
  Light area;
  area.type = LightType::rect;
  area.position = {-1, 4, -1};
  area.edge_u = {2, 0, 0};
  area.edge_v = {0, 0, 2};
  area.samples = 4;
  area.direction = {0, -1, 0};
  area.color = Vec3f(0.8f);
  // The rectangle shines along edge_u x edge_v = (0, -4, 0): down.
  scene.lights = {area};
  Motion m;
  m.velocity = {0.3f, 0, 0};
  scene.world.add_shape(Plane{{0, -1, 0}, {0, 1, 0}}, Mat4(1.0), 0);
  scene.world.add_shape(Sphere{{-1, 0, 0}, 1}, Mat4(1.0), 1, m);
  scene.world.add_shape(Sphere{{1.2f, 0, 1}, 0.8f}, Mat4(1.0), 2);
  add_light_surfaces(scene);
  scene.world.build();
  return scene;
}

TEST(Render, IdenticalForAnyThreadCount) {
  const RayScene scene = busy_scene();
  RenderSettings s;
  s.width = 72;
  s.height = 40;
  s.samples = 4;
  s.tile_size = 8;
  s.progress = false;
  ImageRGB one, two, all;
  {
    const ThreadLimit limit(1);
    one = render(scene, s);
  }
  {
    const ThreadLimit limit(2);
    two = render(scene, s);
  }
  all = render(scene, s);
  ASSERT_EQ(one.pixels().size(), all.pixels().size());
  EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), two.pixels().begin()));
  EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), all.pixels().begin()));
  // The picture is not trivially uniform.
  float lo = 1e9f, hi = -1e9f;
  for (const Vec3f& p : one.pixels()) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
  EXPECT_GT(hi - lo, 0.3f);
}

TEST(Render, RejectsBadSettings) {
  RayScene scene = busy_scene();
  RenderSettings s;
  s.width = 0;
  EXPECT_THROW(render(scene, s), InvalidInput);
  s.width = 8;
  s.samples = 0;
  EXPECT_THROW(render(scene, s), InvalidInput);
  s.samples = 1;
  // Recursion deeper than kMaxDepth is refused: two facing mirrors would recurse until the stack overflowed.
  s.max_depth = RenderSettings::kMaxDepth + 1;
  EXPECT_THROW(render(scene, s), InvalidInput);
  EXPECT_THROW(trace_ray(scene, s, Ray{{0, 0, 5}, {0, 0, -1}}), InvalidInput);
  s.max_depth = 0;
  EXPECT_THROW(render(scene, s), InvalidInput);
  s.max_depth = RenderSettings::kMaxDepth;
  EXPECT_NO_THROW(trace_ray(scene, s, Ray{{0, 0, 5}, {0, 0, -1}}));
  scene.materials.resize(1);
  EXPECT_THROW(render(scene, s), InvalidInput);
}

}  // namespace
}  // namespace tessera
