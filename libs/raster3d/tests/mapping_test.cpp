// Texture, bump, environment and shadow mapping against analytic references: the plane seen in perspective (its
// texture coordinates and their screen derivatives by ray casting), the exact normal of a displaced plane, a mirror
// sphere's reflected directions, and a square's shadow as its projection along the light.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <span>

#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/pipeline.hpp"
#include "tessera/raster3d/surface_shader.hpp"

namespace tessera::raster3d {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The floor y = 0, x and z in [-2, 2], as two triangles with u = (x + 2) / 4 and v = (z + 2) / 4, normal +y.
VertexArrays floor_quad(float half = 2) {
  VertexArrays a;
  a.positions = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
  a.normals.assign(4, Vec3f(0, 1, 0));
  a.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  a.indices = {0, 2, 1, 0, 3, 2};
  return a;
}

/// The world point of the plane y = 0 seen through GL window position (x, y) by the camera view_projection, or
/// nothing when the ray misses it.
std::optional<Vec3> floor_point(const Mat4& view_projection, int width, int height, double x, double y) {
  const Mat4 inverse = glm::inverse(view_projection);
  const auto unproject = [&](double z) {
    const glm::dvec4 p = inverse * glm::dvec4(2 * x / width - 1, 2 * y / height - 1, z, 1);
    return Vec3(p) / p.w;
  };
  const Vec3 a = unproject(-1), b = unproject(1);
  if (a.y * b.y >= 0) return std::nullopt;
  return a + (b - a) * (a.y / (a.y - b.y));
}

/// Records, per pixel, the interpolated uv and its derivatives; the pixel is found from the clip position (its
/// perspective-correct interpolation is the surface point's clip position, so x/w is the pixel center exactly).
struct ProbeVaryings {
  Vec2f uv;
  Vec3f clip;  // x, y, w
};
struct ProbeVertexShader {
  const VertexArrays* arrays;
  Mat4f view_projection;
  VertexOut<ProbeVaryings> operator()(uint32_t i) const {
    const Vec4f c = view_projection * Vec4f(arrays->positions[i], 1.0f);
    return {c, {arrays->uvs[i], Vec3f(c.x, c.y, c.w)}};
  }
};
struct Probe {
  Vec2f uv, ddx, ddy;
  bool set = false;
};
struct ProbeFragmentShader {
  std::vector<Probe>* probes;
  int width, height;
  bool operator()(const ProbeVaryings& in, const ProbeVaryings& ddx, const ProbeVaryings& ddy, Vec3f& color) const {
    const int i = int(std::floor((in.clip.x / in.clip.z + 1) * 0.5f * float(width)));
    const int j = int(std::floor((in.clip.y / in.clip.z + 1) * 0.5f * float(height)));
    if (i >= 0 && j >= 0 && i < width && j < height) (*probes)[size_t(j) * width + i] = {in.uv, ddx.uv, ddy.uv, true};
    color = Vec3f(1);
    return true;
  }
};

TEST(Derivatives, AreTheExactScreenDerivativesOfPerspectiveCorrectUvs) {
  const int w = 160, h = 120;
  const Mat4 view_projection =
      perspective(radians(60), double(w) / h, 0.5, 20) * look_at({0.3, 1.2, 2.6}, {0, 0, -0.5}, {0, 1, 0});
  const VertexArrays quad = floor_quad();
  Framebuffer fb(w, h);
  std::vector<Probe> probes(size_t(w) * h);
  draw_triangles(fb, RasterState{}, 4, quad.indices, ProbeVertexShader{&quad, Mat4f(view_projection)},
                 ProbeFragmentShader{&probes, w, h});
  const auto uv_at = [&](double x, double y) {
    const Vec3 p = *floor_point(view_projection, w, h, x, y);
    return glm::dvec2((p.x + 2) / 4, (p.z + 2) / 4);
  };
  int checked = 0;
  for (int j = 1; j + 1 < h; ++j)
    for (int i = 1; i + 1 < w; ++i) {
      const Probe& p = probes[size_t(j) * w + i];
      if (!p.set) continue;
      const double x = i + 0.5, y = j + 0.5, step = 1e-3;
      const glm::dvec2 uv = uv_at(x, y);
      const glm::dvec2 ddx = (uv_at(x + step, y) - uv_at(x - step, y)) / (2 * step);
      const glm::dvec2 ddy = (uv_at(x, y + step) - uv_at(x, y - step)) / (2 * step);
      ASSERT_NEAR(p.uv.x, uv.x, 2e-5) << i << " " << j;
      ASSERT_NEAR(p.uv.y, uv.y, 2e-5) << i << " " << j;
      const double scale = glm::length(ddx) + glm::length(ddy);
      ASSERT_NEAR(p.ddx.x, ddx.x, 2e-3 * scale) << i << " " << j;
      ASSERT_NEAR(p.ddx.y, ddx.y, 2e-3 * scale) << i << " " << j;
      ASSERT_NEAR(p.ddy.x, ddy.x, 2e-3 * scale) << i << " " << j;
      ASSERT_NEAR(p.ddy.y, ddy.y, 2e-3 * scale) << i << " " << j;
      ++checked;
    }
  EXPECT_GT(checked, w * h / 3);
}

/// Uniforms that show the surface color as it is (ambient 1, no lights): texture and environment tests.
SurfaceUniforms unlit_uniforms(const Mat4& projection, const Mat4& view) {
  SurfaceUniforms u;
  u.set_camera(projection, view);
  u.lighting = PreparedLighting(unlit_lighting());
  return u;
}

TEST(TextureMapping, APerspectiveCheckerboardIsTheRayCastPlanes) {
  // 8 x 8 checks, one texel each, nearest filtering: every pixel shows the check its ray hits.
  ImageRGBA checks(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) checks(x, y) = (x + y) % 2 ? Vec4f(1, 1, 1, 1) : Vec4f(0, 0, 0, 1);
  const Texture2D texture(checks, Sampler{.filter = Filter::nearest});
  const int w = 200, h = 150;
  const Mat4 projection = perspective(radians(55), double(w) / h, 0.5, 20);
  const Mat4 view = look_at({-0.4, 1.0, 2.7}, {0.2, 0, -0.8}, {0, 1, 0});
  SurfaceUniforms u = unlit_uniforms(projection, view);
  u.maps.texture = &texture;
  Framebuffer fb(w, h);
  fb.clear(Vec3f(0.5f));
  draw_surface(fb, RasterState{}, floor_quad(), u);
  int compared = 0, wrong = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const auto p = floor_point(projection * view, w, h, i + 0.5, j + 0.5);
      if (!p || std::abs(p->x) >= 2 || std::abs(p->z) >= 2) continue;
      // Texel (cx, cy) from the bottom-left is image pixel (cx, 7 - cy): white when cx + 7 - cy is odd.
      const int cx = std::min(7, int((p->x + 2) * 2)), cy = std::min(7, int((p->z + 2) * 2));
      const int expected = (cx + 7 - cy) % 2 ? 255 : 0;
      const int got = fb.color()(i, h - 1 - j).x;
      ++compared;
      if (got != expected) {
        // Only pixels whose center lies within a thousandth of a check of a check's edge may differ.
        const double fx = (p->x + 2) * 2 - std::floor((p->x + 2) * 2), fz = (p->z + 2) * 2 - std::floor((p->z + 2) * 2);
        EXPECT_LT(std::min({fx, 1 - fx, fz, 1 - fz}), 1e-3) << i << " " << j;
        ++wrong;
      }
    }
  EXPECT_GT(compared, w * h / 3);
  EXPECT_LT(wrong, compared / 1000 + 2);
}

