// The Context and the gt layer: matrix stacks, immediate mode vs batched drawing, primitive assembly, shading
// models, double buffering, independence of contexts.
#include "tessera/raster3d/context.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "tessera/core/parallel.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/gt.hpp"

namespace tessera::raster3d {
namespace {

bool same_pixels(const Framebuffer& a, const Framebuffer& b) {
  return std::equal(a.color().pixels().begin(), a.color().pixels().end(), b.color().pixels().begin()) &&
         std::equal(a.depth().pixels().begin(), a.depth().pixels().end(), b.depth().pixels().begin());
}

void expect_near_matrix(const Mat4& a, const Mat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-12) << c << "," << r;
}

TEST(Context, MatrixStackFollowsMathTransforms) {
  Context ctx(16, 16);
  ctx.translate(1, 2, 3);
  ctx.push_matrix();
  ctx.rotate_y(0.3);
  ctx.scale(2, 3, 4);
  ctx.rotate(0.7, Vec3(1, 1, 0));
  expect_near_matrix(ctx.model_view(), translate(1, 2, 3) * rotate_y(0.3) * scale(2, 3, 4) * rotate(0.7, {1, 1, 0}));
  ctx.pop_matrix();
  expect_near_matrix(ctx.model_view(), translate(1, 2, 3));
  EXPECT_THROW(ctx.pop_matrix(), InvalidInput);
  ctx.look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  expect_near_matrix(ctx.model_view(), translate(1, 2, 3) * look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}));
  ctx.perspective(1.0, 0.5, 50);
  expect_near_matrix(ctx.projection(), perspective(1.0, 1.0, 0.5, 50));
  ctx.matrix_mode(MatrixMode::projection);
  ctx.load_identity();
  expect_near_matrix(ctx.projection(), Mat4(1.0));
}

// A lit sphere, drawn by `draw` after the shared camera and lighting setup.
template <class Draw>
Framebuffer render_sphere(ShadingModel shading, Draw&& draw) {
  Context ctx(96, 80);
  ctx.perspective(radians(40), 1, 20);
  ctx.look_at({0.5, 1, 4}, {0, 0, 0}, {0, 1, 0});
  ctx.shading(shading);
  ctx.material(Material::plastic({0.8f, 0.3f, 0.2f}, 30));
  ctx.light(0, Light{{1, 2, 3, 0}});
  ctx.cull(CullMode::back);
  draw(ctx);
  return std::move(ctx.framebuffer());
}

TEST(Context, ImmediateModeEqualsTheBatchedPath) {
  const TriMesh mesh = to_tri_mesh(make_uv_sphere(24, 12));
  for (ShadingModel shading : {ShadingModel::unlit, ShadingModel::flat, ShadingModel::gouraud, ShadingModel::phong}) {
    const Framebuffer batched = render_sphere(shading, [&](Context& ctx) { ctx.draw(mesh); });
    const Framebuffer immediate = render_sphere(shading, [&](Context& ctx) {
      gt::gtMakeCurrent(&ctx);
      gt::gtBeginShape(gt::GT_TRIANGLES);
      for (uint32_t i : mesh.indices) {
        const Vec3 n = mesh.normals[i], p = mesh.positions[i];
        gt::gtNormal(n.x, n.y, n.z);
        gt::gtVertex(p.x, p.y, p.z);
      }
      gt::gtEndShape();
      gt::gtMakeCurrent(nullptr);
    });
    EXPECT_TRUE(same_pixels(batched, immediate)) << int(shading);
    int lit = 0;
    for (auto c : batched.color().pixels()) lit += c.x > 0;
    EXPECT_GT(lit, 1000);
  }
}

