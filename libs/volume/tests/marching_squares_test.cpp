#include "tessera/volume/marching_squares.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/memory_budget.hpp"

namespace tessera {
namespace {

TEST(MarchingSquares, CircleIsOneClosedLineNearTheRadius) {
  DepthImage f(41, 41);
  for (int y = 0; y < 41; ++y)
    for (int x = 0; x < 41; ++x) f(x, y) = float(12.0 - std::hypot(x - 20.0, y - 20.0));
  const auto lines = marching_squares(f, 0.0f);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(lines[0].closed);
  for (const auto& p : lines[0].points) EXPECT_NEAR(std::hypot(p.x - 20, p.y - 20), 12.0, 0.05);
}

TEST(MarchingSquares, SaddleIsResolvedByTheCenterValue) {
  DepthImage f(2, 2);
  f(0, 0) = 1, f(1, 1) = 1, f(1, 0) = 0, f(0, 1) = 0;  // diagonal inside corners, center 0.5
  // Center inside (iso 0.4): the inside corners join, so each line cuts off one outside corner.
  auto lines = marching_squares(f, 0.4f);
  ASSERT_EQ(lines.size(), 2u);
  for (const auto& l : lines) {
    const Vec2 mid = 0.5 * (l.points[0] + l.points[1]);
    EXPECT_TRUE(glm::length(mid - Vec2(1, 0)) < 0.7 || glm::length(mid - Vec2(0, 1)) < 0.7);
  }
  // Center outside (iso 0.6): the inside corners are separated.
  lines = marching_squares(f, 0.6f);
  ASSERT_EQ(lines.size(), 2u);
  for (const auto& l : lines) {
    const Vec2 mid = 0.5 * (l.points[0] + l.points[1]);
    EXPECT_TRUE(glm::length(mid - Vec2(0, 0)) < 0.7 || glm::length(mid - Vec2(1, 1)) < 0.7);
  }
}

// Issue 24, class 3: the segments were stored whatever their number. They are counted first and 200 bytes each
// checked against the budget. A checkerboard makes every cell a saddle: 2 (n - 1)^2 segments.
TEST(MarchingSquares, SegmentsOverTheMemoryBudgetAreRefusedBeforeTheyAreStored) {
  const int n = 50;
  DepthImage f(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) f(x, y) = float((x + y) % 2);
  const uint64_t segments = 2 * (n - 1) * (n - 1);
  MemoryBudget::set_limit(200 * segments - 1);
  std::string message = "no error";
  try {
    marching_squares(f, 0.5f);
  } catch (const MemoryBudgetError& e) {
    message = e.what();
  }
  MemoryBudget::set_limit(200 * segments);
  std::vector<Polyline> lines;
  EXPECT_NO_THROW(lines = marching_squares(f, 0.5f));
  MemoryBudget::set_limit(0);
  EXPECT_NE(message.find("marching squares: 4802 contour segments of a 50x50 field needs about"), std::string::npos)
      << message;
  uint64_t drawn = 0;
  for (const auto& l : lines) drawn += l.points.size() - (l.closed ? 0 : 1);
  EXPECT_EQ(drawn, segments);
}

}  // namespace
}  // namespace tessera
