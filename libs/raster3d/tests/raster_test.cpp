// Coverage rules of the triangle rasterizer: tie rule, abutting triangles, clipping, depth, varyings, parallelism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster3d/pipeline.hpp"
#include "test_util.hpp"

namespace tessera::raster3d {
namespace {

using testing::covered;
using testing::covered_gl;
using testing::draw_window_triangles;
using testing::WindowVertexIn;

// Per-pixel coverage counts of triangles drawn one at a time: a tiling must give exactly 1 inside its region.
std::vector<int> coverage_counts(int size, const std::vector<WindowVertexIn>& vertices,
                                 const std::vector<uint32_t>& indices) {
  std::vector<int> counts(size_t(size) * size, 0);
  Framebuffer fb(size, size);
  for (size_t t = 0; t < indices.size(); t += 3) {
    fb.clear_color(Vec3f(0));
    draw_window_triangles(fb, vertices, {indices[t], indices[t + 1], indices[t + 2]});
    const auto c = covered(fb);
    for (size_t p = 0; p < c.size(); ++p) counts[p] += c[p];
  }
  return counts;
}

TEST(Raster, TieRuleOwnsLeftAndBottomEdges) {
  // A square whose edges run exactly through pixel centers, split along either diagonal (which also runs through
  // centers): GL owns the left (interior on +x) and bottom (interior above) edges, so pixels 1..3 in x and y.
  for (int diagonal = 0; diagonal < 2; ++diagonal) {
    std::vector<WindowVertexIn> v = {
        {{1.5f, 1.5f, 0.5f}}, {{4.5f, 1.5f, 0.5f}}, {{4.5f, 4.5f, 0.5f}}, {{1.5f, 4.5f, 0.5f}}};
    const std::vector<uint32_t> idx =
        diagonal ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 1, 3, 1, 2, 3};
    const auto counts = coverage_counts(8, v, idx);
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const int expected = (i >= 1 && i <= 3 && j >= 1 && j <= 3) ? 1 : 0;
        EXPECT_EQ(counts[size_t(7 - j) * 8 + i], expected) << "GL pixel " << i << "," << j << " diagonal " << diagonal;
      }
  }
}

TEST(Raster, TieRuleDoesNotDependOnWinding) {
  Framebuffer a(8, 8), b(8, 8);
  const std::vector<WindowVertexIn> v = {{{0.5f, 0.5f, 0.5f}}, {{6.5f, 0.5f, 0.5f}}, {{0.5f, 6.5f, 0.5f}}};
  draw_window_triangles(a, v, {0, 1, 2});
  draw_window_triangles(b, v, {0, 2, 1});
  EXPECT_EQ(covered(a), covered(b));
  // The hypotenuse x + y = 7 passes through centers; its interior is on the -x side, so those centers are out.
  EXPECT_TRUE(covered_gl(a, 0, 0));
  EXPECT_TRUE(covered_gl(a, 5, 0));
  EXPECT_FALSE(covered_gl(a, 6, 0));
  EXPECT_TRUE(covered_gl(a, 0, 5));
  EXPECT_FALSE(covered_gl(a, 0, 6));
  EXPECT_TRUE(covered_gl(a, 2, 3));   // 2.5 + 3.5 < 7: inside
  EXPECT_FALSE(covered_gl(a, 3, 3));  // 3.5 + 3.5 = 7: on the hypotenuse
}

TEST(Raster, FanAroundAVertexCoversEveryPixelOnce) {
  // 12 triangles around a center that sits on a pixel center, spokes through pixel centers and in between.
  const int size = 32;
  std::vector<WindowVertexIn> v = {{{16.5f, 16.5f, 0.5f}}};
  const int spokes = 12;
  for (int k = 0; k < spokes; ++k) {
    const double a = 2 * kPi * k / spokes;
    v.push_back({{float(16.5 + 12 * std::cos(a)), float(16.5 + 12 * std::sin(a)), 0.5f}});
  }
  std::vector<uint32_t> idx;
  for (int k = 0; k < spokes; ++k) idx.insert(idx.end(), {0u, uint32_t(1 + k), uint32_t(1 + (k + 1) % spokes)});
  const auto counts = coverage_counts(size, v, idx);
  int inside = 0;
  for (int c : counts) {
    EXPECT_LE(c, 1);
    inside += c;
  }
  EXPECT_TRUE(counts[size_t(size - 1 - 16) * size + 16] == 1) << "the center pixel is covered once";
  EXPECT_GT(inside, 300);  // the 12-gon of radius 12 has area about 432
}