TEST(TextureMapping, TrilinearFilteringUsesTheFootprintsLevel) {
  // A checker of single texels: every MIPmap level above 0 is uniform gray 1/2. Far floor pixels cover dozens of
  // texels: trilinear filtering shows them gray; bilinear filtering of level 0 sparkles between black and white.
  ImageRGBA fine(256, 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) fine(x, y) = (x + y) % 2 ? Vec4f(1, 1, 1, 1) : Vec4f(0, 0, 0, 1);
  const int w = 64;
  const Mat4 projection = perspective(radians(50), 1, 0.1, 100);
  const Mat4 view = look_at({0, 0.4, 2.2}, {0, 0, -2}, {0, 1, 0});  // the floor's far edge at the image center
  for (const Filter filter : {Filter::trilinear, Filter::bilinear}) {
    const Texture2D texture(fine, Sampler{.filter = filter});
    SurfaceUniforms u = unlit_uniforms(projection, view);
    u.maps.texture = &texture;
    Framebuffer fb(w, w);
    draw_surface(fb, RasterState{}, floor_quad(2), u);
    int least = 255, most = 0;
    for (int y = 34; y < 44; ++y)  // rows from the top, just below the far edge
      for (int x = 0; x < w; ++x) {
        least = std::min<int>(least, fb.color()(x, y).x);
        most = std::max<int>(most, fb.color()(x, y).x);
      }
    if (filter == Filter::trilinear) {
      EXPECT_GE(least, 124);
      EXPECT_LE(most, 131);
    } else {
      EXPECT_GT(most - least, 100);
    }
  }
}

