#include "tessera/volume/volume_render.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/parallel.hpp"
#include "tessera/image/metrics.hpp"
#include "tessera/volume/procedural.hpp"

namespace tessera {
namespace {

VolumeRenderOptions looking_down_z(int size) {
  VolumeRenderOptions o;
  o.camera.eye = {5, 5, 40};
  o.camera.center = {5, 5, 0};
  o.camera.fovy = radians(10);
  o.width = o.height = size;
  o.shading = false;
  return o;
}

TEST(VolumeRender, ConstantSlabMatchesBeerLambert) {
  // A 11 x 11 x 11 box of constant value: the central ray crosses 10 units. With opacity a per unit length the
  // compositing result is c (1 - (1 - a)^10) + background (1 - a)^10, for any step.
  Volume<float> v(glm::ivec3(11), 1.0f);
  auto o = looking_down_z(33);
  o.transfer = TransferFunction({{0, {1, 0.5f, 0.25f}, 0.1f}, {2, {1, 0.5f, 0.25f}, 0.1f}});
  o.background = {0, 0, 1};
  o.termination = 1.0f;
  for (float step : {0.5f, 0.3f, 1.0f}) {
    o.step = step;
    const ImageRGB img = render_volume(v, o);
    const float transmittance = std::pow(0.9f, 10.0f);
    const Vec3f center = img(16, 16);
    EXPECT_NEAR(center.x, 1 - transmittance, 1e-3) << step;
    EXPECT_NEAR(center.y, 0.5f * (1 - transmittance), 1e-3) << step;
    EXPECT_NEAR(center.z, 0.25f * (1 - transmittance) + transmittance, 2e-3) << step;
  }
}

TEST(VolumeRender, MaximumIntensityProjectionOfAKnownField) {
  // value = x + y + z: along a ray down -z the maximum is at the front face, z = 10, so the gray is (x+y+10)/30.
  Volume<float> v(glm::ivec3(11));
  for (int z = 0; z < 11; ++z)
    for (int y = 0; y < 11; ++y)
      for (int x = 0; x < 11; ++x) v(x, y, z) = float(x + y + z);
  auto o = looking_down_z(33);
  o.mip = true;
  o.step = 0.25f;
  const ImageRGB img = render_volume(v, o);
  EXPECT_NEAR(img(16, 16).x, 20.0f / 30.0f, 0.01f);
}

TEST(VolumeRender, SameImageForOneAndTwoThreadsAndWithoutSkipping) {
  const auto v = make_metaballs(32);
  VolumeRenderOptions o;
  o.camera.eye = {0.5, 0.8, 3.5};
  o.width = o.height = 48;
  o.transfer = TransferFunction({{0.8f, {1, 0.6f, 0.3f}, 0}, {1.2f, {1, 0.9f, 0.7f}, 0.9f}});
  ImageRGB one, two;
  {
    ThreadLimit limit(1);
    one = render_volume(v, o);
  }
  {
    ThreadLimit limit(2);
    two = render_volume(v, o);
  }
  o.skip_empty = false;
  const ImageRGB plain = render_volume(v, o);
  ASSERT_EQ(one.pixels().size(), two.pixels().size());
  EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), two.pixels().begin()));
  EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), plain.pixels().begin()));
  // The same for the scalar path (the 8-ray path's jumps over empty blocks are checked above where it runs).
  o.simd = false;
  const ImageRGB scalar_plain = render_volume(v, o);
  o.skip_empty = true;
  const ImageRGB scalar_skipping = render_volume(v, o);
  EXPECT_TRUE(std::equal(scalar_plain.pixels().begin(), scalar_plain.pixels().end(), scalar_skipping.pixels().begin()));
  float sum = 0;
  for (const auto& p : one.pixels()) sum += p.x;
  EXPECT_GT(sum, 1.0f);
}

