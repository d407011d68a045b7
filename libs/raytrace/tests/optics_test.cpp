// Snell's law and the notes' index table, total internal reflection, a glass slab, Schlick, the sample patterns and
// a chi-square test of the glossy lobe.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "tessera/core/rng.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raytrace/material.hpp"
#include "tessera/raytrace/sampling.hpp"
#include "tessera/raytrace/world.hpp"

namespace tessera {
namespace {

/// A unit direction going down (-y) at angle `theta` from the normal +y, tilted toward +x.
Vec3f incoming(double theta) { return {float(std::sin(theta)), float(-std::cos(theta)), 0.0f}; }

TEST(Optics, SnellForEveryIndexOfTheTable) {
  for (float n2 : {ior::kAir, ior::kWater, ior::kGlass, ior::kIce, ior::kDiamond}) {
    for (double deg : {0.0, 10.0, 30.0, 60.0, 85.0}) {
      const double t1 = radians(deg);
      const auto t = refract_dir(incoming(t1), {0, 1, 0}, 1.0f / n2);
      ASSERT_TRUE(t.has_value());
      // sin t1 / sin t2 = n2 / n1 with n1 = 1; the ray keeps going down and bends toward the normal.
      EXPECT_NEAR(t->x, std::sin(t1) / n2, 2e-6) << n2 << " " << deg;
      EXPECT_LT(t->y, 0.0f);
      EXPECT_NEAR(glm::length(*t), 1.0f, 1e-6);
    }
  }
}

TEST(Optics, TotalInternalReflectionAtTheCriticalAngle) {
  // Glass to vacuum: the critical angle is asin(1 / 1.5) = 41.81 degrees.
  const double tc = critical_angle(ior::kGlass, 1.0);
  EXPECT_NEAR(degrees(tc), 41.8103149, 1e-5);
  const float eta = ior::kGlass / 1.0f;
  const auto below = refract_dir(incoming(tc - 1e-3), {0, 1, 0}, eta);
  ASSERT_TRUE(below.has_value());
  EXPECT_NEAR(below->x, 1.5 * std::sin(tc - 1e-3), 2e-6);  // sin t2 = 1.5 sin t1: nearly grazing
  EXPECT_FALSE(refract_dir(incoming(tc + 1e-4), {0, 1, 0}, eta).has_value());
  EXPECT_FALSE(refract_dir(incoming(radians(60)), {0, 1, 0}, eta).has_value());
  EXPECT_FALSE(refract_dir(incoming(radians(89)), {0, 1, 0}, ior::kDiamond).has_value());
  EXPECT_EQ(schlick_fresnel(float(std::cos(tc + 1e-3)), ior::kGlass, 1.0f), 1.0f);
}

TEST(Optics, GlassSlabShiftsTheRayByTheFormula) {
  // A glass slab of thickness 1 (y in [0, 1]) in a World. A ray entering the top at angle t1 leaves the bottom
  // parallel to itself, shifted sideways by d = thickness sin(t1 - t2) / cos(t2) (sin t1 = 1.5 sin t2).
  World world;
  world.add_shape(Box{{-50, 0, -50}, {50, 1, 50}}, Mat4(1.0), 0);
  world.build();
  for (double deg : {15.0, 40.0, 70.0}) {
    const double t1 = radians(deg), t2 = std::asin(std::sin(t1) / 1.5);
    Ray ray;
    ray.dir = incoming(t1);
    ray.origin = Vec3f(0, 2, 0) - 3.0f * ray.dir;
    SurfaceHit top;
    ASSERT_TRUE(world.intersect(ray, top));
    const auto inside = refract_dir(ray.dir, top.hit.normal, 1.0f / ior::kGlass);
    ASSERT_TRUE(inside.has_value());
    Ray through;
    through.origin = top.hit.point;
    through.dir = *inside;
    through.tmin = 1e-4f;
    SurfaceHit bottom;
    ASSERT_TRUE(world.intersect(through, bottom));
    EXPECT_NEAR(bottom.hit.point.y, 0.0f, 1e-5);
    const auto out = refract_dir(through.dir, -bottom.hit.normal, ior::kGlass);  // the normal on the ray's side
    ASSERT_TRUE(out.has_value());
    EXPECT_NEAR(glm::length(*out - ray.dir), 0.0f, 1e-5) << deg;  // parallel to the entry ray
    // Lateral shift: distance between the exit line and the continued entry line.
    const Vec3f diff = bottom.hit.point - top.hit.point;
    const float shift = glm::length(diff - glm::dot(diff, ray.dir) * ray.dir);
    EXPECT_NEAR(shift, std::sin(t1 - t2) / std::cos(t2), 1e-5) << deg;
  }
}

TEST(Optics, SchlickLimits) {
  const float r0 = (0.5f / 2.5f) * (0.5f / 2.5f);  // ((1 - 1.5) / (1 + 1.5))^2 = 0.04
  EXPECT_NEAR(schlick_fresnel(1.0f, 1.0f, ior::kGlass), r0, 1e-7);
  EXPECT_NEAR(schlick_fresnel(0.0f, 1.0f, ior::kGlass), 1.0f, 1e-7);
  EXPECT_NEAR(schlick_fresnel(1.0f, ior::kGlass, 1.0f), r0, 1e-6);  // symmetric at normal incidence
}

TEST(Sampling, StratifiedInCellsAndStrata) {
  for (uint32_t n : {1u, 4u, 16u, 12u, 64u}) {
    for (uint32_t pattern : {1u, 77u, 123456u}) {
      const auto m = uint32_t(std::ceil(std::sqrt(double(n))));
      const uint32_t rows = (n + m - 1) / m;
      std::set<uint32_t> cells, xs, ys;
      for (uint32_t s = 0; s < n; ++s) {
        const Vec2f u = stratified_sample(s, n, pattern);
        ASSERT_TRUE(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1);
        cells.insert(uint32_t(u.x * float(m)) + m * uint32_t(u.y * float(rows)));
        xs.insert(uint32_t(u.x * float(n)));
        ys.insert(uint32_t(u.y * float(n)));
      }
      EXPECT_EQ(cells.size(), n) << n;  // one sample per grid cell
      EXPECT_EQ(xs.size(), n) << n;     // one per 1/n stratum along x
      EXPECT_EQ(ys.size(), n) << n;
    }
  }
}

TEST(Sampling, PermutationIsABijection) {
  for (uint32_t n : {1u, 5u, 64u, 1000u}) {
    std::set<uint32_t> seen;
    for (uint32_t i = 0; i < n; ++i) seen.insert(permute_index(i, n, 0xabcdef));
    EXPECT_EQ(seen.size(), n);
    EXPECT_LT(*seen.rbegin(), n);
  }
}

TEST(Sampling, PhongLobeChiSquare) {
  // cos(theta) of the lobe has CDF c^(e+1): bins of equal probability 1/k have edges (i/k)^(1/(e+1)). With 200000
  // samples the chi-square statistic over k = 20 bins (19 degrees of freedom) stays below 43.8 (p = 0.001).
  const float exponent = 25.0f;
  const int k = 20, n = 200000;
  std::vector<int> counts(size_t(k), 0);
  Rng rng(7);
  for (int i = 0; i < n; ++i) {
    const Vec3f d = sample_phong_lobe({rng.uniform(), rng.uniform()}, exponent);
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-5);
    const double p = std::pow(double(d.z), exponent + 1.0);  // CDF value, uniform on [0, 1]
    ++counts[size_t(std::min(k - 1, int(p * k)))];
  }
  double chi2 = 0;
  for (int c : counts) chi2 += (c - double(n) / k) * (c - double(n) / k) / (double(n) / k);
  EXPECT_LT(chi2, 43.8);
}

TEST(Sampling, DiskIsUniform) {
  // Uniform points on the unit disk have r^2 uniform on [0, 1]: mean 1/2, and every point lies in the disk.
  Rng rng(3);
  double r2 = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const Vec2f p = sample_disk({rng.uniform(), rng.uniform()});
    ASSERT_LE(glm::dot(p, p), 1.0f + 1e-6f);
    r2 += glm::dot(p, p);
  }
  EXPECT_NEAR(r2 / n, 0.5, 4 * std::sqrt(1.0 / 12 / n));  // var of r^2 (uniform on [0, 1]) is 1/12
}

}  // namespace
}  // namespace tessera