TEST(BumpMapping, BlinnsNormalIsTheDisplacedPlanesNormal) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> d(-1, 1);
  for (int k = 0; k < 200; ++k) {
    const Vec3f p_s(d(rng), d(rng), d(rng)), p_t(d(rng), d(rng), d(rng));
    const Vec3f cross = glm::cross(p_s, p_t);
    if (glm::length(cross) < 0.1f) continue;
    const Vec3f n = glm::normalize(cross);
    const float b_u = d(rng), b_v = d(rng);
    // The plane P + B n has the partial derivatives P_s + B_u n and P_t + B_v n (n is constant on a plane).
    const Vec3f exact = glm::normalize(glm::cross(p_s + b_u * n, p_t + b_v * n));
    const Vec3f got = bump_normal(n, p_s, p_t, b_u, b_v);
    EXPECT_NEAR(glm::length(got - exact), 0, 2e-5f) << k;
    // A mirrored parameterization (the normal against P_s x P_t): the displaced surface's normal on n's side.
    const Vec3f mirrored = glm::normalize(glm::cross(p_t - b_v * n, p_s - b_u * n));
    EXPECT_NEAR(glm::length(bump_normal(-n, p_s, p_t, b_u, b_v) - mirrored), 0, 2e-5f) << k;
  }
  EXPECT_EQ(bump_normal({0, 0, 1}, {1, 0, 0}, {2, 0, 0}, 1, 1), Vec3f(0, 0, 1));  // no area: unchanged
}

/// An n x n gray texture sampling height(u, v) at the texel centers.
template <class Height>
Texture2D height_map(int n, const Height& height) {
  ImageRGBA image(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      // Texel (x, n - 1 - y) from the bottom-left sits at ((x + 0.5) / n, (n - 1 - y + 0.5) / n).
      const float value = float(height((x + 0.5) / n, (n - 1 - y + 0.5) / n));
      image(x, y) = Vec4f(value, value, value, 1);
    }
  return Texture2D(image);
}

TEST(BumpMapping, HeightSlopesAreTheAnalyticDerivatives) {
  const auto height = [](double u, double v) { return 0.5 + 0.4 * std::sin(2 * kPi * u) * std::cos(2 * kPi * v); };
  const Texture2D texture(height_map(256, height));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> d(0.1f, 0.9f);
  for (int k = 0; k < 100; ++k) {
    const float u = d(rng), v = d(rng);
    const Vec2f slope = height_gradient(texture, {u, v}, 0.5f);
    const double du = 0.5 * 0.4 * 2 * kPi * std::cos(2 * kPi * u) * std::cos(2 * kPi * v);
    const double dv = -0.5 * 0.4 * 2 * kPi * std::sin(2 * kPi * u) * std::sin(2 * kPi * v);
    EXPECT_NEAR(slope.x, du, 0.01) << u << " " << v;
    EXPECT_NEAR(slope.y, dv, 0.01) << u << " " << v;
  }
}

TEST(BumpMapping, TangentsOfAnAffineUvMapAreItsInverse) {
  // uv = A (x, z) + c on the grid: then dP/du, dP/dv are the columns of A^-1 (in x and z).
  PolyMesh grid = make_grid(4, 3);
  TriMesh mesh = to_tri_mesh(grid);
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    mesh.uvs[i] = {0.3 * mesh.positions[i].x + 0.1 * mesh.positions[i].z + 0.5,
                   -0.2 * mesh.positions[i].x + 0.4 * mesh.positions[i].z + 0.5};
  const VertexArrays a = VertexArrays::from_mesh(mesh);
  const UvTangents t = uv_tangents(a.positions, a.uvs, a.indices);
  const double det = 0.3 * 0.4 + 0.1 * 0.2;
  const Vec3f p_s(float(0.4 / det), 0, float(0.2 / det)), p_t(float(-0.1 / det), 0, float(0.3 / det));
  for (size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_NEAR(glm::length(t.u[i] - p_s), 0, 1e-4f);
    EXPECT_NEAR(glm::length(t.v[i] - p_t), 0, 1e-4f);
  }
  EXPECT_THROW(uv_tangents(a.positions, std::span<const Vec2f>(a.uvs).first(2), a.indices), InvalidInput);
  const std::vector<uint32_t> bad = {0, 1, 99};
  EXPECT_THROW(uv_tangents(a.positions, a.uvs, bad), InvalidInput);
}

