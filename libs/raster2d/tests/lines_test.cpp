#include "tessera/raster2d/lines.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace tessera {
namespace {

using Pixels = std::vector<std::pair<int, int>>;

Pixels dda(double x0, double y0, double x1, double y1) {
  Pixels out;
  line_dda(x0, y0, x1, y1, [&](int x, int y, float) { out.push_back({x, y}); });
  return out;
}

TEST(Lines, DdaMatchesAHandTraceOfTheNotesLoop) {
  // line(0, 0, 5, 2): length 5, xinc 1, yinc 0.4; y = 0, .4, .8, 1.2, 1.6, 2 rounds to 0 0 1 1 2 2.
  EXPECT_EQ(dda(0, 0, 5, 2), (Pixels{{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}}));
  // line(0, 0, 2, 1): y = 0, .5, 1; round() takes the half away from zero.
  EXPECT_EQ(dda(0, 0, 2, 1), (Pixels{{0, 0}, {1, 1}, {2, 1}}));
  // line(2, 3, -1, 9.5): length 6.5 so i = 0..6 (seven pixels, the end (-1, 9.5) itself is not reached);
  // xinc = -3/6.5: x = 2, 1.54, 1.08, .62, .15, -.31, -.77.
  EXPECT_EQ(dda(2, 3, -1, 9.5), (Pixels{{2, 3}, {2, 4}, {1, 5}, {1, 6}, {0, 7}, {0, 8}, {-1, 9}}));
  // The notes' example line: (100, 400) to (100, 100) is 301 pixels straight up.
  const Pixels vertical = dda(100, 400, 100, 100);
  ASSERT_EQ(vertical.size(), 301u);
  EXPECT_EQ(vertical.front(), (std::pair{100, 400}));
  EXPECT_EQ(vertical.back(), (std::pair{100, 100}));
  // Where the notes would divide by zero: one pixel.
  EXPECT_EQ(dda(3.4, 7.6, 3.4, 7.6), (Pixels{{3, 8}}));
}

// The independent oracle: for each step k along the major axis, the minor coordinate nearest the true line, exact
// halves rounding toward the start.
Pixels closest_pixel_oracle(int x0, int y0, int x1, int y1) {
  const int dx = x1 - x0, dy = y1 - y0;
  const bool x_major = std::abs(dx) >= std::abs(dy);
  const int major = x_major ? std::abs(dx) : std::abs(dy);
  Pixels out;
  for (int k = 0; k <= major; ++k) {
    const double t = major == 0 ? 0.0 : double(k) * (x_major ? std::abs(dy) : std::abs(dx)) / major;
    const int j = int(std::ceil(t - 0.5));
    const int sx = dx >= 0 ? 1 : -1, sy = dy >= 0 ? 1 : -1;
    out.push_back(x_major ? std::pair{x0 + sx * k, y0 + sy * j} : std::pair{x0 + sx * j, y0 + sy * k});
  }
  return out;
}

TEST(Lines, BresenhamEqualsClosestPixelOracleInAllOctants) {
  std::mt19937 rng(41);
  std::uniform_int_distribution<int> u(-60, 60);
  int octants_seen = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int x0 = u(rng), y0 = u(rng), x1 = u(rng), y1 = u(rng);
    Pixels got;
    line_bresenham(x0, y0, x1, y1, [&](int x, int y, float c) {
      EXPECT_EQ(c, 1.0f);
      got.push_back({x, y});
    });
    ASSERT_EQ(got, closest_pixel_oracle(x0, y0, x1, y1)) << x0 << "," << y0 << " -> " << x1 << "," << y1;
    EXPECT_EQ(got.front(), (std::pair{x0, y0}));
    EXPECT_EQ(got.back(), (std::pair{x1, y1}));
    const int dx = x1 - x0, dy = y1 - y0;
    octants_seen |= 1 << ((dx < 0) * 4 + (dy < 0) * 2 + (std::abs(dy) > std::abs(dx)));
  }
  EXPECT_EQ(octants_seen, 0xff);
  // Axis-aligned, diagonal and single-point lines.
  for (const auto& [x1, y1] : {std::pair{5, 0}, {-5, 0}, {0, 5}, {0, -5}, {5, 5}, {-5, 5}, {5, -5}, {-5, -5}, {0, 0}}) {
    Pixels got;
    line_bresenham(0, 0, x1, y1, [&](int x, int y, float) { got.push_back({x, y}); });
    EXPECT_EQ(got, closest_pixel_oracle(0, 0, x1, y1));
  }
}