// The renderer quantizes values and gradients to 16 bits, tabulates the transfer function and the specular power
// and marches 8 rays at a time; this is the notes' algorithm evaluated directly per sample (trilinear value, the
// central-difference gradients of the 8 cell corners interpolated trilinearly, the transfer function with a pow per
// sample), to check that the shortcuts leave the picture essentially unchanged.
ImageRGB direct_render(const Volume<float>& v, const VolumeRenderOptions& o) {
  Camera camera = o.camera;
  camera.aspect = double(o.width) / double(o.height);
  const EyeRays rays(camera, o.width, o.height);
  const float step = o.step > 0 ? o.step : 0.5f * float(v.spacing().x);
  AABB box;
  box.expand(Vec3f(v.origin()));
  box.expand(Vec3f(v.to_world(Vec3(v.dims() - 1))));
  const auto gradient_at = [&](const Vec3f& p) {
    const glm::ivec3 c = glm::min(glm::ivec3(p), v.dims() - 2);
    const Vec3f f = p - Vec3f(c);
    Vec3f g(0.0f);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::ivec3 d(corner & 1, (corner >> 1) & 1, corner >> 2);
      const float w = (d.x ? f.x : 1 - f.x) * (d.y ? f.y : 1 - f.y) * (d.z ? f.z : 1 - f.z);
      g += w * v.gradient(c.x + d.x, c.y + d.y, c.z + d.z);
    }
    return g;
  };
  ImageRGB image(o.width, o.height, o.background);
  for (int j = 0; j < o.height; ++j)
    for (int i = 0; i < o.width; ++i) {
      const Ray ray = rays.ray(i, j);
      float t0 = 0, t1 = 0;
      if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) continue;
      Vec3f color(0.0f);
      float alpha = 0;
      for (float a = t0; a < t1 && alpha < o.termination; a += step) {
        const float b = std::min(t1, a + step);
        const Vec3f p = Vec3f(v.to_voxel(Vec3(ray.at(0.5f * (a + b)))));
        const Vec4f c = o.transfer(v.sample(p));
        const float sample_alpha = 1 - std::pow(1 - c.w, b - a);
        const Vec3f g = gradient_at(glm::clamp(p, Vec3f(0.0f), Vec3f(v.dims() - 1)));
        const float cosine = glm::length(g) > 1e-6f ? std::abs(glm::dot(glm::normalize(g), -ray.dir)) : -1.0f;
        const Vec3f rgb = cosine < 0 ? Vec3f(c)
                                     : Vec3f(c) * (o.ambient + o.diffuse * cosine) +
                                           Vec3f(o.specular * std::pow(cosine, o.shininess));
        color += (1 - alpha) * sample_alpha * rgb;
        alpha += (1 - alpha) * sample_alpha;
      }
      image(i, j) = color + (1 - alpha) * o.background;
    }
  return image;
}

VolumeRenderOptions metaball_view() {
  VolumeRenderOptions o;
  o.camera.eye = {0.5, 0.8, 3.5};
  o.width = o.height = 64;
  o.transfer = TransferFunction({{0.6f, {1, 0.6f, 0.3f}, 0}, {1.0f, {1, 0.8f, 0.5f}, 0.6f}, {1.4f, {1, 0.95f, 0.8f}, 1.0f}});
  return o;
}

TEST(VolumeRender, MatchesTheDirectPerSampleEvaluation) {
  const auto v = make_metaballs(40);
  const auto o = metaball_view();
  const ImageRGB fast = render_volume(v, o), direct = direct_render(v, o);
  double sum = 0;
  for (const auto& p : direct.pixels()) sum += p.x;
  ASSERT_GT(sum, 50.0);  // the picture is not empty
  EXPECT_GT(psnr(fast, direct), 50.0);  // 57.7 dB measured
  EXPECT_LT(rmse(fast, direct), 0.003);
}

TEST(VolumeRender, SimdAndScalarPathsAgreeAndAPreparedVolumeRendersTheSame) {
  const auto v = make_metaballs(40);
  auto o = metaball_view();
  const ImageRGB simd = render_volume(v, o);
  o.simd = false;
  const ImageRGB scalar = render_volume(v, o);
  // Up to rounding: FMA and rsqrt in the 8-ray path (where the CPU has AVX2; else both are the scalar path).
  EXPECT_LT(max_abs_difference(simd, scalar), 1e-5);
  const VolumeRenderer renderer(v);
  const ImageRGB again = renderer.render(o), twice = renderer.render(o);
  EXPECT_TRUE(std::equal(scalar.pixels().begin(), scalar.pixels().end(), again.pixels().begin()));
  EXPECT_TRUE(std::equal(again.pixels().begin(), again.pixels().end(), twice.pixels().begin()));
}

