// The notes' texture and two-texture shaders against their formulas: texel-exact nearest sampling, the bilinear
// formula, the +-0.2 shift, the Venn picture's three regions, and texture2D's level of detail from the derivatives.
#include "tessera/raster3d/notes_shaders.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera::raster3d {
namespace {

// The quad [-1, 1]^2 in clip space (identity MVP: it covers the whole framebuffer), uv (0, 0) at the bottom left.
VertexArrays screen_quad() {
  VertexArrays q;
  q.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  q.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  q.indices = {0, 1, 2, 0, 2, 3};
  return q;
}

// The texture coordinate of pixel (x, y)'s center on a size x size framebuffer covered by screen_quad (row 0 on top).
Vec2f pixel_uv(int x, int y, int size) { return {(x + 0.5f) / float(size), 1 - (y + 0.5f) / float(size)}; }

Vec4f to_float(const glm::u8vec4& c) { return Vec4f(c) / 255.0f; }

TEST(NotesShaders, TextureShaderCopiesTexelsOneToOne) {
  // With as many pixels as texels and nearest filtering, gl_FragColor = texture2D(tex, uv) is texel (x, y) at pixel
  // (x, y): each pixel center is its texel's center.
  const int size = 16;
  ImageRGBA image(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      image(x, y) = Vec4f(float(x * 16) / 255, float(y * 16) / 255, float((x * y) % 256) / 255, 1);
  const Texture2D texture(image, Sampler{.filter = Filter::nearest});
  Framebuffer fb(size, size);
  draw_textured(fb, RasterState{}, screen_quad(), Mat4(1.0), texture);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::u8vec4 c = fb.color()(x, y);
      EXPECT_EQ(int(c.x), x * 16) << x << "," << y;
      EXPECT_EQ(int(c.y), y * 16) << x << "," << y;
      EXPECT_EQ(int(c.z), (x * y) % 256) << x << "," << y;
    }
}

TEST(NotesShaders, TextureShaderFollowsTheBilinearFormula) {
  // A 2 x 2 texture (clamped) magnified to 8 x 8: the notes' bilinear weights from the texel centers at 1/4 and 3/4.
  ImageRGBA image(2, 2);
  image(0, 1) = {1, 0, 0, 1};  // bottom left
  image(1, 1) = {0, 1, 0, 1};  // bottom right
  image(0, 0) = {0, 0, 1, 1};  // top left
  image(1, 0) = {1, 1, 1, 1};  // top right
  const Texture2D texture(image, Sampler{.wrap_u = Wrap::clamp, .wrap_v = Wrap::clamp, .filter = Filter::bilinear});
  const int size = 8;
  Framebuffer fb(size, size);
  draw_textured(fb, RasterState{}, screen_quad(), Mat4(1.0), texture);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const Vec2f uv = pixel_uv(x, y, size);
      const float a = std::clamp(2 * uv.x - 0.5f, 0.0f, 1.0f), b = std::clamp(2 * uv.y - 0.5f, 0.0f, 1.0f);
      const Vec4f expected =
          (1 - b) * ((1 - a) * image(0, 1) + a * image(1, 1)) + b * ((1 - a) * image(0, 0) + a * image(1, 0));
      const Vec4f got = to_float(fb.color()(x, y));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 0.6 / 255) << x << "," << y << " channel " << k;
    }
}

TEST(NotesShaders, TextureShaderLevelOfDetailFromDerivatives) {
  // texture2D's level of detail: a footprint of the whole 4 x 4 texture (duv/dx = (1, 0): rho = 4 texels, lod 2)
  // reads the last MIPmap level, the texture's mean; a footprint of one texel reads level 0.
  ImageRGBA image(4, 4, Vec4f(0, 0, 0, 1));
  image(1, 2) = Vec4f(1, 1, 1, 1);
  const Texture2D texture(image, Sampler{.filter = Filter::trilinear});
  const TextureFragmentShader fs{&texture};
  Vec4f color;
  ASSERT_TRUE(fs({{0.3f, 0.6f}}, {{1, 0}}, {{0, 0}}, color));
  EXPECT_NEAR(color.x, 1.0f / 16, 1e-6);
  ASSERT_TRUE(fs({{0.375f, 0.375f}}, {{0.25f, 0}}, {{0, 0.25f}}, color));  // texel (1, 1) from the bottom = row 2
  EXPECT_NEAR(color.x, 1.0f, 1e-6);
}