TEST(Raster, RandomTrianglesTilingASquareCoverEachPixelOnce) {
  // A grid of jittered points (on the 1/256 grid) triangulated: the triangles tile the square [4, 60]^2 exactly.
  const int size = 64, n = 8;
  Rng rng(7);
  std::vector<WindowVertexIn> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float x = 4 + 7.0f * i, y = 4 + 7.0f * j;
      if (i > 0 && i < n) x += std::round(float(rng.uniform() - 0.5) * 4 * 256) / 256;
      if (j > 0 && j < n) y += std::round(float(rng.uniform() - 0.5) * 4 * 256) / 256;
      v.push_back({{x, y, 0.5f}});
    }
  std::vector<uint32_t> idx;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      if ((i + j) % 2)
        idx.insert(idx.end(), {a, b, d, a, d, c});
      else
        idx.insert(idx.end(), {a, b, c, b, d, c});
    }
  const auto counts = coverage_counts(size, v, idx);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const int j = size - 1 - y;                                           // GL row
      const int expected = (x >= 4 && x < 60 && j >= 4 && j < 60) ? 1 : 0;  // centers in [4, 60): left/bottom in
      EXPECT_EQ(counts[size_t(y) * size + x], expected) << "pixel " << x << "," << y;
    }
}

TEST(Raster, DepthFollowsTheWindowPlane) {
  const int size = 64;
  Framebuffer fb(size, size);
  const std::vector<WindowVertexIn> v = {{{3.0f, 2.0f, 0.1f}}, {{61.0f, 9.0f, 0.7f}}, {{20.0f, 60.0f, 0.95f}}};
  RasterState state;
  draw_triangles(fb, state, 3, std::vector<uint32_t>{0, 1, 2}, testing::WindowShader{&v, 64, 64},
                 ColorFragmentShader{});
  // The analytic plane z = a x + b y + c through the three points.
  const glm::dmat3 m(3, 61, 20, 2, 9, 60, 1, 1, 1);  // columns: x, y, 1
  const glm::dvec3 abc = glm::inverse(m) * glm::dvec3(0.1, 0.7, 0.95);
  int checked = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      if (!covered_gl(fb, i, j)) continue;
      const double z = abc.x * (i + 0.5) + abc.y * (j + 0.5) + abc.z;
      const double expected = std::round(z * double(kDepthMax));
      // The plane is evaluated in float32 as llvmpipe does (pipeline_impl.hpp, fragment_depth): a few roundings of
      // values up to 1 move the result by up to 2 units of 2^-24 from the exact plane.
      EXPECT_NEAR(double(fb.depth()(i, size - 1 - j)), expected, 2.0) << i << "," << j;
      ++checked;
    }
  EXPECT_GT(checked, 1000);
}

TEST(Raster, ZBufferKeepsTheNearerSurfaceAndLessRejectsEqual) {
  Framebuffer fb(16, 16);
  const std::vector<WindowVertexIn> v = {
      {{0, 0, 0.6f}, {1, 0, 0}}, {{16, 0, 0.6f}, {1, 0, 0}}, {{0, 16, 0.6f}, {1, 0, 0}},   // red, far
      {{0, 0, 0.3f}, {0, 1, 0}}, {{16, 0, 0.3f}, {0, 1, 0}}, {{0, 16, 0.3f}, {0, 1, 0}},   // green, near
      {{0, 0, 0.3f}, {0, 0, 1}}, {{16, 0, 0.3f}, {0, 0, 1}}, {{0, 16, 0.3f}, {0, 0, 1}}};  // blue, equal depth
  RasterState state;
  draw_triangles(fb, state, 9, std::vector<uint32_t>{3, 4, 5, 0, 1, 2, 6, 7, 8}, testing::WindowShader{&v, 16, 16},
                 ColorFragmentShader{});
  EXPECT_EQ(fb.color()(2, 13), glm::u8vec4(0, 255, 0, 255));
  // Window z of the float vertex 0.3f after the shader's clip z 2 z - 1 and the viewport's 0.5 z + 0.5, times
  // 2^24 - 1 in float and rounded to nearest (OpenGL on llvmpipe, gl-raster-conventions.md item 7).
  const float window_z = (2 * 0.3f - 1) * 0.5f + 0.5f;
  EXPECT_EQ(fb.depth()(2, 13), uint32_t(std::nearbyint(window_z * 16777215.0f)));
  EXPECT_EQ(fb.depth()(15, 0), kDepthMax);  // uncovered: cleared depth
}

// An analytic perspective scene: a triangle in eye space, the camera at the origin looking down -z.
struct EyeTriangle {
  glm::dvec3 p[3];
};