TEST(DrawSurface, RefusesArraysThatDoNotFitTheMaps) {
  // A bump map without tangents, tangents of other arrays, missing uvs or normals.
  const VertexArrays a = VertexArrays::from_mesh(to_tri_mesh(make_grid(2, 2)));
  const UvTangents t = uv_tangents(a.positions, a.uvs, a.indices);
  const Texture2D bumps(ImageRGBA(4, 4, Vec4f(0.5f)));
  SurfaceUniforms u;
  u.maps.bump = &bumps;
  Framebuffer fb(8, 8);
  EXPECT_THROW(draw_surface(fb, RasterState{}, a, u), InvalidInput);
  const UvTangents other = uv_tangents(std::span<const Vec3f>(a.positions).first(3),
                                       std::span<const Vec2f>(a.uvs).first(3), std::vector<uint32_t>{0, 1, 2});
  EXPECT_THROW(draw_surface(fb, RasterState{}, a, u, &other), InvalidInput);
  VertexArrays bare = a;
  bare.uvs.clear();
  EXPECT_THROW(draw_surface(fb, RasterState{}, bare, u, &t), InvalidInput);
  bare = a;
  bare.normals.clear();
  EXPECT_THROW(draw_surface(fb, RasterState{}, bare, SurfaceUniforms{}), InvalidInput);
  EXPECT_NO_THROW(draw_surface(fb, RasterState{}, a, u, &t));
}

TEST(BumpMapping, ABumpMappedPlaneShadesAsTheDisplacedMesh) {
  // Seen straight down (orthographic), a plane displaced along its normal projects onto the same pixels as the flat
  // one, so the bump-mapped flat plane and a finely tessellated displaced plane, lit alike, must match pixel by pixel.
  const auto height = [](double u, double v) { return 0.5 + 0.5 * std::sin(4 * kPi * u) * std::sin(2 * kPi * v); };
  const float scale = 0.08f;
  const Texture2D bumps(height_map(512, height));
  const TriMesh flat = to_tri_mesh(make_grid(1, 1));
  const VertexArrays flat_arrays = VertexArrays::from_mesh(flat);
  const UvTangents tangents = uv_tangents(flat_arrays.positions, flat_arrays.uvs, flat_arrays.indices);
  const Vec3 p_s(tangents.u[0]), p_t(tangents.v[0]), up(0, 1, 0);
  // The displaced plane P + B up has the partial derivatives P_s + B_u up and P_t + B_v up.
  TriMesh displaced = to_tri_mesh(make_grid(200, 200));
  for (size_t i = 0; i < displaced.positions.size(); ++i) {
    const double u = displaced.uvs[i].x, v = displaced.uvs[i].y;
    displaced.positions[i].y = scale * height(u, v);
    const double b_u = scale * 0.5 * 4 * kPi * std::cos(4 * kPi * u) * std::sin(2 * kPi * v);
    const double b_v = scale * 0.5 * 2 * kPi * std::sin(4 * kPi * u) * std::cos(2 * kPi * v);
    const Vec3 normal = glm::normalize(glm::cross(p_s + b_u * up, p_t + b_v * up));
    displaced.normals[i] = normal.y < 0 ? -normal : normal;
  }
  const Mat4 projection = ortho(-1, 1, -1, 1, 1, 5);
  const Mat4 view = look_at({0, 3, 0}, {0, 0, 0}, {0, 0, -1});
  Lighting l;
  l.color_material = true;
  l.model_ambient = Vec3f(0.1f);
  l.lights[0].position = Vec4f(glm::normalize(Mat3f(view) * Vec3f(0.5f, 1, 0.3f)), 0);
  SurfaceUniforms u = unlit_uniforms(projection, view);
  u.lighting = PreparedLighting(l);
  u.color = Vec3f(0.8f);
  Framebuffer bumped(128, 128), reference(128, 128);
  draw_surface(reference, RasterState{}, VertexArrays::from_mesh(displaced), u);
  u.maps.bump = &bumps;
  u.maps.bump_scale = scale;
  draw_surface(bumped, RasterState{}, flat_arrays, u, &tangents);
  int close = 0, total = 0, lit_range = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const int a = bumped.color()(x, y).x, b = reference.color()(x, y).x;
      ++total;
      close += std::abs(a - b) <= 3;
      lit_range = std::max(lit_range, a);
    }
  EXPECT_GE(close, total * 99 / 100);
  EXPECT_GT(lit_range, 150);  // the comparison is not of two dark images
}

