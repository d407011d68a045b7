#include "tessera/volume/volume.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/volume/procedural.hpp"

namespace tessera {
namespace {

TEST(Volume, TrilinearSampleReproducesLinearFields) {
  Volume<int16_t> v(glm::ivec3(4, 5, 6));
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 4; ++x) v(x, y, z) = int16_t(2 * x - 3 * y + 5 * z);
  EXPECT_FLOAT_EQ(v.sample({1.25f, 2.5f, 3.75f}), 2 * 1.25f - 3 * 2.5f + 5 * 3.75f);
  EXPECT_FLOAT_EQ(v.sample({3.0f, 4.0f, 5.0f}), 2 * 3 - 3 * 4 + 5 * 5);
  EXPECT_FLOAT_EQ(v.sample({-1.0f, 0.0f, 0.0f}), 0.0f);  // clamped
  v.set_spacing({0.5, 1, 2});
  const Vec3 g = v.gradient(2, 2, 2), border = v.gradient(0, 0, 0);
  EXPECT_FLOAT_EQ(g.x, 4.0f);
  EXPECT_FLOAT_EQ(g.y, -3.0f);
  EXPECT_FLOAT_EQ(g.z, 2.5f);
  EXPECT_FLOAT_EQ(border.x, 4.0f);  // one-sided on the border
}

TEST(Volume, RangeHistogramAndSlices) {
  Volume<uint8_t> v(glm::ivec3(3, 2, 2), 10);
  v(2, 1, 0) = 250;
  v(0, 1, 1) = 0;
  const auto [lo, hi] = value_range(v);
  EXPECT_EQ(lo, 0);
  EXPECT_EQ(hi, 250);
  const auto h = histogram(v, 4, 0, 256);
  EXPECT_EQ(h, (std::vector<uint64_t>{11, 0, 0, 1}));
  const DepthImage z = slice(v, Axis::z, 0), x = slice(v, Axis::x, 2), y = slice(v, Axis::y, 1);
  EXPECT_EQ(z.width(), 3);
  EXPECT_EQ(z(2, 1), 250);
  EXPECT_EQ(x.width(), 2);
  EXPECT_EQ(x(1, 0), 250);
  EXPECT_EQ(y(0, 1), 0);
  EXPECT_THROW(slice(v, Axis::z, 2), InvalidInput);
  EXPECT_THROW(parse_axis("w"), InvalidInput);
}

TEST(Volume, FloatRangeMatchesMinmaxElementForAnySizeAndThreadCount) {
  // Sizes around the blocks and lanes of the parallel float path; extremes placed in the scalar tail, in a lane,
  // in a later block; infinities; and NaNs, where minmax_element's own answer must come back.
  for (const int nx : {1, 7, 16, 17, 67}) {
    Volume<float> v(glm::ivec3(nx, 50, 41));
    const size_t n = v.voxel_count();
    Rng rng{static_cast<uint64_t>(nx)};
    for (auto& x : v.voxels()) x = float(rng.uniform() * 200 - 100);
    auto expect_same = [&] {
      const auto [lo, hi] = std::minmax_element(v.voxels().begin(), v.voxels().end());
      for (const int threads : {1, 2}) {
        ThreadLimit limit(threads);
        const auto [rlo, rhi] = value_range(v);
        EXPECT_TRUE(rlo == double(*lo) || (std::isnan(rlo) && std::isnan(*lo))) << nx << " " << rlo;
        EXPECT_TRUE(rhi == double(*hi) || (std::isnan(rhi) && std::isnan(*hi))) << nx << " " << rhi;
      }
    };
    expect_same();
    v.voxels()[n - 1] = -500;
    v.voxels()[n / 2 + 5] = 700;
    expect_same();
    v.voxels()[70000 % n] = INFINITY;
    expect_same();
    v.voxels()[n / 3] = NAN;
    expect_same();
    v.voxels()[0] = NAN;
    expect_same();
  }
}

TEST(Volume, ProceduralFieldsAreInsideAtTheirCenters) {
  EXPECT_GT(make_sphere(17)(8, 8, 8), 0.0f);
  EXPECT_LT(make_torus(17)(8, 8, 8), 0.0f);
  EXPECT_GT(make_metaballs(17)(4, 6, 8), 1.0f);
  const auto a = make_noise(9, 4), b = make_noise(9, 4), c = make_noise(9, 5);
  EXPECT_TRUE(std::equal(a.voxels().begin(), a.voxels().end(), b.voxels().begin()));
  EXPECT_FALSE(std::equal(a.voxels().begin(), a.voxels().end(), c.voxels().begin()));
  Volume<float> g;
  EXPECT_TRUE(make_procedural("gyroid:10", g));
  EXPECT_EQ(g.dims(), glm::ivec3(10));
  EXPECT_FALSE(make_procedural("cube:10", g));
}

}  // namespace
}  // namespace tessera