// The eye-space point where the ray through GL pixel center (i, j) meets the triangle's plane, and its barycentrics.
bool ray_hit(const EyeTriangle& t, const glm::dmat4& projection, int size, int i, int j, glm::dvec3& bary,
             double& eye_z) {
  const glm::dmat4 inv = glm::inverse(projection);
  const double x = 2 * (i + 0.5) / size - 1, y = 2 * (j + 0.5) / size - 1;
  glm::dvec4 a = inv * glm::dvec4(x, y, -1, 1), b = inv * glm::dvec4(x, y, 1, 1);
  const glm::dvec3 o(0.0), d = glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
  const glm::dvec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0], n = glm::cross(e1, e2);
  const double s = glm::dot(n, t.p[0] - o) / glm::dot(n, d);
  if (s <= 0) return false;
  const glm::dvec3 q = o + s * d;
  const double area = glm::dot(n, n);
  bary.y = glm::dot(n, glm::cross(q - t.p[0], e2)) / area;
  bary.z = glm::dot(n, glm::cross(e1, q - t.p[0])) / area;
  bary.x = 1 - bary.y - bary.z;
  eye_z = q.z;
  return true;
}

struct EyeVertexShader {
  const EyeTriangle* triangle;
  Mat4f projection;
  VertexOut<ColorVaryings> operator()(uint32_t i) const {
    const Vec3f barycentric(i == 0, i == 1, i == 2);
    return {projection * Vec4f(Vec3f(triangle->p[i]), 1.0f), {barycentric}};
  }
};

TEST(Raster, NearPlaneClippingMatchesRayCasting) {
  // A floor triangle running from behind the camera to far in front: the near plane cuts it.
  const int size = 64;
  const EyeTriangle tri{{{-3, -1, 2}, {3, -1, 2}, {0, -1, -30}}};
  const double near = 0.5, far = 100;
  const glm::dmat4 projection = perspective(radians(60), 1, near, far);
  Framebuffer fb(size, size);
  RasterState state;
  draw_triangles(fb, state, 3, std::vector<uint32_t>{0, 1, 2}, EyeVertexShader{&tri, Mat4f(projection)},
                 ColorFragmentShader{});
  int mismatches = 0, inside = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      glm::dvec3 b;
      double z;
      const bool hit =
          ray_hit(tri, projection, size, i, j, b, z) && b.x >= 0 && b.y >= 0 && b.z >= 0 && -z >= near && -z <= far;
      // Skip centers within a hair of an edge, where the fixed-point snapping legitimately decides.
      const double margin = std::min({b.x, b.y, b.z});
      if (std::abs(margin) < 1e-3) continue;
      inside += hit;
      mismatches += hit != covered_gl(fb, i, j);
    }
  EXPECT_GT(inside, 200);
  EXPECT_EQ(mismatches, 0);
}

TEST(Raster, PerspectiveCorrectVaryingsMatchRayCasting) {
  // The interpolated barycentrics, written as a color, equal the ray-cast ones; affine interpolation would not.
  const int size = 64;
  const EyeTriangle tri{{{-2, -1, -1.5}, {2, -1, -1.5}, {0, -1, -40}}};
  const glm::dmat4 projection = perspective(radians(90), 1, 0.1, 100);
  Framebuffer fb(size, size);
  RasterState state;
  draw_triangles(fb, state, 3, std::vector<uint32_t>{0, 1, 2}, EyeVertexShader{&tri, Mat4f(projection)},
                 ColorFragmentShader{});
  int checked = 0;
  double worst = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      glm::dvec3 b;
      double z;
      if (!covered_gl(fb, i, j) || !ray_hit(tri, projection, size, i, j, b, z)) continue;
      const auto c = fb.color()(i, size - 1 - j);
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(c[k] - std::round(255 * b[k])));
      ++checked;
    }
  EXPECT_GT(checked, 100);
  EXPECT_LE(worst, 1.0);
}