TEST(Context, ImmediateModeKeepsVerticesThatDifferOnlyInNormalOrColor) {
  // Immediate mode stores a repeated vertex once per batch: the sphere's corners sent with per-face normals and
  // colors (each position with several different attribute sets, signed zeros included) must still equal the
  // batched draw of fully separate vertices.
  // A second pass shares the normal too, so that only the color (two different ones, alternating from triangle to
  // triangle, and back) tells the corners apart.
  const TriMesh mesh = to_tri_mesh(make_uv_sphere(24, 12));
  for (const bool face_normals : {true, false}) {
    VertexArrays separate;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      const Vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                 c = mesh.positions[mesh.indices[t + 2]];
      const Vec3f face = face_normals ? Vec3f(glm::normalize(glm::cross(b - a, c - a))) : Vec3f(0.6f, 0.0f, 0.8f);
      const Vec3f color = face_normals ? Vec3f(0.8f, 0.5f, t % 2 ? -0.0f : 0.0f)  // equal but for the sign of a zero
                                       : (t % 2 ? Vec3f(0.8f, 0.5f, 0.0f) : Vec3f(0.1f, 0.4f, 0.9f));
      for (const Vec3& p : {a, b, c}) {
        separate.indices.push_back(uint32_t(separate.positions.size()));
        separate.positions.emplace_back(p);
        separate.normals.push_back(face);
        separate.colors.push_back(color);
      }
    }
    for (ShadingModel shading : {ShadingModel::flat, ShadingModel::gouraud}) {
      const auto setup = [&](Context& ctx) { ctx.color_material(true); };
      const Framebuffer batched = render_sphere(shading, [&](Context& ctx) {
        setup(ctx);
        ctx.draw(separate);
      });
      const Framebuffer immediate = render_sphere(shading, [&](Context& ctx) {
        setup(ctx);
        ctx.begin(Primitive::triangles);
        for (size_t i = 0; i < separate.positions.size(); ++i) {
          ctx.normal(separate.normals[i]);
          ctx.color(separate.colors[i]);
          ctx.vertex(separate.positions[i].x, separate.positions[i].y, separate.positions[i].z);
        }
        ctx.end();
      });
      EXPECT_TRUE(same_pixels(batched, immediate)) << int(shading) << " face normals " << face_normals;
    }
  }
}

TEST(Context, ImmediateModeStripPastTheVertexCacheIndexRange) {
  // A triangle strip is not cut into batches, so its batch can hold more vertices than a cache entry indexes
  // (65536): 70000 distinct vertices on a spiral, sent twice, must equal the batched draw of the same triangles.
  constexpr uint32_t kDistinct = 70000;
  VertexArrays strip;
  for (uint32_t lap = 0; lap < 2; ++lap)
    for (uint32_t i = 0; i < kDistinct; ++i) {
      const double a = 0.05 * (i / 2), r = (i % 2 ? 1.0 : 0.8) - 1e-6 * i;
      strip.positions.emplace_back(Vec3(r * std::cos(a), r * std::sin(a), 0.1 * std::sin(3 * a)));
      strip.normals.emplace_back(glm::normalize(Vec3(std::cos(a), std::sin(a), 2.0)));
    }
  const auto n = uint32_t(strip.positions.size());
  for (uint32_t i = 0; i + 2 < n; ++i)  // the strip's winding, as assembled in immediate mode
    for (uint32_t k : i % 2 == 0 ? std::array{i, i + 1, i + 2} : std::array{i + 1, i, i + 2})
      strip.indices.push_back(k);
  const Framebuffer batched = render_sphere(ShadingModel::gouraud, [&](Context& ctx) {
    ctx.cull(CullMode::none);
    ctx.draw(strip);
  });
  const Framebuffer immediate = render_sphere(ShadingModel::gouraud, [&](Context& ctx) {
    ctx.cull(CullMode::none);
    ctx.begin(Primitive::triangle_strip);
    for (uint32_t i = 0; i < n; ++i) {
      ctx.normal(strip.normals[i]);
      ctx.vertex(strip.positions[i].x, strip.positions[i].y, strip.positions[i].z);
    }
    ctx.end();
  });
  EXPECT_TRUE(same_pixels(batched, immediate));
  int lit = 0;
  for (auto c : batched.color().pixels()) lit += c.x > 0;
  EXPECT_GT(lit, 500);  // the ring covers about 1000 of the 96 x 80 pixels
}