TEST(VolumeRender, ThinAndTinyVolumesRenderOnBothPaths) {
  // Axes of one or two voxels: cells clamp to the grid, corner offsets along a single-voxel axis are 0.
  for (const glm::ivec3 dims : {glm::ivec3(16, 16, 1), glm::ivec3(1, 9, 9), glm::ivec3(2, 2, 2), glm::ivec3(1, 1, 1)}) {
    Volume<float> v(dims, 0.0f, Vec3(0.1), Vec3(-0.5));
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) v(x, y, z) = float((x * 7 + y * 3 + z * 5) % 11) / 10.0f;
    auto o = metaball_view();
    o.transfer = TransferFunction({{0.0f, {1, 1, 1}, 0.0f}, {1.0f, {1, 0.5f, 0.2f}, 0.9f}});
    for (const bool simd : {true, false}) {
      o.simd = simd;
      const ImageRGB img = render_volume(v, o);
      for (const auto& p : img.pixels()) ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    }
  }
}

TEST(TransferFunction, InterpolatesAndParses) {
  const auto tf = TransferFunction::from_csv("# v,r,g,b,a\n0,0,0,0,0\n10,1,1,1,1\n", "t.csv");
  EXPECT_FLOAT_EQ(tf(5).w, 0.5f);
  EXPECT_FLOAT_EQ(tf(20).x, 1.0f);
  EXPECT_FLOAT_EQ(tf.max_opacity(-5, 2), 0.2f);
  const auto j = TransferFunction::from_json(R"({"points": [[0, 1, 0, 0, 0.5]]})", "t.json");
  EXPECT_FLOAT_EQ(j(3).w, 0.5f);
  EXPECT_THROW(TransferFunction::from_csv("1,2\n", "bad.csv"), InvalidInput);
  EXPECT_THROW(TransferFunction::from_json("{", "bad.json"), InvalidInput);
  EXPECT_THROW(TransferFunction::preset("pet"), InvalidInput);
  EXPECT_NO_THROW(TransferFunction::preset("ct-bone"));
}

// Found by fuzz/transfer_fuzz.cpp: a number beyond float's range was converted anyway (undefined behaviour; an infinite
// color in practice), and points near both ends of float's range made the interpolation NaN.
TEST(TransferFunction, RefusesNumbersBeyondFloatAndInterpolatesExtremePoints) {
  const auto message = [](const auto& load) {
    try {
      load();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message([] { TransferFunction::from_csv("0,0,0,0,0\n1, 2.6e116, 0, 0, 0.5\n", "t.csv"); }),
            "t.csv:2: 2.6e+116 does not fit a float");
  EXPECT_EQ(message([] { TransferFunction::from_json(R"({"points": [[1e300, 0, 0, 0, 0]]})", "t.json"); }),
            "t.json: 1e+300 does not fit a float");
  EXPECT_EQ(message([] { TransferFunction({{0, {0, -1, 0}, 0}}); }), "color component -1 is outside [0, 1000000]");
  EXPECT_EQ(message([] { TransferFunction({{0, {2e6f, 0, 0}, 0}}); }),
            "color component 2000000 is outside [0, 1000000]");
  EXPECT_EQ(message([] { TransferFunction({{INFINITY, {0, 0, 0}, 0}}); }), "point value inf is not finite");
  const auto tf = TransferFunction::from_json(R"({"points": [[-3e38, 0, 0, 0, 0], [3e38, 1, 1, 1, 1]]})", "t.json");
  EXPECT_FLOAT_EQ(tf(0).w, 0.5f);
  EXPECT_FLOAT_EQ(tf(0).x, 0.5f);
}

}  // namespace
}  // namespace tessera