TEST(Raster, PartlyOffScreenTrianglesMatchTheUnclippedReference) {
  // The same triangles on a 64^2 screen (clipped at x, y = +-w) and on a 256^2 screen with clip x, y divided by 4,
  // where nothing is clipped: the 64^2 image is the middle of the big one (window offset 96, a whole pixel count).
  Rng rng(3);
  std::vector<Vec4f> clip;
  for (int k = 0; k < 3 * 40; ++k)
    clip.push_back(Vec4f(std::round(float(rng.uniform() * 5 - 2.5) * 1024) / 1024,
                         std::round(float(rng.uniform() * 5 - 2.5) * 1024) / 1024, float(rng.uniform() * 1.8 - 0.9),
                         1.0f));
  struct ClipShader {
    const std::vector<Vec4f>* clip;
    float xy_scale;
    VertexOut<ColorVaryings> operator()(uint32_t i) const {
      const Vec4f p = (*clip)[i];
      return {Vec4f(p.x * xy_scale, p.y * xy_scale, p.z, p.w), {Vec3f(float(i / 3 % 7 + 1) / 8, 0.5f, 1.0f)}};
    }
  };
  std::vector<uint32_t> idx(clip.size());
  for (size_t k = 0; k < idx.size(); ++k) idx[k] = uint32_t(k);
  Framebuffer small(64, 64), big(256, 256);
  RasterState state;
  draw_triangles(small, state, uint32_t(clip.size()), idx, ClipShader{&clip, 1.0f}, ColorFragmentShader{});
  draw_triangles(big, state, uint32_t(clip.size()), idx, ClipShader{&clip, 0.25f}, ColorFragmentShader{});
  int differ = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) differ += small.color()(x, y) != big.color()(x + 96, y + 96);
  // New vertices on the clip planes are rounded to float, which can move a clipped edge by a hair.
  EXPECT_LE(differ, 4);
}

TEST(Raster, BackFaceCulling) {
  Framebuffer fb(8, 8);
  const std::vector<WindowVertexIn> v = {{{0, 0, 0.5f}}, {{8, 0, 0.5f}}, {{0, 8, 0.5f}}};
  RasterState state;
  state.cull = CullMode::back;
  draw_window_triangles(fb, v, {0, 2, 1}, state);  // clockwise on screen: a back face
  EXPECT_FALSE(covered_gl(fb, 1, 1));
  draw_window_triangles(fb, v, {0, 1, 2}, state);
  EXPECT_TRUE(covered_gl(fb, 1, 1));
}

TEST(Raster, FlatTakesTheLastVertex) {
  Framebuffer fb(8, 8);
  const std::vector<WindowVertexIn> v = {
      {{0, 0, 0.5f}, {1, 0, 0}}, {{8, 0, 0.5f}, {0, 1, 0}}, {{0, 8, 0.5f}, {0, 0, 1}}};
  RasterState state;
  state.flat = true;
  draw_window_triangles(fb, v, {0, 1, 2}, state);
  EXPECT_EQ(fb.color()(1, 6), glm::u8vec4(0, 0, 255, 255));
  EXPECT_EQ(fb.color()(5, 6), glm::u8vec4(0, 0, 255, 255));
}

TEST(Raster, SameImageForOneAndAllThreads) {
  Rng rng(11);
  std::vector<WindowVertexIn> v;
  for (int k = 0; k < 3 * 3000; ++k)
    v.push_back({{float(rng.uniform() * 300 - 22), float(rng.uniform() * 220 - 10), float(rng.uniform())},
                 {float(rng.uniform()), float(rng.uniform()), float(rng.uniform())}});
  std::vector<uint32_t> idx(v.size());
  for (size_t k = 0; k < idx.size(); ++k) idx[k] = uint32_t(k);
  auto render = [&](int threads) {
    ThreadLimit limit(threads);
    Framebuffer fb(256, 200);
    RasterState state;
    draw_triangles(fb, state, uint32_t(v.size()), idx, testing::WindowShader{&v, 256, 200, 2.0f},
                   ColorFragmentShader{});
    return fb;
  };
  // 0: all cores; 4: the raster job's loop in an arena of 3 slots (pipeline_for), whatever the core count.
  const Framebuffer one = render(1);
  for (const int threads : {0, 4}) {
    const Framebuffer other = render(threads);
    EXPECT_TRUE(std::equal(one.color().pixels().begin(), one.color().pixels().end(), other.color().pixels().begin()))
        << threads;
    EXPECT_TRUE(std::equal(one.depth().pixels().begin(), one.depth().pixels().end(), other.depth().pixels().begin()))
        << threads;
  }
}

TEST(Raster, PainterMatchesZBufferWithoutOverlapCycles) {
  // Three layers at different depths, submitted near first: the painter sorts them, the z-buffer tests them.
  const std::vector<WindowVertexIn> v = {
      {{4, 4, 0.2f}, {1, 0, 0}}, {{40, 8, 0.2f}, {1, 0, 0}},  {{10, 40, 0.2f}, {1, 0, 0}},
      {{0, 0, 0.5f}, {0, 1, 0}}, {{48, 0, 0.5f}, {0, 1, 0}},  {{0, 48, 0.5f}, {0, 1, 0}},
      {{8, 2, 0.8f}, {0, 0, 1}}, {{48, 30, 0.8f}, {0, 0, 1}}, {{20, 48, 0.8f}, {0, 0, 1}}};
  const std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  Framebuffer z(48, 48), p(48, 48);
  RasterState zs, ps;
  ps.painter = true;
  const testing::WindowShader shader{&v, 48, 48};
  draw_triangles(z, zs, 9, idx, shader, ColorFragmentShader{});
  draw_triangles(p, ps, 9, idx, shader, ColorFragmentShader{});
  EXPECT_TRUE(std::equal(z.color().pixels().begin(), z.color().pixels().end(), p.color().pixels().begin()));
}

