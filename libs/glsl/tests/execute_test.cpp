// Running programs: each result checked against the same expression evaluated in C++ at the pixel center, or an
// analytic value (derivatives, texels, control flow).
#include "execute.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "glsl_math.hpp"
#include "glsl_test_util.hpp"
#include "tessera/core/cpu.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/math/transform.hpp"

namespace tessera::glsl {
namespace {

using testing::compile;
using testing::full_screen;
using testing::pixel;

constexpr float kTolerance = 1.0f / 255.0f;  // one 8-bit step: the stored color is rounded

// uv at the center of GL pixel (i, j) of a size x size full_screen draw.
Vec2f uv_at(int i, int j, int size) { return Vec2f((float(i) + 0.5f) / float(size), (float(j) + 0.5f) / float(size)); }

template <class F>
void expect_pixels(const raster3d::Framebuffer& fb, F expected) {
  int bad = 0;
  for (int j = 0; j < fb.height(); ++j)
    for (int i = 0; i < fb.width(); ++i) {
      const Vec4f want = expected(i, j), got = pixel(fb, i, j);
      for (int c = 0; c < 4; ++c)
        if (std::abs(want[c] - got[c]) > kTolerance && bad++ < 5)
          ADD_FAILURE() << "pixel " << i << "," << j << " channel " << c << ": want " << want[c] << ", got " << got[c];
    }
  EXPECT_EQ(bad, 0);
}

TEST(GlslExecute, FragCoordAndVaryings) {
  Program p = compile("void main() { gl_FragColor = vec4(gl_FragCoord.xy / 32.0, gl_TexCoord[0].s, 1.0); }");
  expect_pixels(full_screen(p), [](int i, int j) {
    return Vec4f((float(i) + 0.5f) / 32, (float(j) + 0.5f) / 32, uv_at(i, j, 32).x, 1);
  });
}

TEST(GlslExecute, BuiltInFunctions) {
  Program p = compile(R"(
    void main() {
      vec2 uv = gl_TexCoord[0].st;
      float a = smoothstep(0.2, 0.8, uv.x);
      float b = pow(uv.y, 2.2) * 0.5 + 0.25 * clamp(sin(uv.x * 6.0), 0.0, 1.0);
      float c = fract(uv.x * 3.7) * step(0.5, uv.y) + mix(0.1, 0.3, uv.x) * (1.0 - step(0.5, uv.y));
      vec3 n = normalize(vec3(uv - 0.5, 1.0));
      float d = length(reflect(vec3(0.0, 0.0, -1.0), n).xy) + abs(dot(n, vec3(1.0, 0.0, 0.0))) * 0.0;
      gl_FragColor = vec4(a, b, c, clamp(d, 0.0, 1.0));
    })");
  expect_pixels(full_screen(p), [](int i, int j) {
    const Vec2f uv = uv_at(i, j, 32);
    const float t = std::clamp((uv.x - 0.2f) / 0.6f, 0.0f, 1.0f);
    const float a = t * t * (3 - 2 * t);
    const float b = std::pow(uv.y, 2.2f) * 0.5f + 0.25f * std::clamp(std::sin(uv.x * 6.0f), 0.0f, 1.0f);
    const float c = uv.y >= 0.5f ? uv.x * 3.7f - std::floor(uv.x * 3.7f) : 0.1f + 0.2f * uv.x;
    const Vec3f n = glm::normalize(Vec3f(uv - 0.5f, 1.0f));
    const float d = glm::length(Vec2f(glm::reflect(Vec3f(0, 0, -1), n)));
    return Vec4f(a, b, c, std::clamp(d, 0.0f, 1.0f));
  });
}

TEST(GlslExecute, LoopsBranchesFunctionsAndArrays) {
  Program p = compile(R"(
    uniform int count;
    uniform float weights[4];
    float shade(float x, out float twice) { twice = 2.0 * x; if (x > 0.5) return 1.0 - x; return x; }
    void main() {
      vec2 uv = gl_TexCoord[0].st;
      float sum = 0.0;
      for (int k = 0; k < 4; ++k) {
        if (k >= count) break;
        if (uv.x < 0.25 && k == 1) continue;
        sum += weights[k];
      }
      int steps = 0;
      float x = uv.y;
      while (x < 1.0) { x += 0.25; steps++; }
      float twice;
      float s = shade(uv.x, twice);
      int index = int(uv.x * 4.0);
      gl_FragColor = vec4(sum, float(steps) / 4.0, s + 0.0 * twice, weights[index]);
    })");
  const float weights[4] = {0.1f, 0.2f, 0.3f, 0.4f};
  p.set_uniform("weights", weights);
  p.set_uniform_text("count", "3");
  expect_pixels(full_screen(p), [&](int i, int j) {
    const Vec2f uv = uv_at(i, j, 32);
    float sum = 0;
    for (int k = 0; k < 3; ++k)
      if (!(uv.x < 0.25f && k == 1)) sum += weights[k];
    int steps = 0;
    for (float x = uv.y; x < 1.0f; x += 0.25f) ++steps;
    const float s = uv.x > 0.5f ? 1 - uv.x : uv.x;
    return Vec4f(sum, float(steps) / 4, s, weights[int(uv.x * 4)]);
  });
}

TEST(GlslExecute, DiscardLeavesPixels) {
  Program p = compile(R"(
    void main() {
      if (mod(floor(gl_FragCoord.x / 4.0) + floor(gl_FragCoord.y / 4.0), 2.0) > 0.5) discard;
      gl_FragColor = vec4(1.0);
    })");
  EXPECT_TRUE(p.discards());
  // Discarded pixels keep the clear color, opaque black.
  expect_pixels(full_screen(p), [](int i, int j) { return ((i / 4 + j / 4) % 2) ? Vec4f(0, 0, 0, 1) : Vec4f(1); });
}

TEST(GlslExecute, QuadDerivatives) {
  // u = x / 32 and v = y / 32 across the screen: dFdx(u) = 1/32, dFdy(v) = 1/32, fwidth(u) = 1/32.
  Program p = compile(R"(
    void main() {
      vec2 uv = gl_TexCoord[0].st;
      gl_FragColor = vec4(dFdx(uv.s) * 8.0, dFdy(uv.t) * 16.0, fwidth(uv.s) * 4.0, 1.0 - abs(dFdy(uv.s)));
    })");
  expect_pixels(full_screen(p), [](int, int) { return Vec4f(8.0f / 32, 16.0f / 32, 4.0f / 32, 1); });
}

TEST(GlslExecute, TextureSamplingMagnified) {
  // A 4 x 4 texture with nearest filtering over 32 x 32 pixels: each texel covers 8 x 8 pixels.
  ImageRGBA8 image(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) image(x, y) = glm::u8vec4(x * 60, y * 60, 255 - x * 20, 255);
  Sampler sampler;
  sampler.filter = Filter::nearest;
  Program p = compile("uniform sampler2D tex; void main() { gl_FragColor = texture2D(tex, gl_TexCoord[0].st); }");
  p.bind_texture(0, std::make_shared<Texture2D>(image, sampler));
  const raster3d::Framebuffer fb = full_screen(p);
  // v = 0 is the image's bottom row (its last: images are stored top row first).
  expect_pixels(fb, [&](int i, int j) { return Vec4f(image(i / 8, 3 - j / 8)) / 255.0f; });
}

TEST(GlslExecute, UnboundSamplerReadsOpaqueBlack) {
  Program p = compile("uniform sampler2D tex; void main() { gl_FragColor = texture2D(tex, gl_TexCoord[0].st); }");
  expect_pixels(full_screen(p), [](int, int) { return Vec4f(0, 0, 0, 1); });
}

TEST(GlslExecute, FixedFunctionMatricesAndFtransform) {
  // A scaled model-view: ftransform() and gl_ModelViewProjectionMatrix * gl_Vertex both halve the quad.
  for (const char* position : {"ftransform()", "gl_ModelViewProjectionMatrix * gl_Vertex"}) {
    Program p = compile("void main() { gl_FragColor = vec4(1.0); }",
                        std::string("void main() { gl_Position = ") + position + "; }");
    FixedFunctionState state;
    state.model_view = Mat4f(scale(0.5, 0.5, 0.5));
    p.set_fixed_function(state);
    expect_pixels(full_screen(p), [](int i, int j) {
      const bool inside = i >= 8 && i < 24 && j >= 8 && j < 24;
      return inside ? Vec4f(1) : Vec4f(0, 0, 0, 1);
    });
  }
}

TEST(GlslExecute, SameResultForAnyThreadCount) {
  Program p = compile(R"(
    void main() {
      vec2 uv = gl_TexCoord[0].st;
      float v = 0.0;
      for (int k = 0; k < 8; ++k) v += sin(uv.x * float(k)) * cos(uv.y * float(k + 1));
      gl_FragColor = vec4(fract(v), fract(v * 3.0), uv.x, 1.0);
    })");
  raster3d::Framebuffer one(1, 1), two(1, 1);
  {
    ThreadLimit limit(1);
    one = full_screen(p, 200);
  }
  {
    ThreadLimit limit(2);
    two = full_screen(p, 200);
  }
  int differences = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) differences += one.color()(x, y) != two.color()(x, y);
  EXPECT_EQ(differences, 0);
}

TEST(GlslExecute, EndlessLoopIsAnError) {
  Program p = compile(R"(
    uniform float step_size;
    void main() {
      float x = 0.0;
      while (x < 1.0) x += step_size;
      gl_FragColor = vec4(x);
    })");
  const float zero[1] = {0.0f};
  p.set_uniform("step_size", zero);
  EXPECT_THROW(full_screen(p, 8), InvalidInput);
}

}  // namespace
}  // namespace tessera::glsl