TEST(EnvironmentMapping, AMirrorSphereShowsTheReflectedDirections) {
  // Environment radiance 0.5 + 0.5 d: the color at a pixel tells the direction looked up.
  const int n = 1024;
  ImageRGBA latlong(n, n / 2);
  for (int y = 0; y < n / 2; ++y)
    for (int x = 0; x < n; ++x) {
      const Vec3f d = latlong_direction({(x + 0.5f) / n, 1 - (y + 0.5f) / (n / 2)});
      latlong(x, y) = Vec4f(0.5f + 0.5f * d, 1);
    }
  const EnvironmentMap environment(latlong);
  PolyMesh sphere = make_uv_sphere(256, 128);
  const VertexArrays arrays = VertexArrays::from_mesh(to_tri_mesh(sphere));
  const int w = 96;
  SurfaceUniforms u = unlit_uniforms(ortho(-1, 1, -1, 1, 1, 5), look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0}));
  u.color = Vec3f(0);
  u.maps.environment = &environment;
  u.maps.reflectivity = 1;
  Framebuffer fb(w, w);
  draw_surface(fb, RasterState{}, arrays, u);
  int compared = 0, close = 0;
  double worst = 0;
  for (int j = 0; j < w; ++j)
    for (int i = 0; i < w; ++i) {
      const double x = (i + 0.5) / w * 2 - 1, y = (j + 0.5) / w * 2 - 1;
      if (x * x + y * y > 0.8) continue;  // near the rim R turns fast; the facets then show
      const Vec3 normal(x, y, std::sqrt(1 - x * x - y * y)), eye(0, 0, 1);
      const Vec3 r = 2 * glm::dot(normal, eye) * normal - eye;
      const auto c = fb.color()(i, w - 1 - j);
      const double error = std::max({std::abs(c.x - 255 * (0.5 + 0.5 * r.x)), std::abs(c.y - 255 * (0.5 + 0.5 * r.y)),
                                     std::abs(c.z - 255 * (0.5 + 0.5 * r.z))});
      ++compared;
      close += error <= 2;
      worst = std::max(worst, error);
    }
  EXPECT_GT(compared, w * w / 2);
  EXPECT_GE(close, compared * 99 / 100);
  EXPECT_LT(worst, 6);
}

TEST(EnvironmentMapping, ARenderedCubeMapShowsWhatIsSeenFromItsCenter) {
  // A room, the cube [-2, 2]^3 with six walls of six colors, rendered 6 times from an off-center point: looking up a
  // direction must give the color of the wall that the ray from that point hits first (away from the room's edges).
  const Vec3f colors[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  VertexArrays room;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-2.0f, 2.0f}) {
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      const auto base = uint32_t(room.positions.size());
      for (const auto& [a, b] : {std::pair{-2.f, -2.f}, {2.f, -2.f}, {2.f, 2.f}, {-2.f, 2.f}}) {
        Vec3f p(0);
        p[axis] = side;
        p[i] = a;
        p[j] = b;
        room.positions.push_back(p);
        room.normals.push_back(Vec3f(0, 0, 1));  // unlit: unused
        room.colors.push_back(colors[2 * axis + (side > 0)]);
      }
      room.indices.insert(room.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  const Vec3 center(0.3, -0.4, 0.5);
  const CubeMap cube = render_cube_map(center, 64, [&](Framebuffer& fb, const Mat4& projection, const Mat4& view) {
    draw_surface(fb, RasterState{}, room, unlit_uniforms(projection, view));
  });
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> d(-1, 1);
  int checked = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 dir = glm::normalize(Vec3(d(rng), d(rng), d(rng)));
    // The first wall along the ray: the least positive t of the three slabs.
    double t_best = 1e30;
    int wall = -1;
    for (int axis = 0; axis < 3; ++axis) {
      const double t = ((dir[axis] > 0 ? 2.0 : -2.0) - center[axis]) / dir[axis];
      if (t < t_best) t_best = t, wall = 2 * axis + (dir[axis] > 0);
    }
    const Vec3 hit = center + t_best * dir;
    // Skip hits near the room's edges, where a texel may mix two walls.
    int near_edge = 0;
    for (int axis = 0; axis < 3; ++axis) near_edge += std::abs(std::abs(hit[axis]) - 2) < 0.15;
    if (near_edge > 1) continue;
    const Vec3f got(cube.lookup(Vec3f(dir)));
    EXPECT_NEAR(glm::length(got - colors[wall]), 0, 0.02f) << dir.x << " " << dir.y << " " << dir.z;
    ++checked;
  }
  EXPECT_GT(checked, 1500);
  EXPECT_THROW(render_cube_map(center, 0, [](Framebuffer&, const Mat4&, const Mat4&) {}), InvalidInput);
  EXPECT_THROW(render_cube_map(
                   center, 8, [](Framebuffer&, const Mat4&, const Mat4&) {}, 1, 1),
               InvalidInput);
}

/// The analytic shadow of the square |x|, |z| <= 0.5 at height 1 on the floor, for light toward `to_light`.
bool in_square_shadow(const Vec3& to_light, double x, double z) {
  const double t = 1 / to_light.y;
  return std::abs(x + t * to_light.x) <= 0.5 && std::abs(z + t * to_light.z) <= 0.5;
}