TEST(Raster, PainterFailsOnCyclicOverlap) {
  // Three long strips, each above the next at one end and below it at the other (the classic cycle): no order of
  // whole triangles is right, the z-buffer is.
  const int s = 96;
  std::vector<WindowVertexIn> v;
  const Vec3f colors[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * kPi * k / 3;
    const glm::dvec2 c(48, 48), dir(std::cos(a), std::sin(a)), perp(-dir.y, dir.x);
    const glm::dvec2 p0 = c - 40.0 * dir + 10.0 * perp, p1 = c + 40.0 * dir + 10.0 * perp,
                     p2 = c - 40.0 * dir - 6.0 * perp;
    // Depth rises along the strip: near at its start, far at its end.
    v.push_back({{float(p0.x), float(p0.y), 0.2f}, colors[k]});
    v.push_back({{float(p1.x), float(p1.y), 0.8f}, colors[k]});
    v.push_back({{float(p2.x), float(p2.y), 0.2f}, colors[k]});
  }
  const std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  Framebuffer z(s, s), p(s, s);
  RasterState zs, ps;
  ps.painter = true;
  const testing::WindowShader shader{&v, float(s), float(s)};
  draw_triangles(z, zs, 9, idx, shader, ColorFragmentShader{});
  draw_triangles(p, ps, 9, idx, shader, ColorFragmentShader{});
  int differ = 0;
  for (size_t k = 0; k < z.color().pixels().size(); ++k) differ += z.color().pixels()[k] != p.color().pixels()[k];
  EXPECT_GT(differ, 20);
}

struct WindowPointShader {
  const std::vector<WindowVertexIn>* vertices;
  float size;
  VertexOut<NoVaryings> operator()(uint32_t i) const {
    const Vec3f w = (*vertices)[i].window;
    return {Vec4f(2 * w.x / size - 1, 2 * w.y / size - 1, 2 * w.z - 1, 1), {}};
  }
};

TEST(Raster, LinesCoverOnePixelPerColumnHalfOpen) {
  Framebuffer fb(16, 16);
  const std::vector<WindowVertexIn> v = {{{1.5f, 3.2f, 0.5f}}, {{9.5f, 7.2f, 0.5f}}};
  RasterState state;
  draw_lines(fb, state, 2, std::vector<uint32_t>{0, 1}, WindowPointShader{&v, 16}, testing::FlatFragmentShader{});
  int count = 0;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) count += covered_gl(fb, i, j);
  EXPECT_EQ(count, 8);  // columns 1..8: centers 1.5 <= c < 9.5
  for (int i = 1; i <= 8; ++i) {
    const int j = int(std::floor(3.2 + (i + 0.5 - 1.5) * 0.5));
    EXPECT_TRUE(covered_gl(fb, i, j)) << i;
  }
}

TEST(Raster, PointsCoverTheirPixel) {
  Framebuffer fb(8, 8);
  const std::vector<WindowVertexIn> v = {{{2.7f, 5.1f, 0.5f}}, {{9.0f, 1.0f, 0.5f}}};
  RasterState state;
  draw_points(fb, state, 2, std::vector<uint32_t>{0, 1}, WindowPointShader{&v, 8}, testing::FlatFragmentShader{});
  EXPECT_TRUE(covered_gl(fb, 2, 5));
  int count = 0;
  for (int p : covered(fb)) count += p;
  EXPECT_EQ(count, 1);
}

TEST(Raster, NonFiniteVerticesAreDropped) {
  // A NaN or infinite coordinate (from a bad mesh or a degenerate matrix) drops the primitive; the others draw.
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<WindowVertexIn> v = {{{1, 1, 0.5f}},   {{7, 1, 0.5f}},   {{1, 7, 0.5f}},
                                         {{nan, 1, 0.5f}}, {{inf, 2, 0.5f}}, {{3, -inf, 0.5f}}};
  Framebuffer fb(8, 8);
  RasterState state;
  const testing::WindowShader shader{&v, 8, 8};
  draw_triangles(fb, state, 6, std::vector<uint32_t>{3, 4, 5, 0, 1, 2, 0, 3, 1}, shader, ColorFragmentShader{});
  draw_lines(fb, state, 6, std::vector<uint32_t>{3, 4, 0, 5}, shader, ColorFragmentShader{});
  draw_points(fb, state, 6, std::vector<uint32_t>{3, 4, 5}, shader, ColorFragmentShader{});
  int count = 0;
  for (int p : covered(fb)) count += p;
  EXPECT_EQ(count, 15);  // the finite triangle: centers (i + 0.5, j + 0.5) with i, j >= 1 and i + j <= 6
}

