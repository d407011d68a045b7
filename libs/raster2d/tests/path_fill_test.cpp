#include <gtest/gtest.h>

#include <random>

#include "raster_oracle.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/raster2d/blend.hpp"
#include "tessera/raster2d/path.hpp"

namespace tessera {
namespace {

Path rect_path(double x, double y, double w, double h) {
  return Path{{{{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}}};
}

TEST(PathFill, RectIsHalfOpen) {
  // rect(100, 200, 10, 10) covers exactly x in [100, 110), y in [200, 210), with and without antialiasing.
  for (const bool aa : {false, true}) {
    ImageRGBA img(400, 400, Vec4f(0, 0, 0, 1));
    fill_path(img, rect_path(100, 200, 10, 10), FillRule::non_zero, Vec4f(1, 0, 0, 1), aa);
    for (int y = 190; y < 220; ++y)
      for (int x = 90; x < 120; ++x) {
        const bool in = x >= 100 && x < 110 && y >= 200 && y < 210;
        EXPECT_EQ(img(x, y), in ? Vec4f(1, 0, 0, 1) : Vec4f(0, 0, 0, 1)) << x << "," << y << " aa=" << aa;
      }
  }
}

TEST(PathFill, ConcavePolygonWithHoleMatchesPointInPolygon) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 10; ++trial) {
    const Path path = test::random_polygon_with_holes(rng, 150, 110);
    for (const FillRule rule : {FillRule::non_zero, FillRule::even_odd}) {
      ImageRGBA img(150, 110, Vec4f(0, 0, 0, 0));
      fill_path(img, path, rule, Vec4f(0.2f, 0.4f, 0.6f, 1), false);
      int mismatches = 0;
      for (int y = 0; y < 110; ++y)
        for (int x = 0; x < 150; ++x)
          mismatches += (img(x, y).w == 1.0f) != test::point_in_path(path, rule, {x + 0.5, y + 0.5});
      EXPECT_EQ(mismatches, 0);
    }
  }
}

TEST(PathFill, AntialiasedCoverageMatchesSupersampledOracle) {
  std::mt19937 rng(29);
  for (int trial = 0; trial < 4; ++trial) {
    const Path path = test::random_polygon_with_holes(rng, 64, 48);
    for (const FillRule rule : {FillRule::non_zero, FillRule::even_odd}) {
      ImageRGBA img(64, 48, Vec4f(0, 0, 0, 0));
      fill_path(img, path, rule, Vec4f(1, 1, 1, 1), true);  // over transparent, alpha = coverage
      const std::vector<double> oracle = test::supersampled_coverage(path, rule, 64, 48, 64);
      double max_err = 0, sum = 0, sum_oracle = 0;
      for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
          max_err = std::max(max_err, std::fabs(img(x, y).w - oracle[size_t(y * 64 + x)]));
          sum += img(x, y).w;
          sum_oracle += oracle[size_t(y * 64 + x)];
        }
      EXPECT_LT(max_err, 0.02);
      EXPECT_NEAR(sum, sum_oracle, 1e-3 * sum_oracle);
    }
  }
}

TEST(PathFill, AntialiasedAreaOfARotatedSquareIsExact) {
  // A square of side 20 rotated by 30 degrees: the coverages sum to its area, 400.
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6);
  Path path{{{}}};
  for (const Vec2 corner : {Vec2(-10, -10), Vec2(10, -10), Vec2(10, 10), Vec2(-10, 10)})
    path.contours[0].push_back(Vec2(32.3, 31.7) + Vec2(c * corner.x - s * corner.y, s * corner.x + c * corner.y));
  ImageRGBA img(64, 64, Vec4f(0));
  fill_path(img, path, FillRule::non_zero, Vec4f(1), true);
  double area = 0;
  for (const Vec4f& p : img.pixels()) area += p.w;
  EXPECT_NEAR(area, 400.0, 1e-3);
}

TEST(PathFill, CompositesSourceOverWithStraightAlpha) {
  ImageRGBA img(4, 4, Vec4f(0, 0, 1, 1));
  fill_path(img, rect_path(0, 0, 2, 4), FillRule::non_zero, Vec4f(1, 0, 0, 0.25f), false);
  EXPECT_EQ(img(0, 0), blend_over(Vec4f(0, 0, 1, 1), Vec4f(1, 0, 0, 0.25f)));
  EXPECT_NEAR(img(1, 3).x, 0.25f, 1e-6f);
  EXPECT_NEAR(img(1, 3).z, 0.75f, 1e-6f);
  EXPECT_EQ(img(2, 0), Vec4f(0, 0, 1, 1));
  // Over a transparent pixel the color stays straight (not darkened) and alpha accumulates.
  const Vec4f over_clear = blend_over(Vec4f(0), Vec4f(0.8f, 0.6f, 0.4f, 0.5f));
  EXPECT_NEAR(over_clear.x, 0.8f, 1e-6f);
  EXPECT_NEAR(over_clear.w, 0.5f, 1e-6f);
  EXPECT_NEAR(blend_over(over_clear, Vec4f(0.8f, 0.6f, 0.4f, 0.5f)).w, 0.75f, 1e-6f);
}

TEST(PathFill, IdenticalForAnyThreadCount) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-20, 700);
  Path path{{{}}};
  for (int i = 0; i < 500; ++i) path.contours[0].push_back({u(rng), u(rng)});
  for (const bool aa : {false, true}) {
    ImageRGBA one(640, 640, Vec4f(0.1f, 0.2f, 0.3f, 1)), all = one;
    {
      ThreadLimit limit(1);
      fill_path(one, path, FillRule::even_odd, Vec4f(0.9f, 0.5f, 0.1f, 0.7f), aa);
    }
    fill_path(all, path, FillRule::even_odd, Vec4f(0.9f, 0.5f, 0.1f, 0.7f), aa);
    EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), all.pixels().begin()));
  }
}

TEST(PathFill, ZeroAlphaAndEmptyPathsChangeNothing) {
  ImageRGBA img(8, 8, Vec4f(0.5f));
  fill_path(img, rect_path(0, 0, 8, 8), FillRule::non_zero, Vec4f(1, 0, 0, 0), true);
  fill_path(img, Path{}, FillRule::non_zero, Vec4f(1), true);
  fill_path(img, rect_path(-50, -50, 10, 10), FillRule::non_zero, Vec4f(1), true);
  fill_path(img, rect_path(20, 0, 10, 10), FillRule::non_zero, Vec4f(1), false);
  for (const Vec4f& p : img.pixels()) EXPECT_EQ(p, Vec4f(0.5f));
}

}  // namespace
}  // namespace tessera
