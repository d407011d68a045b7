#include "tessera/curves/convex.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

double triangle_area(const Vec2& a, const Vec2& b, const Vec2& c) { return 0.5 * std::abs(signed_area2(a, b, c)); }

TEST(Convex, CombineAndConvexWeights) {
  const std::vector<Vec2> points{{0, 0}, {2, 0}, {0, 2}};
  const std::vector<double> w{0.25, 0.25, 0.5};
  EXPECT_EQ(combine(points, w), Vec2(0.5, 1.0));
  EXPECT_TRUE(is_convex_combination(w));
  EXPECT_FALSE(is_convex_combination(std::vector<double>{0.5, 0.6}));
  EXPECT_FALSE(is_convex_combination(std::vector<double>{1.5, -0.5}));
  EXPECT_THROW(combine(points, std::vector<double>{1.0}), InvalidInput);
}

TEST(Convex, BarycentricIsRatioOfOppositeAreas) {
  // The notes: w_i = a_i / A, a_i the area of the sub-triangle opposite p_i.
  const Vec2 p1(1, 1), p2(7, 2), p3(3, 6);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 200; ++k) {
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Vec2 q = p1 + a * (p2 - p1) + b * (p3 - p1);
    const auto w = barycentric(q, p1, p2, p3);
    const double area = triangle_area(p1, p2, p3);
    EXPECT_NEAR(w[0], triangle_area(q, p2, p3) / area, 1e-12);
    EXPECT_NEAR(w[1], triangle_area(p1, q, p3) / area, 1e-12);
    EXPECT_NEAR(w[2], triangle_area(p1, p2, q) / area, 1e-12);
    const Vec2 back = w[0] * p1 + w[1] * p2 + w[2] * p3;
    EXPECT_NEAR(back.x, q.x, 1e-12);
    EXPECT_NEAR(back.y, q.y, 1e-12);
  }
  const auto c = barycentric((p1 + p2 + p3) / 3.0, p1, p2, p3);
  for (const double w : c) EXPECT_NEAR(w, 1.0 / 3.0, 1e-15);
  // Outside: a negative weight, still summing to 1.
  const auto out = barycentric(Vec2(-5, -5), p1, p2, p3);
  EXPECT_LT(std::min({out[0], out[1], out[2]}), 0);
  EXPECT_NEAR(out[0] + out[1] + out[2], 1.0, 1e-12);
  EXPECT_THROW(barycentric(Vec2(0, 0), p1, p1, p3), InvalidInput);
}

TEST(Convex, Barycentric3DMatches2DInPlane) {
  const Vec3 p1(0, 0, 1), p2(4, 0, 1), p3(0, 3, 1), q(1, 1, 1);
  const auto w3 = barycentric(q, p1, p2, p3);
  const auto w2 = barycentric(Vec2(1, 1), Vec2(0, 0), Vec2(4, 0), Vec2(0, 3));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(w3[size_t(i)], w2[size_t(i)], 1e-15);
  EXPECT_THROW(barycentric(q, p1, p2, p1 + 2.0 * (p2 - p1)), InvalidInput);
}

TEST(Convex, HullOfSquareWithInteriorAndCollinearPoints) {
  const std::vector<Vec2> points{{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}, {0.5, 1.5}, {0, 0}, {2, 1}};
  const auto hull = convex_hull(points);
  ASSERT_EQ(hull.size(), 4u);
  EXPECT_EQ(hull[0], Vec2(0, 0));
  EXPECT_EQ(hull[1], Vec2(2, 0));
  EXPECT_EQ(hull[2], Vec2(2, 2));
  EXPECT_EQ(hull[3], Vec2(0, 2));
  EXPECT_EQ(convex_hull(std::vector<Vec2>{{1, 1}, {1, 1}}).size(), 1u);
  EXPECT_EQ(convex_hull(std::vector<Vec2>{{0, 0}, {1, 1}, {2, 2}}).size(), 2u);
}

TEST(Convex, PointInHullAgreesWithBarycentricSigns) {
  // Oracle: for a triangle, inside the hull <=> every barycentric weight >= 0 (the notes' convex-combination test).
  const Vec2 p1(0.1, 0.2), p2(0.9, 0.3), p3(0.4, 0.95);
  const std::vector<Vec2> tri{p1, p2, p3};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  int inside = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec2 q(u(rng), u(rng));
    const auto w = barycentric(q, p1, p2, p3);
    const bool expected = w[0] >= 0 && w[1] >= 0 && w[2] >= 0;
    EXPECT_EQ(in_convex_hull(q, tri, 0.0), expected) << q.x << "," << q.y;
    inside += expected;
  }
  EXPECT_GT(inside, 200);  // both outcomes are exercised
  EXPECT_TRUE(in_convex_hull(Vec2(0.5, 0.5), std::vector<Vec2>{{0, 0}, {1, 1}}));
  EXPECT_FALSE(in_convex_hull(Vec2(0.5, 0.6), std::vector<Vec2>{{0, 0}, {1, 1}}));
  EXPECT_FALSE(in_convex_hull(Vec2(0, 0), std::vector<Vec2>{}));
}

TEST(Convex, DistanceToSegment) {
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(1, 1), Vec2(0, 0), Vec2(2, 0)), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(3, 0), Vec2(0, 0), Vec2(2, 0)), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec3(0, 0, 2), Vec3(0, 0, 0), Vec3(0, 0, 0)), 2.0);
}

}  // namespace
}  // namespace tessera