TEST(Raster, BadIndicesThrow) {
  Framebuffer fb(8, 8);
  const std::vector<WindowVertexIn> v = {{{0, 0, 0.5f}}, {{8, 0, 0.5f}}, {{0, 8, 0.5f}}};
  RasterState state;
  const testing::WindowShader shader{&v, 8, 8};
  EXPECT_THROW(draw_triangles(fb, state, 3, std::vector<uint32_t>{0, 1}, shader, ColorFragmentShader{}), InvalidInput);
  EXPECT_THROW(draw_triangles(fb, state, 3, std::vector<uint32_t>{0, 1, 3}, shader, ColorFragmentShader{}),
               InvalidInput);
}

TEST(Raster, ADepthOnlyFramebufferStoresTheSameDepth) {
  // Overlapping random triangles, lines and points, drawn into a full framebuffer and into a depth-only one: the
  // depth buffers are identical, the depth-only one has no color or stencil, and a stencil test on it throws.
  const int size = 64;
  Rng rng(11);
  std::vector<WindowVertexIn> v;
  for (int k = 0; k < 90; ++k)
    v.push_back({{float(rng.uniform(-8, 72)), float(rng.uniform(-8, 72)), float(rng.uniform(0.05, 0.95))}});
  std::vector<uint32_t> all(v.size());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  const testing::WindowShader shader{&v, size, size};
  Framebuffer full(size, size), depth = Framebuffer::depth_only(size, size);
  for (Framebuffer* fb : {&full, &depth}) {
    RasterState state;
    draw_triangles(*fb, state, uint32_t(v.size()), all, shader, ColorFragmentShader{});
    state.depth_func = DepthFunc::lequal;
    draw_lines(*fb, state, uint32_t(v.size()), std::span(all).first(40), shader, ColorFragmentShader{});
    draw_points(*fb, state, uint32_t(v.size()), all, shader, ColorFragmentShader{});
  }
  EXPECT_EQ(depth.width(), size);
  EXPECT_EQ(depth.height(), size);
  EXPECT_TRUE(full.has_color());
  EXPECT_FALSE(depth.has_color());
  EXPECT_TRUE(depth.color().empty() && depth.stencil().empty() && depth.color_rgb().empty());
  EXPECT_TRUE(std::ranges::equal(depth.depth().pixels(), full.depth().pixels()));
  int drawn = 0;
  for (const uint32_t d : depth.depth().pixels()) drawn += d < kDepthMax;
  EXPECT_GT(drawn, size * size / 2);
  RasterState stencil;
  stencil.stencil_test = true;
  EXPECT_THROW(draw_triangles(depth, stencil, uint32_t(v.size()), all, shader, ColorFragmentShader{}), InvalidInput);
  EXPECT_THROW(draw_points(depth, stencil, uint32_t(v.size()), all, shader, ColorFragmentShader{}), InvalidInput);
  EXPECT_THROW(Framebuffer::depth_only(0, 4), InvalidInput);
}

TEST(Raster, FragmentShaderExceptionReachesTheCaller) {
  // Tiles are rasterized on the framebuffer's raster thread: an exception there is rethrown by the draw, once, and
  // the next draw works.
  Framebuffer fb(8, 8);
  const std::vector<WindowVertexIn> v = {{{0, 0, 0.5f}}, {{8, 0, 0.5f}}, {{0, 8, 0.5f}}};
  const std::vector<uint32_t> indices = {0, 1, 2};
  const testing::WindowShader shader{&v, 8, 8};
  const auto throwing = [](const ColorVaryings&, Vec3f&) -> bool { throw IoError("fragment shader failed"); };
  EXPECT_THROW(draw_triangles(fb, RasterState{}, 3, indices, shader, throwing), IoError);
  EXPECT_EQ(draw_triangles(fb, RasterState{}, 3, indices, shader, ColorFragmentShader{}).rasterized, 1u);
  EXPECT_TRUE(covered_gl(fb, 1, 1));
}

