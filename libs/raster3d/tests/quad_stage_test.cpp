// The quad fragment stage against draw_triangles: the same coverage, depth and interpolated varyings pixel for pixel
// (the stage evaluates them in the same operations), the lane layout of FragmentBatch, quad derivatives, discard.
#include "tessera/raster3d/quad_stage.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d {
namespace {

// Random overlapping triangles in clip space (some crossing the near and side planes), 3 varyings per vertex.
struct Soup {
  std::vector<float> vertices;  // x y z w r g b
  std::vector<uint32_t> indices;
};

Soup random_soup(int triangles, uint64_t seed) {
  Rng rng(seed);
  Soup s;
  for (int t = 0; t < 3 * triangles; ++t) {
    const float w = 0.5f + 2.0f * rng.uniform();
    s.vertices.insert(s.vertices.end(),
                      {(2.4f * rng.uniform() - 1.2f) * w, (2.4f * rng.uniform() - 1.2f) * w,
                       (2.2f * rng.uniform() - 1.1f) * w, w, rng.uniform(), rng.uniform(), rng.uniform()});
    s.indices.push_back(uint32_t(t));
  }
  return s;
}

struct Rgb {
  float r, g, b;
};

// The varyings as color, through draw_triangles with C++ functors.
void draw_functor(Framebuffer& fb, const RasterState& state, const Soup& s) {
  const auto vs = [&](uint32_t i) {
    const float* v = s.vertices.data() + 7 * size_t(i);
    return VertexOut<Rgb>{Vec4f(v[0], v[1], v[2], v[3]), Rgb{v[4], v[5], v[6]}};
  };
  const auto fs = [](const Rgb& in, Vec3f& color) {
    color = Vec3f(in.r, in.g, in.b);
    return true;
  };
  draw_triangles(fb, state, uint32_t(s.vertices.size() / 7), s.indices, vs, fs);
}

// The same on the quad stage; discards lanes whose red is above `discard_above`.
class ColorShader : public QuadFragmentShader {
 public:
  explicit ColorShader(float discard_above = 2.0f) : discard_above_(discard_above) {}
  std::unique_ptr<QuadShaderScratch> begin() const override { return std::make_unique<QuadShaderScratch>(); }
  void shade(FragmentBatch& b, QuadShaderScratch&) const override {
    for (int l = 0; l < 4 * b.quads; ++l) {
      for (int c = 0; c < 3; ++c) b.color[c][l] = b.varyings[c][l];
      b.color[3][l] = 1.0f;
      if (b.varyings[0][l] > discard_above_) b.kept[l] = 0;
    }
  }

 private:
  float discard_above_;
};

void expect_same(const Framebuffer& a, const Framebuffer& b) {
  int color_diffs = 0, depth_diffs = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      color_diffs += a.color()(x, y) != b.color()(x, y);
      depth_diffs += a.depth()(x, y) != b.depth()(x, y);
    }
  EXPECT_EQ(color_diffs, 0);
  EXPECT_EQ(depth_diffs, 0);
}

TEST(QuadStage, SamePixelsAsDrawTrianglesForAnyThreadCount) {
  const Soup s = random_soup(300, 7);
  for (const bool depth_test : {true, false})
    for (const int threads : {1, 2}) {
      ThreadLimit limit(threads);
      RasterState state;
      state.depth_test = depth_test;
      Framebuffer a(173, 131), b(173, 131);  // odd sizes: partial tiles and quads
      a.clear_color(Vec3f(0.1f)), b.clear_color(Vec3f(0.1f));
      draw_functor(a, state, s);
      const DrawStats stats = draw_triangles_quads(b, state, s.vertices, 3, s.indices, ColorShader());
      EXPECT_EQ(stats.primitives, 300u);
      expect_same(a, b);
    }
}

TEST(QuadStage, ViewportAtOddOffsetAndFlatShading) {
  const Soup s = random_soup(100, 11);
  RasterState state;
  state.viewport = {13, 7, 101, 77};
  state.flat = true;
  Framebuffer a(128, 96), b(128, 96);
  draw_functor(a, state, s);
  draw_triangles_quads(b, state, s.vertices, 3, s.indices, ColorShader());
  expect_same(a, b);
}

TEST(QuadStage, DiscardedLanesWriteNothing) {
  const Soup s = random_soup(200, 3);
  RasterState state;
  Framebuffer a(96, 96), b(96, 96);
  const auto vs = [&](uint32_t i) {
    const float* v = s.vertices.data() + 7 * size_t(i);
    return VertexOut<Rgb>{Vec4f(v[0], v[1], v[2], v[3]), Rgb{v[4], v[5], v[6]}};
  };
  const auto fs = [](const Rgb& in, Vec3f& color) {
    color = Vec3f(in.r, in.g, in.b);
    return !(in.r > 0.5f);
  };
  draw_triangles(a, state, uint32_t(s.vertices.size() / 7), s.indices, vs, fs);
  draw_triangles_quads(b, state, s.vertices, 3, s.indices, ColorShader(0.5f));
  expect_same(a, b);
}