TEST(ShadowMap, ASquaresShadowIsItsProjectionAlongTheLight) {
  const Vec3 to_light = glm::normalize(Vec3(0.6, 1, 0.3));
  VertexArrays occluder = floor_quad(0.5f);
  for (Vec3f& p : occluder.positions) p.y = 1;
  const VertexArrays ground = floor_quad(2);
  ShadowMap map(1024, ShadowMap::directional(to_light, {-2, 0, -2}, {2, 1, 2}));
  map.draw(ground);
  map.draw(occluder);
  // Top view of the floor alone, lit by the light; the occluder casts its shadow only.
  const int w = 256;
  const Mat4 view = look_at({0, 5, 0}, {0, 0, 0}, {0, 0, -1});
  Lighting l;
  l.color_material = true;
  l.model_ambient = Vec3f(0.2f);
  l.lights[0].position = Vec4f(Vec3f(Mat3(view) * to_light), 0);
  SurfaceUniforms u = unlit_uniforms(ortho(-2, 2, -2, 2, 1, 10), view);
  u.lighting = PreparedLighting(l);
  u.maps.shadows[0] = &map;
  u.maps.shadow_pcf = 0;
  Framebuffer fb(w, w);
  draw_surface(fb, RasterState{}, ground, u);
  const double texel = 2 * 1.01 * glm::length(Vec3(4, 1, 4)) / 2 / 1024;  // the map's texel in world units
  int shadowed = 0, wrong = 0;
  for (int j = 0; j < w; ++j)
    for (int i = 0; i < w; ++i) {
      // Pixel (i, j) (j from the bottom) looks at x = -2 + 4 (i + 0.5) / w, z = 2 - 4 (j + 0.5) / w... from above
      // with up = -z: window y grows toward -z.
      const double x = -2 + 4 * (i + 0.5) / w, z = 2 - 4 * (j + 0.5) / w;
      const bool expected = in_square_shadow(to_light, x, z);
      const bool got = fb.color()(i, w - 1 - j).x < 100;
      shadowed += got;
      if (got != expected) {
        // Only within two map texels of the shadow's edge (the map's resolution).
        bool near_edge = false;
        for (const double dx : {-2 * texel, 2 * texel})
          for (const double dz : {-2 * texel, 2 * texel})
            near_edge |= in_square_shadow(to_light, x + dx, z + dz) != expected;
        EXPECT_TRUE(near_edge) << i << " " << j;
        ++wrong;
      }
    }
  EXPECT_NEAR(shadowed, w * w / 16, w * w / 100);  // a 1 x 1 square on a 4 x 4 floor
  EXPECT_LT(wrong, 4 * w);
}

TEST(ShadowMap, LitSurfacesDoNotShadowThemselves) {
  // A sphere over a floor under an oblique light: points facing the light and floor points outside the sphere's
  // shadow cylinder are fully lit (no acne), points inside it fully shadowed, at every filter radius.
  const Vec3 to_light = glm::normalize(Vec3(-0.5, 1, 0.7));
  const VertexArrays ground = floor_quad(3);
  const VertexArrays sphere = VertexArrays::from_mesh(to_tri_mesh(make_uv_sphere(96, 48)));
  const Mat4 lift = translate(0, 1.2, 0);
  for (const int size : {256, 2048}) {
    ShadowMap map(size, ShadowMap::directional(to_light, {-3, 0, -3}, {3, 2.2, 3}));
    map.draw(ground);
    map.draw(sphere, lift);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> d(-1, 1);
    for (const int pcf : {0, 1, 2}) {
      int checked = 0;
      for (int k = 0; k < 4000; ++k) {
        // Floor points: distance of the point's ray toward the light from the sphere's center.
        const Vec3 p(2.5 * d(rng), 0, 2.5 * d(rng));
        const Vec3 center(0, 1.2, 0);
        const double along = std::max(glm::dot(center - p, to_light), 0.0);  // the ray's point nearest the center
        const double miss = glm::length(center - (p + along * to_light));
        const double margin = 8.0 * 6 / size;  // filter taps and texel size
        if (std::abs(miss - 1) < margin) continue;
        EXPECT_EQ(map.visibility(Vec3f(p), {0, 1, 0}, pcf), miss > 1 ? 1.0f : 0.0f) << size << " " << pcf;
        ++checked;
        // Sphere points facing the light.
        const Vec3 n = glm::normalize(Vec3(d(rng), d(rng), d(rng)));
        if (glm::dot(n, to_light) < 0.2) continue;
        EXPECT_EQ(map.visibility(Vec3f(center + n), Vec3f(n), pcf), 1.0f) << size << " " << pcf;
      }
      EXPECT_GT(checked, 3000);
    }
  }
}