TEST(Raster, FillSpanGivesTheSamePixelsInEveryInstructionSet) {
  // The constant-color span loop runs as AVX-512, AVX2 or SSE2 depending on the CPU: the same depths and colors on
  // random spans, depth planes and stored depths (the loop's clamps included) in each set the CPU has.
  Rng rng(11);
  int changed = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int lo = int(rng.next_u32() % 40), hi = lo + int(rng.next_u32() % 200);
    const float za = float(rng.uniform(-0.1, 1.1)), zdx = float(rng.uniform(-0.01, 0.01)),
                zdy = float(rng.uniform(-0.01, 0.01)), r = float(rng.next_u32() % 64);
    std::vector<uint32_t> depth(size_t(hi) + 1), color(size_t(hi) + 1);
    for (size_t i = 0; i < depth.size(); ++i) depth[i] = rng.next_u32() % (kDepthMax + 1), color[i] = rng.next_u32();
    const auto run = [&](auto fill) {
      std::vector<uint32_t> d = depth, c = color;
      fill(d.data(), c.data(), lo, hi, za, zdx, zdy, r, 0x11223344u);
      return std::pair(d, c);
    };
    // The baseline loop is always_inline: call it directly (a pointer to it cannot be inlined at -O1).
    const auto expected = run([](auto... args) { detail::fill_span_loop<DepthFunc::less, true>(args...); });
    if (detail::span_isa() >= 1) {
      EXPECT_EQ(run(detail::fill_span_avx2<DepthFunc::less, true>), expected);
    }
    if (detail::span_isa() == 2) {
      EXPECT_EQ(run(detail::fill_span_avx512<DepthFunc::less, true>), expected);
    }
    changed += expected.first != depth;
    // The early-z loop of interpolated triangles: the same depths and outcomes.
    const auto run_test = [&](auto test) {
      std::vector<uint32_t> d(size_t(hi - lo) + 1);
      std::vector<char> pass(size_t(hi - lo) + 1);
      test(depth.data(), lo, hi, za, zdx, zdy, r, d.data(), reinterpret_cast<bool*>(pass.data()));
      return std::pair(d, pass);
    };
    const auto expected_test = run_test([](auto... args) { detail::test_span_loop<DepthFunc::less>(args...); });
    if (detail::span_isa() >= 1) {
      EXPECT_EQ(run_test(detail::test_span_avx2<DepthFunc::less>), expected_test);
    }
    if (detail::span_isa() == 2) {
      EXPECT_EQ(run_test(detail::test_span_avx512<DepthFunc::less>), expected_test);
    }
  }
  EXPECT_GT(changed, 100);  // most spans have fragments that pass
}

TEST(Raster, CoversRectangleAgreesWithEveryPixelCenter) {
  // The whole-rectangle shortcut of the span loops against testing each center of random rectangles against
  // random edges (E = 256 (a i + b j) + c >= 0 inside), with both outcomes frequent.
  Rng rng(5);
  int covered = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    detail::TriangleRecord r{};
    for (detail::Edge& e : r.edges) {
      e.a = int32_t(rng.next_u32() % 512) - 256;
      e.b = int32_t(rng.next_u32() % 512) - 256;
      e.c = int64_t(rng.next_u32() % 40000000) - 2000000;
    }
    const int x0 = int(rng.next_u32() % 64), y0 = int(rng.next_u32() % 64);
    const int x1 = x0 + 1 + int(rng.next_u32() % 64), y1 = y0 + 1 + int(rng.next_u32() % 64);
    bool all = true;
    for (int j = y0; j < y1; ++j)
      for (int i = x0; i < x1; ++i)
        for (const detail::Edge& e : r.edges) all = all && 256 * (int64_t(e.a) * i + int64_t(e.b) * j) + e.c >= 0;
    EXPECT_EQ(detail::covers_rectangle(r, x0, x1, y0, y1), all) << trial;
    covered += all;
  }
  EXPECT_GT(covered, 200);
  EXPECT_LT(covered, 1800);
}

