// The notes' shaders (diffuse, twist) and per-pixel against per-vertex shading.
#include <gtest/gtest.h>

#include <cmath>

#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"

namespace tessera::raster3d {
namespace {

TEST(Shaders, DiffuseShaderGivesRedTimesNDotL) {
  // A unit sphere under an orthographic camera, the light far along +z: at the pixel through the sphere's center the
  // normal faces the light (N.L = 1, pure red), and at image point (x, y) N.L is sqrt(1 - x^2 - y^2) approximately.
  const VertexArrays sphere = VertexArrays::from_mesh(to_tri_mesh(make_uv_sphere(96, 48)));
  const int size = 64;
  Framebuffer fb(size, size);
  DiffuseVertexShader vs;
  vs.attributes = sphere.attributes();
  vs.model_view = Mat4f(translate(0, 0, -5));
  vs.model_view_projection = Mat4f(ortho(-1.25, 1.25, -1.25, 1.25, 1, 10)) * vs.model_view;
  vs.normal_matrix = Mat3f(1.0f);
  vs.light_position = Vec3f(0, 0, 1000);
  draw_triangles(fb, RasterState{}, uint32_t(sphere.positions.size()), sphere.indices, vs, DiffuseFragmentShader{});
  int checked = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double px = ((x + 0.5) / size * 2 - 1) * 1.25, py = (1 - (y + 0.5) / size * 2) * 1.25;
      const double r2 = px * px + py * py;
      if (r2 > 0.8) continue;  // away from the faceted silhouette
      const auto c = fb.color()(x, y);
      EXPECT_EQ(c.y, 0);
      EXPECT_EQ(c.z, 0);
      EXPECT_NEAR(c.x / 255.0, std::sqrt(1 - r2), 0.02) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 1000);
}

TEST(Shaders, TwistRotatesByDistanceFromTheCenter) {
  const std::vector<Vec3f> positions = {{0.5f, 0, 0}, {0, 0, 0}, {0.3f, 0.4f, 0.2f}};
  TwistVertexShader vs;
  vs.attributes.positions = positions.data();
  vs.twist = 2.0f;
  // Distance 0.5 from the center: rotated counterclockwise by 1 radian.
  const Vec4f p = vs(0).position;
  EXPECT_NEAR(p.x, 0.5f * std::cos(1.0f), 1e-6f);
  EXPECT_NEAR(p.y, 0.5f * std::sin(1.0f), 1e-6f);
  EXPECT_EQ(vs(1).position, Vec4f(0, 0, 0, 1));  // the center stays
  const Vec4f q = vs(2).position;                // distance 0.5 again: same angle, z and w kept
  EXPECT_NEAR(q.x, std::cos(1.0f) * 0.3f - std::sin(1.0f) * 0.4f, 1e-6f);
  EXPECT_NEAR(q.y, std::sin(1.0f) * 0.3f + std::cos(1.0f) * 0.4f, 1e-6f);
  EXPECT_EQ(q.z, 0.2f);
  EXPECT_EQ(vs(2).varyings.color, Vec3f(1, 1, 1));
  vs.twist = 0;
  EXPECT_EQ(vs(2).position, Vec4f(0.3f, 0.4f, 0.2f, 1));
}

TEST(Shaders, PhongInterpolationCatchesAHighlightGouraudMisses) {
  // One big quad whose corner normals tilt away from the viewer; the light and viewer are head-on, so the highlight
  // peaks in the middle, where the interpolated normal is (0, 0, 1). Gouraud only sees the corners' dim highlight.
  auto render = [](ShadingModel shading) {
    Context ctx(33, 33);
    ctx.ortho(-1, 1, -1, 1, -1, 1);
    ctx.shading(shading);
    Material m;
    m.diffuse = Vec3f(0);
    m.ambient = Vec3f(0);
    m.specular = Vec3f(1);
    m.shininess = 50;
    ctx.material(m);
    ctx.begin(Primitive::quads);
    for (auto [x, y] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) {
      ctx.normal(glm::normalize(Vec3f(float(x), float(y), 1.5f)));
      ctx.vertex(x, y, 0);
    }
    ctx.end();
    return ctx.framebuffer().color()(16, 16).x;
  };
  EXPECT_GE(render(ShadingModel::phong), 250);  // (H.N)^50 = 1 at the center
  EXPECT_LE(render(ShadingModel::gouraud), 10);
}

TEST(Shaders, ViewportPlacesTheImage) {
  // glViewport(8, 4, 16, 8): a full-screen quad covers exactly that rectangle (y up from the bottom).
  Context ctx(32, 32);
  ctx.viewport(8, 4, 16, 8);
  ctx.begin(Primitive::quads);
  for (auto [x, y] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) ctx.vertex(x * 2, y * 2, 0);
  ctx.end();
  const Framebuffer& fb = ctx.framebuffer();
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const int j = 31 - y;
      const bool inside = x >= 8 && x < 24 && j >= 4 && j < 12;
      EXPECT_EQ(fb.color()(x, y).x == 255, inside) << x << "," << y;
    }
}

}  // namespace
}  // namespace tessera::raster3d