// Records what the shader saw: each covered lane's window position, and the quad differences of a varying.
class ProbeShader : public QuadFragmentShader {
 public:
  mutable std::vector<float> dx, dy;
  mutable int lanes_out_of_layout = 0;
  std::unique_ptr<QuadShaderScratch> begin() const override { return std::make_unique<QuadShaderScratch>(); }
  void shade(FragmentBatch& b, QuadShaderScratch&) const override {
    for (int q = 0; q < b.quads; ++q) {
      const int l = 4 * q;
      // Lane layout: 1 is right of 0, 2 above 0, 3 above 1.
      const float x = b.frag_coord[0][l], y = b.frag_coord[1][l];
      lanes_out_of_layout += b.frag_coord[0][l + 1] != x + 1 || b.frag_coord[1][l + 1] != y ||
                             b.frag_coord[0][l + 2] != x || b.frag_coord[1][l + 2] != y + 1 ||
                             b.frag_coord[0][l + 3] != x + 1 || b.frag_coord[1][l + 3] != y + 1;
      lanes_out_of_layout += int(x - 0.5f) % 2 != 0 || int(y - 0.5f) % 2 != 0;
      dx.push_back(b.varyings[0][l + 1] - b.varyings[0][l]);
      dy.push_back(b.varyings[0][l + 2] - b.varyings[0][l]);
      for (int k = 0; k < 4; ++k) b.color[0][l + k] = b.color[1][l + k] = b.color[2][l + k] = b.color[3][l + k] = 1;
    }
  }
};

TEST(QuadStage, LaneLayoutAndQuadDerivatives) {
  // A screen-filling quad (w = 1) whose varying is 3 x + 5 y in window pixels: dFdx = 3, dFdy = 5 at every quad,
  // helper lanes included (the plane extended beyond the triangle).
  const int size = 64;
  const auto v = [&](float x, float y) {
    const float wx = (x + 1) * 0.5f * size, wy = (y + 1) * 0.5f * size;
    return std::vector<float>{x, y, 0, 1, 3 * wx + 5 * wy};
  };
  std::vector<float> vertices;
  for (const auto& p : {v(-1, -1), v(1, -1), v(1, 1), v(-1, 1)}) vertices.insert(vertices.end(), p.begin(), p.end());
  Framebuffer fb(size, size);
  ProbeShader probe;
  draw_triangles_quads(fb, RasterState{}, vertices, 1, std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, probe);
  EXPECT_EQ(probe.lanes_out_of_layout, 0);
  ASSERT_FALSE(probe.dx.empty());
  for (size_t q = 0; q < probe.dx.size(); ++q) {
    EXPECT_NEAR(probe.dx[q], 3.0f, 1e-3f);
    EXPECT_NEAR(probe.dy[q], 5.0f, 1e-3f);
  }
  // Every pixel written once by exactly one of the two triangles: all white.
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) EXPECT_EQ(fb.color()(x, y), glm::u8vec4(255)) << x << "," << y;
}

TEST(QuadStage, RefusesWhatItCannotDraw) {
  Framebuffer fb(8, 8);
  const std::vector<float> vertices(15, 0.0f);
  const std::vector<uint32_t> triangle = {0, 1, 2};
  ColorShader shader;
  Framebuffer depth_only = Framebuffer::depth_only(8, 8);
  EXPECT_THROW(draw_triangles_quads(fb, {}, vertices, 2, triangle, shader), InvalidInput);  // 15 % 6 != 0
  EXPECT_THROW(draw_triangles_quads(fb, {}, vertices, 40, triangle, shader), InvalidInput);
  EXPECT_THROW(draw_triangles_quads(depth_only, RasterState{.stencil_test = true}, std::vector<float>(12, 0.0f), 0,
                                    triangle, shader),
               InvalidInput);  // no stencil buffer
}

TEST(QuadStage, StencilAsDrawTriangles) {
  // Overlapping triangles of both orientations count into the stencil buffer (wrapping, front and back apart, on
  // depth pass and fail: shadow volumes' operations), then a second pass draws where the count is not 0. Color, depth
  // and stencil as draw_triangles'.
  const Soup s = random_soup(250, 19);
  RasterState count;
  count.stencil_test = true;
  count.depth_write = false;
  count.stencil_front = {DepthFunc::always, 0, 0xff, 0xff, StencilOp::keep, StencilOp::decr_wrap, StencilOp::incr_wrap};
  count.stencil_back = {DepthFunc::always, 0, 0xff, 0xff, StencilOp::invert, StencilOp::incr, StencilOp::decr_wrap};
  RasterState show;
  show.stencil_test = true;
  show.depth_func = DepthFunc::lequal;
  show.stencil_front = show.stencil_back = {DepthFunc::notequal, 0, 0xff, 0xff};
  for (const int threads : {1, 2}) {
    ThreadLimit limit(threads);
    Framebuffer a(150, 110), b(150, 110);
    for (Framebuffer* fb : {&a, &b}) fb->clear_color(Vec3f(0.2f));
    const Soup first = random_soup(60, 23);
    draw_functor(a, RasterState{}, first);
    draw_triangles_quads(b, RasterState{}, first.vertices, 3, first.indices, ColorShader());
    draw_functor(a, count, s);
    draw_triangles_quads(b, count, s.vertices, 3, s.indices, ColorShader());
    draw_functor(a, show, s);
    draw_triangles_quads(b, show, s.vertices, 3, s.indices, ColorShader());
    expect_same(a, b);
    int stencil_diffs = 0, nonzero = 0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x) {
        stencil_diffs += a.stencil()(x, y) != b.stencil()(x, y);
        nonzero += a.stencil()(x, y) != 0;
      }
    EXPECT_EQ(stencil_diffs, 0);
    EXPECT_GT(nonzero, a.width() * a.height() / 4);  // the test exercised the operations
  }
}

}  // namespace
}  // namespace tessera::raster3d