// Blending against OpenGL's definition in real numbers (the 4.6 spec, 17.3.6): with S the fragment's color rounded to
// 8 bits and D the stored one, each in [0, 1], add stores S src + D dst (subtract, reverse subtract likewise; min and
// max ignore the factors), clamped and rounded. The 8-bit fixed-point blend may differ from it by 1, no more; the
// common "over" cases with alpha 0 and 1 must be exact.
TEST(Raster, BlendingIsOpenGLsFormulaWithinOneStep) {
  const std::vector<Vec3f> corners{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<uint32_t> quad{0, 1, 2, 0, 2, 3};
  Rng rng(4, 2);
  const auto value = [&] { return float(rng.next_u32() >> 24) / 255.0f; };
  const auto real_factor = [](BlendFactor b, const Vec4& s, const Vec4& d, int c) {
    switch (b) {
      case BlendFactor::zero:
        return 0.0;
      case BlendFactor::one:
        return 1.0;
      case BlendFactor::src_color:
        return s[c];
      case BlendFactor::one_minus_src_color:
        return 1 - s[c];
      case BlendFactor::dst_color:
        return d[c];
      case BlendFactor::one_minus_dst_color:
        return 1 - d[c];
      case BlendFactor::src_alpha:
        return s.w;
      case BlendFactor::one_minus_src_alpha:
        return 1 - s.w;
      case BlendFactor::dst_alpha:
        return d.w;
      case BlendFactor::one_minus_dst_alpha:
        return 1 - d.w;
    }
    return 0.0;
  };
  int evaluations = 0;
  Framebuffer fb(2, 2);
  for (int e = 0; e < 5; ++e)
    for (int src = 0; src < 10; ++src)
      for (int dst = 0; dst < 10; ++dst)
        for (int trial = 0; trial < 8; ++trial) {
          const Vec3f background(value(), value(), value());
          const float background_alpha = value();
          const Vec4f color(value(), value(), value(), value());
          fb.clear_color(background, background_alpha);
          RasterState state;
          state.depth_test = false;
          state.blend = true;
          state.blend_function = {BlendFactor(src), BlendFactor(dst), BlendEquation(e)};
          draw_triangles(fb, state, 4, quad, testing::FlatVertexShader{corners.data()},
                         Translucent<testing::FlatFragmentShader>{{Vec3f(color)}, color.w});
          const glm::u8vec4 got = fb.color()(0, 0);
          const Vec4 s = Vec4(to_color8(color)) / 255.0;
          const Vec4 d = Vec4(to_color8(Vec4f(background, background_alpha))) / 255.0;
          for (int c = 0; c < 4; ++c) {
            const double ws = s[c] * real_factor(BlendFactor(src), s, d, c);
            const double wd = d[c] * real_factor(BlendFactor(dst), s, d, c);
            const double exact = e == 0   ? ws + wd
                                 : e == 1 ? ws - wd
                                 : e == 2 ? wd - ws
                                 : e == 3 ? std::min(s[c], d[c])
                                          : std::max(s[c], d[c]);
            const int expected = int(std::lround(std::clamp(exact, 0.0, 1.0) * 255));
            ++evaluations;
            ASSERT_LE(std::abs(int(got[c]) - expected), 1) << "equation " << e << " src " << src << " dst " << dst;
          }
        }
  EXPECT_EQ(evaluations, 5 * 100 * 8 * 4);
  // "Over" with an opaque and a fully transparent source: the source, and the stored color, exactly.
  for (const float alpha : {0.0f, 1.0f}) {
    fb.clear_color({0.2f, 0.4f, 0.6f}, 1.0f);
    RasterState state;
    state.depth_test = false;
    state.blend = true;
    state.blend_function = {BlendFactor::src_alpha, BlendFactor::one_minus_src_alpha};
    draw_triangles(fb, state, 4, quad, testing::FlatVertexShader{corners.data()},
                   Translucent<testing::FlatFragmentShader>{{Vec3f(0.9f, 0.1f, 0.3f)}, alpha});
    const glm::u8vec4 expected =
        alpha == 1 ? glm::u8vec4(to_color8(Vec3f(0.9f, 0.1f, 0.3f))) : glm::u8vec4(to_color8(Vec3f(0.2f, 0.4f, 0.6f)));
    EXPECT_EQ(Vec3(fb.color()(1, 1)), Vec3(expected)) << alpha;
  }
}

// An RGBA fragment shader's alpha is what the buffer stores (blending off), and Translucent scales it.
TEST(Raster, RgbaShadersStoreTheirAlpha) {
  const std::vector<Vec3f> corners{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<uint32_t> quad{0, 1, 2, 0, 2, 3};
  Framebuffer fb(4, 4);
  RasterState state;
  state.depth_test = false;
  const auto rgba = [](const NoVaryings&, Vec4f& c) {
    c = Vec4f(0.25f, 0.5f, 0.75f, 0.5f);
    return true;
  };
  draw_triangles(fb, state, 4, quad, testing::FlatVertexShader{corners.data()}, rgba);
  EXPECT_EQ(fb.color()(2, 2), glm::u8vec4(64, 128, 191, 128));
  draw_triangles(fb, state, 4, quad, testing::FlatVertexShader{corners.data()},
                 Translucent<decltype(rgba)>{rgba, 0.5f});
  EXPECT_EQ(fb.color()(2, 2).w, 64);
  draw_triangles(fb, state, 4, quad, testing::FlatVertexShader{corners.data()}, testing::FlatFragmentShader{});
  EXPECT_EQ(fb.color()(2, 2), glm::u8vec4(255, 255, 255, 255));  // an RGB shader's alpha is 1
}

}  // namespace
}  // namespace tessera::raster3d