TEST(Context, UniformNormalGivesTheShadingEquationEverywhere) {
  // A screen-filling quad with one normal: Gouraud and Phong both give shade(n) at every pixel.
  for (ShadingModel shading : {ShadingModel::gouraud, ShadingModel::phong}) {
    Context ctx(32, 32);
    ctx.ortho(-1, 1, -1, 1, -1, 1);
    ctx.shading(shading);
    const Material m = Material::plastic({0.3f, 0.5f, 0.7f}, 5);
    ctx.material(m);
    ctx.light(0, Light{{0, 1, 2, 0}});
    ctx.normal(glm::normalize(Vec3f(0.2f, 0.1f, 1)));
    ctx.begin(Primitive::quads);
    for (auto [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) ctx.vertex(x, y, 0);
    ctx.end();
    Lighting lighting;
    lighting.material = m;
    lighting.lights[0].position = Vec4f(0, 1, 2, 0);
    const glm::u8vec4 expected = to_color8(shade(lighting, glm::normalize(Vec3f(0.2f, 0.1f, 1)), {0, 0, 0}, {1, 1, 1}));
    for (auto c : ctx.framebuffer().color().pixels()) ASSERT_EQ(c, expected) << int(shading);
  }
}

TEST(Context, DisabledLightLeavesTheAmbientTerm) {
  // glDisable(GL_LIGHT0): the shading equation without the light's terms, the model ambient times the material's
  // ambient (0.2 * 0.3, 0.2 * 0.5, 0.2 * 0.7), rounded to 8 bits: (15, 26, 36).
  Context ctx(8, 8);
  ctx.ortho(-1, 1, -1, 1, -1, 1);
  ctx.shading(ShadingModel::gouraud);
  ctx.material(Material::plastic({0.3f, 0.5f, 0.7f}, 5));
  ctx.light(0, Light{{0, 0, 1, 0}});
  ctx.enable_light(0, false);
  ctx.normal({0, 0, 1});
  ctx.begin(Primitive::quads);
  for (auto [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) ctx.vertex(x, y, 0);
  ctx.end();
  for (auto c : ctx.framebuffer().color().pixels()) ASSERT_EQ(c, glm::u8vec4(15, 26, 36, 255));
  ctx.enable_light(0, true);  // back on: the head-on light adds the diffuse color and the highlight
  ctx.clear({0, 0, 0});
  ctx.begin(Primitive::quads);
  for (auto [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) ctx.vertex(x, y, 0);
  ctx.end();
  EXPECT_GT(int(ctx.framebuffer().color().pixels()[0].x), 15 + 60);
  EXPECT_THROW(ctx.enable_light(8, true), InvalidInput);
}

TEST(Context, WireframeDrawsTheEdgesNotTheFaces) {
  // Two triangles of a square (the diagonal shared): five edges. Unlit white lines on black in a 64 x 64
  // window over [0, 64]^2: the square's outline covers 4 sides of ~40 pixels, the diagonal ~40 more (one per column).
  Context ctx(64, 64);
  ctx.ortho(0, 64, 0, 64, -1, 1);
  ctx.shading(ShadingModel::unlit);
  ctx.color({1, 1, 1});
  TriMesh square;
  square.positions = {{12.5, 12.5, 0}, {52.5, 12.5, 0}, {52.5, 52.5, 0}, {12.5, 52.5, 0}};
  square.indices = {0, 1, 2, 0, 2, 3};
  ctx.draw_wireframe(square);
  ctx.flush();
  int lit = 0;
  for (auto c : ctx.framebuffer().color().pixels()) lit += c.x > 0;
  EXPECT_GE(lit, 4 * 40 + 40 - 8);  // corners shared by two sides, the diagonal's ends on corners
  EXPECT_LE(lit, 4 * 41 + 41);
  // Inside the triangles nothing is filled: the pixel at (20, 40) (above the diagonal, off every edge) stays black.
  EXPECT_EQ(ctx.framebuffer().color().pixels()[size_t(40 * 64 + 20)].x, 0);
}

TEST(Context, IndexedLinesDrawAsImmediateModeLines) {
  // A star of segments (steep, shallow, diagonal, crossing, one leaving the window) in the current color: the indexed
  // draw gives the bytes of the same segments given vertex by vertex between begin(lines) and end().
  const std::vector<Vec3f> points = {{-0.9f, -0.8f, 0.1f}, {0.7f, 0.9f, -0.2f}, {0.95f, -0.3f, 0},
                                     {-0.4f, 0.6f, 0.3f},  {1.6f, 0.2f, 0},     {0.05f, -0.95f, -0.5f}};
  const std::vector<uint32_t> lines = {0, 1, 2, 3, 1, 4, 5, 3, 0, 2};
  const auto render = [&](auto&& submit) {
    Context ctx(48, 40);
    ctx.shading(ShadingModel::unlit);
    ctx.color({0.9f, 0.5f, 0.2f});
    submit(ctx);
    ctx.flush();
    const auto pixels = ctx.framebuffer().color().pixels();
    return std::vector<glm::u8vec4>(pixels.begin(), pixels.end());
  };
  VertexArrays arrays;
  arrays.positions = points;
  const auto indexed = render([&](Context& c) { c.draw_lines(arrays, lines); });
  const auto immediate = render([&](Context& c) {
    c.begin(Primitive::lines);
    for (uint32_t i : lines) c.vertex(points[i].x, points[i].y, points[i].z);
    c.end();
  });
  EXPECT_EQ(indexed, immediate);
  EXPECT_GT(std::count_if(indexed.begin(), indexed.end(), [](auto c) { return c.x > 0; }), 100);
  Context ctx(8, 8);
  EXPECT_THROW(ctx.draw_lines(arrays, std::vector<uint32_t>{0, 1, 2}), InvalidInput);  // an odd count
  EXPECT_THROW(ctx.draw_lines(arrays, std::vector<uint32_t>{0, 6}), InvalidInput);     // out of range
}

TEST(Context, PrimitiveAssemblyCoversLikeExplicitTriangles) {
  // A strip, a fan, quads and a polygon over the same region as triangles: identical coverage.
  const std::vector<Vec3> ring = {{-0.9, -0.8, 0}, {0.7, -0.9, 0}, {0.9, 0.6, 0}, {-0.2, 0.95, 0}, {-0.95, 0.3, 0}};
  auto render = [&](auto&& submit) {
    Context ctx(40, 40);
    ctx.ortho(-1, 1, -1, 1, -1, 1);
    submit(ctx);
    Framebuffer fb = std::move(ctx.framebuffer());
    std::vector<int> cov;
    for (auto c : fb.color().pixels()) cov.push_back(c.x > 0);
    return cov;
  };
  const auto triangles = render([&](Context& c) {
    c.begin(Primitive::triangles);
    for (int i = 1; i + 1 < 5; ++i)
      for (int k : {0, i, i + 1}) c.vertex(ring[k].x, ring[k].y, 0);
    c.end();
  });
  const auto fan = render([&](Context& c) {
    c.begin(Primitive::triangle_fan);
    for (const Vec3& p : ring) c.vertex(p.x, p.y, 0);
    c.end();
  });
  const auto polygon = render([&](Context& c) {
    c.begin(Primitive::polygon);
    for (const Vec3& p : ring) c.vertex(p.x, p.y, 0);
    c.end();
  });
  const auto strip = render([&](Context& c) {  // 0 1 4 2 3 as a strip makes triangles 014, 142, 423
    c.begin(Primitive::triangle_strip);
    for (int k : {0, 1, 4, 2, 3}) c.vertex(ring[k].x, ring[k].y, 0);
    c.end();
  });
  EXPECT_EQ(fan, triangles);
  EXPECT_EQ(polygon, triangles);
  EXPECT_EQ(strip, triangles);
  int n = 0;
  for (int v : triangles) n += v;
  EXPECT_GT(n, 600);
}

TEST(Context, FlatShadingUsesTheProvokingVertex) {
  Context ctx(16, 16);
  ctx.ortho(-1, 1, -1, 1, -1, 1);
  ctx.shading(ShadingModel::flat);
  ctx.color_material(true);
  ctx.light_model_ambient(Vec3f(1));  // lit color = vertex color * (1 + N.L): clamp to the vertex color's 1s
  ctx.begin(Primitive::triangles);
  ctx.color({1, 0, 0});
  ctx.vertex(-1, -1, 0);
  ctx.color({0, 1, 0});
  ctx.vertex(1, -1, 0);
  ctx.color({0, 0, 1});
  ctx.vertex(-1, 1, 0);
  ctx.end();
  EXPECT_EQ(ctx.framebuffer().color()(1, 14), glm::u8vec4(0, 0, 255, 255));
  EXPECT_EQ(ctx.framebuffer().color()(10, 14), glm::u8vec4(0, 0, 255, 255));
}

TEST(Context, TwoContextsDoNotInterfere) {
  const TriMesh mesh = to_tri_mesh(make_torus(1, 0.4, 24, 12));
  auto setup = [](Context& c, double angle, Vec3f color) {
    c.perspective(radians(45), 0.5, 20);
    c.look_at({0, 2, 4}, {0, 0, 0}, {0, 1, 0});
    c.rotate_y(angle);
    c.color(color);
    c.shading(ShadingModel::gouraud);
  };
  Context a(64, 64), b(64, 64), a_alone(64, 64);
  setup(a, 0.3, {1, 0, 0});
  setup(b, 1.2, {0, 1, 0});
  b.light(0, Light{{0, 1, 0, 0}});
  b.begin(Primitive::triangles);
  a.begin(Primitive::triangles);  // both open at once
  for (uint32_t i : mesh.indices) {
    a.normal(Vec3f(mesh.normals[i]));
    a.vertex(mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z);
    b.vertex(mesh.positions[i].x, -mesh.positions[i].y, mesh.positions[i].z);
  }
  a.end();
  b.end();
  setup(a_alone, 0.3, {1, 0, 0});
  a_alone.begin(Primitive::triangles);
  for (uint32_t i : mesh.indices) {
    a_alone.normal(Vec3f(mesh.normals[i]));
    a_alone.vertex(mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z);
  }
  a_alone.end();
  EXPECT_TRUE(same_pixels(a.framebuffer(), a_alone.framebuffer()));
  EXPECT_FALSE(same_pixels(a.framebuffer(), b.framebuffer()));
}

TEST(Context, ContextsOnTwoThreadsAtOnce) {
  // Each thread makes its own context current (the current context is per thread) and draws through the gt layer;
  // the results equal the same drawings made one after the other.
  const TriMesh mesh = to_tri_mesh(make_uv_sphere(32, 16));
  auto draw = [&](double angle) {
    Context ctx(64, 64);
    gt::gtMakeCurrent(&ctx);
    gt::gtPerspective(radians(40), 1, 20);
    gt::gtLookAt(0, 0, 4, 0, 0, 0, 0, 1, 0);
    gt::gtRotateY(angle);
    ctx.shading(ShadingModel::phong);
    ctx.material(Material::metal({0.9f, 0.6f, 0.2f}, 20));
    for (int k = 0; k < 5; ++k) {
      gt::gtBeginShape(gt::GT_TRIANGLES);
      for (uint32_t i : mesh.indices) {
        gt::gtNormal(mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z);
        gt::gtVertex(mesh.positions[i].x, mesh.positions[i].y + 0.1 * k, mesh.positions[i].z);
      }
      gt::gtEndShape();
    }
    gt::gtMakeCurrent(nullptr);
    return std::move(ctx.framebuffer());
  };
  const Framebuffer a_alone = draw(0.2), b_alone = draw(1.4);
  std::optional<Framebuffer> a, b;
  std::thread ta([&] { a.emplace(draw(0.2)); }), tb([&] { b.emplace(draw(1.4)); });
  ta.join();
  tb.join();
  EXPECT_TRUE(same_pixels(*a, a_alone));
  EXPECT_TRUE(same_pixels(*b, b_alone));
}

// A frame that changes some state before nearly every shape, with immediate-mode batches of every size (one
// triangle to several full batches of ~8-pixel triangles), batched draws, lines, points and a clear in between.
// With `synchronous` every call is followed by flush(), so nothing is collected or set up while tiles are drawn.
Framebuffer render_state_churn(bool synchronous) {
  Context ctx(200, 136);  // 4 x 3 tiles, the last column and row partial
  const auto step = [&] {
    if (synchronous) ctx.flush();
  };
  const TriMesh sphere = to_tri_mesh(make_uv_sphere(20, 10));
  ctx.perspective(radians(50), 0.5, 20);
  ctx.look_at({0, 0.5, 4}, {0, 0, 0}, {0, 1, 0});
  ctx.light(0, Light{{1, 2, 3, 0}});
  ctx.clear({0.1f, 0.2f, 0.3f});
  for (int k = 0; k < 24; ++k) {
    if (k == 12) ctx.clear({0.3f, 0.1f, 0.1f});  // waits for what is in flight, then wipes it
    ctx.shading(ShadingModel(k % 4));
    ctx.material(Material::plastic({0.2f + 0.03f * float(k), 0.5f, 0.9f - 0.03f * float(k)}, 10.0f + float(k)));
    ctx.depth_func(k % 5 == 4 ? DepthFunc::lequal : DepthFunc::less);
    ctx.cull(k % 3 == 0 ? CullMode::back : CullMode::none);
    ctx.push_matrix();
    ctx.rotate_y(0.3 * k);
    ctx.translate(0.9 * std::cos(0.5 * k), 0.6 * std::sin(0.7 * k), 0.1 * (k % 7));
    ctx.scale(0.5, 0.5, 0.5);
    step();
    if (k % 6 == 5) {
      ctx.draw(sphere);
    } else {
      ctx.begin(Primitive::triangles);
      const size_t triangles = k % 6 == 4 ? 1 : sphere.indices.size() / 3;
      for (size_t i = 0; i < 3 * triangles; ++i) {
        const uint32_t v = sphere.indices[i];
        if (i % 7 == 0) ctx.color(Vec3f(float(i % 5) / 4, 0.5f, float(k) / 24));
        ctx.normal(Vec3f(sphere.normals[v]));
        ctx.vertex(sphere.positions[v].x, sphere.positions[v].y, sphere.positions[v].z);
      }
      ctx.end();
    }
    ctx.pop_matrix();
    step();
  }
  // A fine grid over the view: 2 x 140 x 100 triangles of ~1 pixel, several immediate-mode batches in one shape.
  ctx.shading(ShadingModel::gouraud);
  ctx.depth_func(DepthFunc::less);
  ctx.begin(Primitive::triangles);
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 140; ++i) {
      const auto corner = [&](int di, int dj) {
        const double x = -2 + 4.0 * (i + di) / 140, y = -1.5 + 3.0 * (j + dj) / 100;
        ctx.normal(Vec3f(float(0.3 * std::sin(3 * x)), float(0.3 * std::cos(2 * y)), 1.0f));
        ctx.vertex(x, y, -0.5 + 0.2 * std::sin(x * y));
      };
      corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 0), corner(1, 1), corner(0, 1);
    }
  ctx.end();
  step();
  ctx.shading(ShadingModel::unlit);
  ctx.color(Vec3f(1, 1, 0));
  ctx.begin(Primitive::line_loop);
  for (int i = 0; i < 12; ++i) ctx.vertex(1.5 * std::cos(0.5 * i), 1.2 * std::sin(0.5 * i), 0.5);
  ctx.end();
  ctx.begin(Primitive::points);
  for (int i = 0; i < 40; ++i) ctx.vertex(-1.8 + 0.09 * i, -1.0, 0.6);
  ctx.end();
  return std::move(ctx.framebuffer());
}

TEST(Context, PipelinedDrawingEqualsDrawingOneCallAtATime) {
  // The raster thread draws a batch while the caller changes state and collects the next one: every batch must still
  // be drawn with the state it was specified under, in order, on 1, 2 and 4 threads alike.
  const Framebuffer synchronous = render_state_churn(true);
  for (int threads : {1, 2, 4}) {
    const ThreadLimit limit(threads);
    for (int run = 0; run < 3; ++run) EXPECT_TRUE(same_pixels(render_state_churn(false), synchronous)) << threads;
  }
  // Not a blank frame: several colors, and the grid covers most of the view.
  std::set<uint32_t> colors;
  int background = 0;
  for (const auto c : synchronous.color().pixels()) {
    colors.insert(uint32_t(c.x) | uint32_t(c.y) << 8 | uint32_t(c.z) << 16);
    background += c == glm::u8vec4(77, 26, 26, 255);  // the second clear color
  }
  EXPECT_GT(colors.size(), 1000u);
  EXPECT_LT(background, synchronous.width() * synchronous.height() / 4);
}

TEST(Context, StatsCountTheTrianglesTheRasterJobsSetUp) {
  // The raster thread sets up the last chunks of every pass: once flush() returns, their triangles are counted too.
  // 40000 small triangles, none culled or clipped: more than two passes of the immediate-mode batch.
  for (int threads : {1, 2}) {
    const ThreadLimit limit(threads);
    Context ctx(200, 200);
    ctx.ortho(0, 200, 0, 200, -1, 1);
    ctx.begin(Primitive::triangles);
    for (int t = 0; t < 40000; ++t) {
      const double x = 1 + t % 190, y = 1 + (t / 190) % 190;
      ctx.vertex(x, y, 0.5);
      ctx.vertex(x + 3, y, 0.5);
      ctx.vertex(x, y + 3, 0.5);
    }
    ctx.end();
    ctx.flush();
    EXPECT_EQ(ctx.stats().primitives, 40000u) << threads;
    EXPECT_EQ(ctx.stats().rasterized, 40000u) << threads;
  }
}

TEST(Context, DoubleBufferingPresentsOnSwap) {
  Context ctx(8, 8);
  ctx.clear({0, 0, 1});
  EXPECT_EQ(ctx.framebuffer().front()(0, 0), glm::u8vec4(0, 0, 0, 255));
  ctx.swap_buffers();
  EXPECT_EQ(ctx.framebuffer().front()(0, 0), glm::u8vec4(0, 0, 255, 255));
  EXPECT_EQ(ctx.framebuffer().color()(0, 0), glm::u8vec4(0, 0, 0, 255));
}

TEST(Context, PainterModeDrawsFarToNear) {
  // Two overlapping quads submitted near first: the z-buffer and the painter agree, no depth test keeps the last.
  auto render = [](HiddenSurface method, bool depth) {
    Context ctx(16, 16);
    ctx.ortho(-1, 1, -1, 1, -1, 1);
    ctx.hidden_surface(method);
    ctx.depth_test(depth);
    ctx.begin(Primitive::quads);
    ctx.color({1, 0, 0});
    for (auto [x, y] : {std::pair{-1.0, -1.0}, {0.5, -1.0}, {0.5, 0.5}, {-1.0, 0.5}}) ctx.vertex(x, y, 0.5);  // near
    ctx.color({0, 1, 0});
    for (auto [x, y] : {std::pair{-0.5, -0.5}, {1.0, -0.5}, {1.0, 1.0}, {-0.5, 1.0}}) ctx.vertex(x, y, -0.5);  // far
    ctx.end();
    return ctx.framebuffer().color()(8, 8);
  };
  EXPECT_EQ(render(HiddenSurface::zbuffer, true), glm::u8vec4(255, 0, 0, 255));
  EXPECT_EQ(render(HiddenSurface::painter, true), glm::u8vec4(255, 0, 0, 255));
  EXPECT_EQ(render(HiddenSurface::zbuffer, false), glm::u8vec4(0, 255, 0, 255));
}

TEST(Context, StencilMaskConfinesLaterDrawing) {
  // A triangle drawn into the stencil buffer only (no color, no depth), then a red full-screen quad where the stencil
  // holds 1: red exactly where the same triangle drawn in color covers, black elsewhere; the state changes are
  // pipelined with the draws.
  auto quad = [](Context& ctx, Vec3f color) {
    ctx.begin(Primitive::quads);
    ctx.color(color);
    for (auto [x, y] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) ctx.vertex(x, y, 0);
    ctx.end();
  };
  auto triangle = [](Context& ctx) {
    ctx.begin(Primitive::triangles);
    ctx.color({1, 0, 0});
    for (auto [x, y] : {std::pair{-0.8, -0.7}, {0.9, -0.2}, {-0.1, 0.8}}) ctx.vertex(x, y, 0);
    ctx.end();
  };
  Context masked(32, 32), direct(32, 32);
  for (Context* ctx : {&masked, &direct}) {
    ctx->ortho(-1, 1, -1, 1, -1, 1);
    ctx->clear({0, 0, 0});
    ctx->depth_test(false);
  }
  masked.clear_stencil(0);
  masked.stencil_test(true);
  masked.color_write(false);
  StencilFace write_one{.func = DepthFunc::always, .ref = 1, .zpass = StencilOp::replace};
  masked.stencil(write_one, write_one);
  triangle(masked);
  masked.color_write(true);
  StencilFace where_one{.func = DepthFunc::equal, .ref = 1};
  masked.stencil(where_one, where_one);
  quad(masked, {1, 0, 0});
  triangle(direct);
  const Framebuffer& a = masked.framebuffer();
  const Framebuffer& b = direct.framebuffer();
  int red = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      ASSERT_EQ(a.color()(x, y), b.color()(x, y)) << x << ", " << y;
      ASSERT_EQ(a.stencil()(x, y), b.color()(x, y).x ? 1 : 0) << x << ", " << y;
      red += a.color()(x, y).x ? 1 : 0;
    }
  EXPECT_GT(red, 200);
}

