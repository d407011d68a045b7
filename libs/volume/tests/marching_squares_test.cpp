#include "tessera/volume/marching_squares.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace tessera