TEST(Lines, WuIntensitiesSumToOnePerColumn) {
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> u(0, 100);
  for (int trial = 0; trial < 200; ++trial) {
    const double x0 = u(rng), y0 = u(rng), x1 = u(rng), y1 = u(rng);
    const bool steep = std::fabs(y1 - y0) > std::fabs(x1 - x0);
    std::map<int, double> per_step;  // major-axis coordinate -> summed intensity
    line_wu(x0, y0, x1, y1, [&](int x, int y, float c) {
      EXPECT_GT(c, 0.0f);
      EXPECT_LE(c, 1.0f);
      per_step[steep ? y : x] += c;
    });
    if (per_step.size() < 3) continue;
    // Interior columns hold exactly 1; the two end columns hold the fraction of the pixel the line covers.
    for (auto it = std::next(per_step.begin()); it != std::prev(per_step.end()); ++it)
      EXPECT_NEAR(it->second, 1.0, 1e-6);
    const double a = std::min(steep ? y0 : x0, steep ? y1 : x1), b = std::max(steep ? y0 : x0, steep ? y1 : x1);
    EXPECT_NEAR(per_step.begin()->second, std::floor(a + 0.5) + 0.5 - a, 1e-6);
    EXPECT_NEAR(std::prev(per_step.end())->second, b + 0.5 - std::floor(b + 0.5), 1e-6);
  }
}

TEST(Lines, WuIntensityFollowsDistanceToTheLine) {
  // y = 0.25 x from (0, 0) to (8, 2): column 2 has y = 0.5, split evenly between rows 0 and 1.
  std::map<std::pair<int, int>, float> got;
  line_wu(0, 0, 8, 2, [&](int x, int y, float c) { got[{x, y}] = c; });
  auto at = [&](int x, int y) { return got[{x, y}]; };
  EXPECT_NEAR(at(2, 0), 0.5f, 1e-6f);
  EXPECT_NEAR(at(2, 1), 0.5f, 1e-6f);
  EXPECT_NEAR(at(1, 0), 0.75f, 1e-6f);
  EXPECT_NEAR(at(1, 1), 0.25f, 1e-6f);
  EXPECT_EQ(got.count(std::pair(4, 0)), 0u);  // exactly on row 1: one pixel at full intensity
  EXPECT_NEAR(at(4, 1), 1.0f, 1e-6f);
}

TEST(Lines, CircleSegmentsAreTheNotesLoop) {
  const std::vector<Vec2> v = circle_segments(20);
  ASSERT_EQ(v.size(), 40u);
  EXPECT_EQ(v[0], Vec2(1, 0));
  for (int i = 0; i < 20; ++i) {
    EXPECT_NEAR(glm::length(v[size_t(2 * i + 1)]), 1.0, 1e-12);
    if (i > 0) {
      EXPECT_EQ(v[size_t(2 * i)], v[size_t(2 * i - 1)]);  // each segment starts where the last ended
    }
  }
  EXPECT_NEAR(v[39].x, 1.0, 1e-12);
  EXPECT_NEAR(v[39].y, 0.0, 1e-12);
  EXPECT_THROW(circle_segments(0), InvalidInput);
}

TEST(Lines, DrawLineClipsAndBlends) {
  ImageRGBA img(10, 10, Vec4f(0, 0, 0, 1));
  draw_line(img, {-5, 2}, {20, 2}, Vec4f(1, 1, 1, 1), LineAlgorithm::bresenham);
  for (int x = 0; x < 10; ++x) EXPECT_EQ(img(x, 2), Vec4f(1, 1, 1, 1));
  draw_line(img, {0, 5}, {9, 5}, Vec4f(1, 0, 0, 0.5f), LineAlgorithm::dda);
  EXPECT_NEAR(img(3, 5).x, 0.5f, 1e-6f);
  draw_line(img, {0, 7.5}, {9, 7.5}, Vec4f(1, 1, 1, 1), LineAlgorithm::wu);
  EXPECT_NEAR(img(4, 7).x, 0.5f, 1e-6f);
  EXPECT_NEAR(img(4, 8).x, 0.5f, 1e-6f);
}

}  // namespace
}  // namespace tessera
