// A Context drawing through a GLSL program (use_program): the built-ins come from its state, and a program that does
// what the fixed function does gives its pixels exactly (ftransform() is invariant with it, the quad stage
// interpolates as the pipeline does).
#include "tessera/raster3d/context.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "glsl_test_util.hpp"

namespace tessera::glsl {
namespace {

// A UV sphere of radius 1 with per-vertex colors from the position.
TriMesh color_sphere(int rings, int segments) {
  TriMesh m;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const double theta = M_PI * r / rings, phi = 2 * M_PI * s / segments;
      const Vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(p);
      m.normals.push_back(p);
      m.colors.push_back(0.5 * p + 0.5);
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const auto a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments) + 1;
      m.indices.insert(m.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
  return m;
}

void set_camera(raster3d::Context& ctx) {
  ctx.matrix_mode(raster3d::MatrixMode::projection);
  ctx.perspective(M_PI / 3, 0.5, 10);
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  ctx.look_at(Vec3(0.3, 0.8, 3), Vec3(0), Vec3(0, 1, 0));
}

TEST(GlslContext, ColorProgramMatchesTheFixedFunctionExactly) {
  const TriMesh sphere = color_sphere(24, 48);
  raster3d::Context fixed(160, 120), programmable(160, 120);
  for (raster3d::Context* ctx : {&fixed, &programmable}) {
    set_camera(*ctx);
    ctx->shading(raster3d::ShadingModel::unlit);
  }
  programmable.use_program(std::make_shared<Program>(
      testing::compile("void main() { gl_FragColor = gl_Color; }",
                       "void main() { gl_FrontColor = gl_Color; gl_Position = ftransform(); }")));
  fixed.draw(sphere);
  programmable.draw(sphere);
  const raster3d::Framebuffer& a = fixed.framebuffer();
  const raster3d::Framebuffer& b = programmable.framebuffer();
  int color_diffs = 0, depth_diffs = 0, covered = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      color_diffs += a.color()(x, y) != b.color()(x, y);
      depth_diffs += a.depth()(x, y) != b.depth()(x, y);
      covered += a.depth()(x, y) != raster3d::kDepthMax;
    }
  EXPECT_GT(covered, 2000);
  EXPECT_EQ(color_diffs, 0);
  EXPECT_EQ(depth_diffs, 0);
}

TEST(GlslContext, BuiltInsComeFromTheContextState) {
  // The fragment color is the light's diffuse color times the material's, read through gl_LightSource[0] and
  // gl_FrontMaterial, and the current color's alpha channel is gl_Color.a.
  raster3d::Context ctx(16, 16);
  raster3d::Light light;
  light.diffuse = Vec3f(0.5f, 1.0f, 0.25f);
  ctx.light(0, light);
  raster3d::Material material;
  material.diffuse = Vec3f(1.0f, 0.5f, 1.0f);
  ctx.material(material);
  ctx.use_program(std::make_shared<Program>(testing::compile(
      "void main() { gl_FragColor = vec4((gl_LightSource[0].diffuse * gl_FrontMaterial.diffuse).rgb, 1.0); }",
      "void main() { gl_Position = gl_Vertex; }")));
  ctx.begin(raster3d::Primitive::quads);
  for (const auto& [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) ctx.vertex(x, y, 0);
  ctx.end();
  const Vec4f c = testing::pixel(ctx.framebuffer(), 8, 8);
  EXPECT_NEAR(c.x, 0.5f, 1.0f / 255);
  EXPECT_NEAR(c.y, 0.5f, 1.0f / 255);
  EXPECT_NEAR(c.z, 0.25f, 1.0f / 255);
}

}  // namespace
}  // namespace tessera::glsl
