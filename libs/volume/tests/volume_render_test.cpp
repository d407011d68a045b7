#include "tessera/volume/volume_render.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/parallel.hpp"
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
  float sum = 0;
  for (const auto& p : one.pixels()) sum += p.x;
  EXPECT_GT(sum, 1.0f);
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

}  // namespace
}  // namespace tessera