TEST(NotesShaders, TwoTextureVertexShaderShiftsByPointTwo) {
  const std::vector<Vec3f> positions = {{0.5f, -0.25f, 0.1f}};
  const std::vector<Vec2f> uvs = {{0.5f, 0.3f}};
  TwoTextureVertexShader vs;
  vs.attributes.positions = positions.data();
  vs.attributes.uvs = uvs.data();
  const auto out = vs(0);
  EXPECT_FLOAT_EQ(out.varyings.left.x, 0.3f);
  EXPECT_FLOAT_EQ(out.varyings.left.y, 0.3f);
  EXPECT_FLOAT_EQ(out.varyings.right.x, 0.7f);
  EXPECT_FLOAT_EQ(out.varyings.right.y, 0.3f);
  EXPECT_EQ(out.position, Vec4f(0.5f, -0.25f, 0.1f, 1.0f));
}

TEST(NotesShaders, TwoTextureShaderDrawsTheVennDiagram) {
  // One white disc of radius 1/4 at (1/2, 1/2) on black: 0.5 (disc(uv - (0.2, 0)) + disc(uv + (0.2, 0))) is two
  // discs centered at u = 0.7 and u = 0.3, gray where one covers the pixel and white where both do (the lens).
  const int size = 128, texels = 128;
  const double r = 0.25;
  const Texture2D texture = disc_texture(texels, r, Vec4f(1), Vec4f(0, 0, 0, 1), Filter::nearest);
  Framebuffer fb(size, size);
  draw_two_textured(fb, RasterState{}, screen_quad(), Mat4(1.0), texture);
  int counts[3] = {0, 0, 0};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const Vec2f uv = pixel_uv(x, y, size);
      const double dl = std::hypot(uv.x - 0.2 - 0.5, uv.y - 0.5), dr = std::hypot(uv.x + 0.2 - 0.5, uv.y - 0.5);
      if (std::abs(dl - r) < 1.5 / texels || std::abs(dr - r) < 1.5 / texels) continue;  // a texel from a circle
      const int inside = int(dl < r) + int(dr < r);
      ++counts[inside];
      EXPECT_NEAR(fb.color()(x, y).x, 127.5 * inside, 0.5) << x << "," << y;
    }
  EXPECT_GT(counts[0], 1000);
  EXPECT_GT(counts[1], 1000);
  EXPECT_GT(counts[2], 150);  // the lens: 0.0204 of the square (334 pixels), less the band along the circles
}

TEST(NotesShaders, TwoTexturesMixWhereTheyOverlap) {
  // A red disc read at uv - 0.2 and a blue one at uv + 0.2: the red disc appears shifted right, the blue one left, each
  // at half strength, and the lens where they overlap is half of each (purple).
  const Texture2D red = disc_texture(64, 0.25, {1, 0, 0, 1}, {0, 0, 0, 1}, Filter::nearest);
  const Texture2D blue = disc_texture(64, 0.25, {0, 0, 1, 1}, {0, 0, 0, 1}, Filter::nearest);
  const int size = 64;
  Framebuffer fb(size, size);
  draw_two_textured(fb, RasterState{}, screen_quad(), Mat4(1.0), red, &blue);
  // Pixel centers at u = 0.5 (both), u = 0.7 (the red disc only: 0.7 - 0.2 = 0.5), u = 0.3 (the blue one only).
  const auto expect_color = [&](float u, const Vec3f& expected) {
    const glm::u8vec4 c = fb.color()(int(u * size), size / 2);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 255 * expected[k], 0.5) << "u " << u << " channel " << k;
  };
  expect_color(0.5f, {0.5f, 0, 0.5f});
  expect_color(0.7f, {0.5f, 0, 0});
  expect_color(0.3f, {0, 0, 0.5f});
}

TEST(NotesShaders, TextureShadersNeedTextureCoordinates) {
  VertexArrays quad = screen_quad();
  quad.uvs.clear();
  const Texture2D texture = disc_texture(4, 0.25, Vec4f(1), Vec4f(0));
  Framebuffer fb(4, 4);
  EXPECT_THROW(draw_textured(fb, RasterState{}, quad, Mat4(1.0), texture), InvalidInput);
  EXPECT_THROW(draw_two_textured(fb, RasterState{}, quad, Mat4(1.0), texture), InvalidInput);
  EXPECT_THROW(disc_texture(0, 0.25, Vec4f(1), Vec4f(0)), InvalidInput);
}

}  // namespace
}  // namespace tessera::raster3d