namespace tessera::glsl {
namespace {

TEST(GlslExecute, InstructionSetsAgree) {
  // The vector executors against the baseline one on arithmetic, transcendentals, branches and a trilinear texture:
  // the same operations in the same order (no contraction), so the same pixels.
  if (simd_level() < SimdLevel::avx2) GTEST_SKIP() << "this CPU has no AVX2";
  Program p = compile(R"(
    uniform sampler2D tex;
    void main() {
      vec2 uv = gl_TexCoord[0].st;
      vec4 t = texture2D(tex, uv * 7.0 + vec2(0.3, 0.1));
      float s = pow(uv.x + 0.1, 3.3) + sin(uv.y * 9.0) * 0.2;
      if (uv.x > uv.y) s = sqrt(s * s + 0.01); else s = exp(-s);
      gl_FragColor = vec4(t.rg, fract(s), t.a);
    })");
  ImageRGBA8 image(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) image(x, y) = glm::u8vec4(x * 4, (x ^ y) * 4, y * 3, 255);
  p.bind_texture(0, std::make_shared<Texture2D>(image, Sampler{.filter = Filter::trilinear}));
  executor_isa_cap() = 0;
  const raster3d::Framebuffer base = full_screen(p, 96);
  // AVX2, and AVX-512 where the CPU has it, against the baseline.
  for (const int cap : {1, -1}) {
    executor_isa_cap() = cap;
    const raster3d::Framebuffer wide = full_screen(p, 96);
    int worst = 0;
    for (int y = 0; y < 96; ++y)
      for (int x = 0; x < 96; ++x)
        for (int c = 0; c < 4; ++c)
          worst = std::max(worst, std::abs(int(wide.color()(x, y)[c]) - int(base.color()(x, y)[c])));
    EXPECT_EQ(worst, 0) << "cap " << cap;
  }
  executor_isa_cap() = -1;
}

}  // namespace
}  // namespace tessera::glsl

namespace tessera::glsl {
namespace {

TEST(GlslExecute, FastPowAgreesWithTheLibrary) {
  // The executor's pow against std::pow in double, over the bases and exponents of lighting and beyond.
  double worst = 0;
  for (float x = 1e-3f; x < 20.0f; x *= 1.0137f)
    for (float y = -8.0f; y <= 128.0f; y += 0.37f) {
      ASSERT_TRUE(glsl_pow_covers(x, y));
      const double exact = std::pow(double(x), double(y));
      if (exact < 1e-30 || exact > 1e30) continue;
      worst = std::max(worst, std::abs(double(glsl_pow(x, y)) - exact) / exact);
    }
  EXPECT_LT(worst, 2e-5);
  EXPECT_FALSE(glsl_pow_covers(0.0f, 2.0f));
  EXPECT_FALSE(glsl_pow_covers(-1.0f, 2.0f));
  EXPECT_FALSE(glsl_pow_covers(1e-40f, 2.0f));  // subnormal
}

}  // namespace
}  // namespace tessera::glsl