TEST(ShadowMap, AMapFittedToTheCastersShadowsReceiversBeyondIt) {
  // The map holds only the occluder square (at height 1); the floor lies beyond its far plane, yet is shadowed
  // exactly where the square's projection falls, and lit elsewhere (also outside the map).
  const Vec3 to_light = glm::normalize(Vec3(0.4, 1, -0.3));
  VertexArrays occluder = floor_quad(0.5f);
  for (Vec3f& p : occluder.positions) p.y = 1;
  ShadowMap map(512, ShadowMap::directional(to_light, {-0.5, 1, -0.5}, {0.5, 1, 0.5}));
  map.draw(occluder);
  map.draw(floor_quad(2));  // mostly clipped away: beyond the far plane
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> d(-2, 2);
  int shadowed = 0;
  for (int k = 0; k < 4000; ++k) {
    const double x = d(rng), z = d(rng);
    const bool expected = in_square_shadow(to_light, x, z);
    bool near_edge = false;
    for (const double e : {-0.02, 0.02})
      near_edge |= in_square_shadow(to_light, x + e, z) != expected || in_square_shadow(to_light, x, z + e) != expected;
    if (near_edge) continue;
    shadowed += expected;
    EXPECT_EQ(map.visibility(Vec3f(float(x), 0, float(z)), {0, 1, 0}, 1), expected ? 0.0f : 1.0f) << x << " " << z;
  }
  EXPECT_GT(shadowed, 100);
  // The occluder itself, lit from above, is not shadowed by its own depth.
  EXPECT_EQ(map.visibility({0.1f, 1, 0.2f}, {0, 1, 0}, 1), 1.0f);
}

/// A square tile of half-size `half` at unit distance from `light` in direction `dir`, facing the light.
struct Tile {
  Vec3 center, u, v;
  double half;
  /// Where the ray from the light along unit w crosses the tile's plane, in the tile's coordinates (|x|, |y| <= half
  /// inside); nothing when it points away.
  std::optional<glm::dvec2> crossing(const Vec3& light, const Vec3& w) const {
    const Vec3 n = center - light;
    if (glm::dot(w, n) <= 0) return std::nullopt;
    const Vec3 h = light + w * (glm::dot(n, n) / glm::dot(w, n)) - center;
    return glm::dvec2(glm::dot(h, u), glm::dot(h, v));
  }
  VertexArrays arrays() const {
    VertexArrays a;
    for (const auto& [s, t] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}})
      a.positions.push_back(Vec3f(center + half * (s * u + t * v)));
    a.normals.assign(4, Vec3f(glm::cross(u, v)));
    a.indices = {0, 1, 2, 0, 2, 3};
    return a;
  }
};

TEST(ShadowMap, APointLightAmongTheCastersShadowsAllAround) {
  // Tiles around a point light in the 26 directions of a 3 x 3 x 3 grid: toward the middles of the faces of the cube
  // around the light, of its edges and of its corners, where two and three of the omnidirectional map's faces meet.
  // A point on a sphere around them is in shadow exactly when the segment to the light crosses a tile.
  const Vec3 light(0.2, 0.1, -0.15);
  std::vector<Tile> tiles;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z) {
        if (x == 0 && y == 0 && z == 0) continue;
        const Vec3 d = glm::normalize(Vec3(x, y, z));
        const Vec3 u = glm::normalize(glm::cross(d, std::abs(d.y) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0)));
        tiles.push_back({light + d, u, glm::cross(d, u), 0.2});
      }
  ShadowMap map = ShadowMap::point(1024, light, light - Vec3(1.2), light + Vec3(1.2));
  ASSERT_EQ(map.face_count(), 6);
  EXPECT_EQ(map.size(), 512);
  for (const Tile& t : tiles) map.draw(t.arrays());
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss;
  for (const int pcf : {0, 1, 3}) {
    int shadowed = 0, checked = 0;
    for (int k = 0; k < 6000; ++k) {
      // Half the points uniform on the sphere, half near the directions where faces meet.
      Vec3 w = glm::normalize(Vec3(gauss(rng), gauss(rng), gauss(rng)));
      if (k % 2) {
        const Tile& t = tiles[size_t(k / 2) % tiles.size()];
        w = glm::normalize(t.center - light + 0.25 * w);
      }
      bool inside = false, near_edge = false;
      for (const Tile& t : tiles)
        if (const auto c = t.crossing(light, w)) {
          const double edge = std::max(std::abs(c->x), std::abs(c->y));
          inside |= edge < t.half;
          near_edge |= std::abs(edge - t.half) < 0.02;
        }
      if (near_edge) continue;
      ++checked;
      shadowed += inside;
      const Vec3 p = light + 3.0 * w;
      EXPECT_EQ(map.visibility(Vec3f(p), Vec3f(-w), pcf), inside ? 0.0f : 1.0f)
          << pcf << " " << w.x << " " << w.y << " " << w.z;
    }
    EXPECT_GT(shadowed, checked / 5) << pcf;
    EXPECT_LT(shadowed, checked * 4 / 5) << pcf;
  }
  // The tiles themselves, facing the light, are lit.
  for (const Tile& t : tiles)
    EXPECT_EQ(map.visibility(Vec3f(t.center + 0.1 * t.u), Vec3f(glm::normalize(light - t.center)), 1), 1.0f);
}