TEST(Context, GtLayerMisuseThrows) {
  gt::gtMakeCurrent(nullptr);
  EXPECT_THROW(gt::gtVertex(0, 0, 0), InvalidInput);
  Context ctx(8, 8);
  gt::gtMakeCurrent(&ctx);
  EXPECT_THROW(gt::gtVertex(0, 0, 0), InvalidInput);  // outside a shape
  EXPECT_THROW(gt::gtEndShape(), InvalidInput);
  gt::gtBeginShape(gt::GT_LINES);
  EXPECT_THROW(gt::gtBeginShape(gt::GT_LINES), InvalidInput);
  EXPECT_THROW(gt::gtTranslate(1, 0, 0), InvalidInput);  // matrices are fixed inside a shape, as OpenGL
  gt::gtEndShape();
  EXPECT_THROW(ctx.light(8, Light{}), InvalidInput);
  gt::gtRotate(0.5, 0, 0, 2);
  expect_near_matrix(ctx.model_view(), rotate_z(0.5));
  gt::gtMakeCurrent(nullptr);
}

TEST(Context, MeshWithMismatchedAttributesThrows) {
  TriMesh mesh = to_tri_mesh(make_tetrahedron());
  mesh.colors.assign(2, Vec3(1));
  Context ctx(8, 8);
  EXPECT_THROW(ctx.draw(mesh), InvalidInput);
}

