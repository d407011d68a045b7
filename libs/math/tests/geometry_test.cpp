#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "tessera/math/frame.hpp"
#include "tessera/math/power_of_two.hpp"
#include "tessera/math/ray.hpp"

namespace tessera {
namespace {

TEST(AABB, EmptyExpandArea) {
  AABB b;
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(b.area(), 0.0f);
  b.expand(Vec3f(0, 0, 0));
  b.expand(Vec3f(1, 2, 3));
  EXPECT_FALSE(b.empty());
  EXPECT_FLOAT_EQ(b.area(), 2 * (2 + 6 + 3));
  EXPECT_EQ(b.longest_axis(), 2);
  EXPECT_TRUE(b.contains(Vec3f(0.5f, 1, 1)));
}

TEST(AABB, SlabTestAgreesWithSampling) {
  std::mt19937 gen(1);
  std::uniform_real_distribution<float> u(-2, 2);
  AABB box;
  box.expand(Vec3f(-0.5f, -0.3f, -0.7f));
  box.expand(Vec3f(0.6f, 0.4f, 0.2f));
  for (int i = 0; i < 2000; ++i) {
    Ray r;
    r.origin = {u(gen), u(gen), u(gen)};
    r.dir = glm::normalize(Vec3f(u(gen), u(gen), u(gen)));
    r.tmax = 10;
    float t0, t1;
    const bool hit = intersect_slabs(box, r, 1.0f / r.dir, t0, t1);
    // Oracle: march along the ray.
    bool inside = false;
    for (int k = 0; k <= 4000 && !inside; ++k) inside = box.contains(r.at(10.0f * k / 4000));
    if (inside) {
      EXPECT_TRUE(hit) << i;
    }
    if (hit) {
      EXPECT_TRUE(box.contains(r.at(0.5f * (t0 + t1)))) << i;
    }
  }
}

TEST(Frame, IsOrthonormal) {
  std::mt19937 gen(2);
  std::normal_distribution<float> g;
  for (int i = 0; i < 1000; ++i) {
    const Vec3f n = glm::normalize(Vec3f(g(gen), g(gen), g(gen)));
    const Frame f = Frame::from_normal(n);
    EXPECT_NEAR(glm::dot(f.s, f.t), 0, 1e-5);
    EXPECT_NEAR(glm::dot(f.s, f.n), 0, 1e-5);
    EXPECT_NEAR(glm::length(f.s), 1, 1e-5);
    EXPECT_NEAR(glm::length(f.t), 1, 1e-5);
    EXPECT_NEAR(glm::dot(glm::cross(f.s, f.t), f.n), 1, 1e-5);
    const Vec3f v(0.3f, -0.2f, 0.9f);
    EXPECT_LT(glm::length(f.to_world(f.to_local(v)) - v), 1e-5f);
  }
}

}  // namespace
}  // namespace tessera

// Scaling by powers of two (power_of_two.hpp): only magnitudes outside [2^-128, 2^128] are rescaled, into [0.5, 1).
TEST(PowerOfTwo, RescalesOnlyMagnitudesFarFromOne) {
  EXPECT_EQ(tessera::rescale_exponent(1e300), 997);  // 1e300 = 0.7466... x 2^997
  EXPECT_EQ(tessera::rescale_exponent(1e-300), -996);
  EXPECT_EQ(tessera::rescale_exponent(std::ldexp(1.0, 128)), 129);
  EXPECT_EQ(tessera::rescale_exponent(std::ldexp(1.0, 127)), 0);
  EXPECT_EQ(tessera::rescale_exponent(0.0), 0);
  EXPECT_EQ(tessera::rescale_exponent(std::numeric_limits<double>::infinity()), 0);
  const std::vector<tessera::Vec3> points{{1, -3e300, 2}, {std::numeric_limits<double>::infinity(), 0, 1e299}};
  EXPECT_EQ(tessera::largest_coordinate(points), 3e300);  // non-finite coordinates are left out
  std::vector<tessera::Vec3> scaled = points;
  tessera::scale_by_power_of_two(scaled, -tessera::rescale_exponent(points));
  EXPECT_GE(std::fabs(scaled[0].y), 0.5);
  EXPECT_LT(std::fabs(scaled[0].y), 1.0);
  EXPECT_EQ(tessera::ldexp(scaled[0], tessera::rescale_exponent(points)), points[0]);  // exact both ways
}