TEST(ShadowMap, APointLightOutsideTheCastersGetsOneView) {
  const ShadowMap outside = ShadowMap::point(64, {0, 5, 0}, {-1, 0, -1}, {1, 1, 1});
  EXPECT_EQ(outside.face_count(), 1);
  EXPECT_EQ(outside.size(), 64);
  EXPECT_EQ(ShadowMap::point(64, {0, 0.5, 0}, {-1, 0, -1}, {1, 1, 1}).face_count(), 6);
  EXPECT_THROW(ShadowMap::point(0, {0, 0.5, 0}, {-1, 0, -1}, {1, 1, 1}), InvalidInput);
  EXPECT_THROW(ShadowMap::point(64, {0, 0.5, 0}, {1, 1, 1}, {-1, 0, -1}), InvalidInput);
}

TEST(ShadowMap, RejectsBadInput) {
  EXPECT_THROW(ShadowMap(0, Mat4(1.0)), InvalidInput);
  EXPECT_THROW(ShadowMap(20000, Mat4(1.0)), InvalidInput);
  EXPECT_THROW(ShadowMap::directional({0, 0, 0}, {0, 0, 0}, {1, 1, 1}), InvalidInput);
  EXPECT_THROW(ShadowMap::directional({0, 1, 0}, {1, 1, 1}, {0, 0, 0}), InvalidInput);
  EXPECT_THROW(ShadowMap::spot({0.5, 0.5, 0.5}, {0, 0, 0}, {1, 1, 1}), InvalidInput);
  const ShadowMap map(8, ShadowMap::spot({0, 5, 0}, {-1, 0, -1}, {1, 0, 1}));
  EXPECT_THROW((void)map.visibility({0, 0, 0}, {0, 1, 0}, -1), InvalidInput);
  EXPECT_EQ(map.visibility({0, 0, 0}, {0, 1, 0}), 1.0f);   // nothing drawn: lit
  EXPECT_EQ(map.visibility({50, 0, 0}, {0, 1, 0}), 1.0f);  // outside the light's view: lit
}

TEST(ShadowMap, ASpotLightsShadowFollowsItsRays) {
  // A point light above a small square: the shadow on the floor is the square scaled from the light.
  const Vec3 light(0.3, 4, -0.2);
  VertexArrays occluder = floor_quad(0.5f);
  for (Vec3f& p : occluder.positions) p.y = 1;
  ShadowMap map(1024, ShadowMap::spot(light, {-2, 0, -2}, {2, 1, 2}));
  map.draw(floor_quad(2));
  map.draw(occluder);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.9, 1.9);
  int inside = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 p(d(rng), 0, d(rng));
    // Where the segment to the light crosses y = 1.
    const Vec3 q = p + (light - p) * (1 / light.y);
    const double edge = std::max(std::abs(q.x), std::abs(q.z));
    if (std::abs(edge - 0.5) < 0.02) continue;
    const bool shadowed = edge < 0.5;
    inside += shadowed;
    EXPECT_EQ(map.visibility(Vec3f(p), {0, 1, 0}, 1), shadowed ? 0.0f : 1.0f) << p.x << " " << p.z;
  }
  EXPECT_GT(inside, 50);
}

TEST(Lighting, VisibilityScalesEachLightsDirectTerms) {
  Lighting l;
  l.material = Material::plastic({0.2f, 0.2f, 0.2f}, 8, 0.2f);  // sums below 1: nothing clamped
  l.light_count = 2;
  l.lights[0].position = Vec4f(0, 0, 1, 0);
  l.lights[1].position = Vec4f(0, 1, 1, 0);
  l.model_ambient = Vec3f(0.1f);
  const PreparedLighting prepared(l);
  const Vec3f n(0, 0, 1), p(0, 0, -2), c(1);
  const auto shade = [&](std::initializer_list<float> visibility) {
    return prepared.shade(n, p, c, std::span<const float>(visibility.begin(), visibility.size()));
  };
  const Vec3f both = prepared.shade(n, p, c), half = shade({0.5f}), none = shade({0});
  // Without light 0, or without light 1: the other light and the ambient stay.
  for (int off = 0; off < 2; ++off) {
    Lighting other = l;
    other.lights[0] = other.lights[size_t(1 - off)];
    other.light_count = 1;
    EXPECT_EQ(off == 0 ? none : shade({1, 0}), PreparedLighting(other).shade(n, p, c)) << off;
  }
  EXPECT_NEAR(glm::length(half - 0.5f * (both + none)), 0, 1e-6f);
  EXPECT_EQ(shade({1}), both);
  EXPECT_EQ(shade({1, 1, 0}), both);  // entries past the lights are not read
  Lighting dark = l;
  dark.light_count = 0;
  EXPECT_EQ(shade({0, 0}), PreparedLighting(dark).shade(n, p, c));
}

}  // namespace
}  // namespace tessera::raster3d