// Triangles far to near through the model-view: three quads at z = -1, -3, -2 (in that order in the arrays) come out
// -3, -2, -1; a rotation that turns the scene around reverses the order.
TEST(Context, SortBackToFrontOrdersByEyeDepth) {
  VertexArrays arrays;
  for (const float z : {-1.0f, -3.0f, -2.0f}) {
    const auto base = uint32_t(arrays.positions.size());
    for (const Vec3f& p : {Vec3f(0, 0, z), Vec3f(1, 0, z), Vec3f(1, 1, z), Vec3f(0, 1, z)})
      arrays.positions.push_back(p);
    arrays.indices.insert(arrays.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  const auto depths = [&] {
    std::vector<float> z;
    for (size_t t = 0; t < arrays.indices.size(); t += 3) z.push_back(arrays.positions[arrays.indices[t]].z);
    return z;
  };
  sort_back_to_front(arrays, Mat4(1.0));
  EXPECT_EQ(depths(), (std::vector<float>{-3, -3, -2, -2, -1, -1}));
  sort_back_to_front(arrays, rotate_y(kPi));  // now z = -1 is the farthest
  EXPECT_EQ(depths(), (std::vector<float>{-1, -1, -2, -2, -3, -3}));
}

// Context::alpha and blend: a white unlit quad at alpha 0.5 "over" black stores round(0.5 * 255) = 128 (the alpha
// rounded to 8 bits first, then the product rounded); over a red layer, the two mix; with blending off, the quad
// replaces the layer and its alpha is stored.
TEST(Context, AlphaBlendsOver) {
  Context ctx(8, 8);
  ctx.clear({0, 0, 0});
  const auto quad = [&] {
    ctx.begin(Primitive::quads);
    ctx.vertex(-1, -1, 0);
    ctx.vertex(1, -1, 0);
    ctx.vertex(1, 1, 0);
    ctx.vertex(-1, 1, 0);
    ctx.end();
  };
  ctx.depth_test(false);
  ctx.alpha(0.5f);
  ctx.blend(true);
  ctx.blend_function({BlendFactor::src_alpha, BlendFactor::one_minus_src_alpha});
  quad();
  EXPECT_EQ(ctx.framebuffer().color()(4, 4), glm::u8vec4(128, 128, 128, 191));  // alpha: 0.5 + 0.5 * (1 - 0.5)
  ctx.clear({1, 0, 0});
  quad();
  EXPECT_EQ(Vec3(ctx.framebuffer().color()(4, 4)), Vec3(255, 128, 128));
  ctx.blend(false);
  quad();
  EXPECT_EQ(ctx.framebuffer().color()(4, 4), glm::u8vec4(255, 255, 255, 128));
}

}  // namespace
}  // namespace tessera::raster3d
