#include "tessera/fractal/self_similar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

TEST(SelfSimilar, CantorSetCountsAndMeasure) {
  for (int n = 0; n <= 10; ++n) {
    const auto set = cantor_set(n);
    ASSERT_EQ(set.size(), size_t(1) << n);
    double total = 0;
    for (size_t i = 0; i < set.size(); ++i) {
      // Every left end times 3^n is an integer without the digit 1 in base 3.
      auto k = int64_t(std::llround(set[i].a * std::pow(3.0, n)));
      for (int d = 0; d < n; ++d, k /= 3) {
        ASSERT_NE(k % 3, 1);
      }
      EXPECT_NEAR(set[i].b - set[i].a, std::pow(3.0, -n), 1e-15);
      if (i > 0) {
        EXPECT_GT(set[i].a, set[i - 1].b);  // disjoint, left to right
      }
      total += set[i].b - set[i].a;
    }
    EXPECT_NEAR(total, cantor_measure(n), 1e-13);
    EXPECT_DOUBLE_EQ(cantor_measure(n), std::pow(2.0, n) / std::pow(3.0, n));
  }
  EXPECT_EQ(cantor_set(1)[1].a, 2.0 / 3.0);
}

TEST(SelfSimilar, CantorDustAndCarpetAreas) {
  for (int n = 0; n <= 4; ++n) {
    const auto dust = cantor_dust(n);
    EXPECT_EQ(dust.size(), size_t(1) << (2 * n));
    const auto carpet = sierpinski_carpet(n);
    ASSERT_EQ(carpet.size(), size_t(std::pow(8, n)));
    double area = 0;
    std::set<std::pair<long, long>> cells;
    for (const Rect& r : carpet) {
      area += r.w * r.h;
      const long i = std::lround(r.x * std::pow(3, n)), j = std::lround(r.y * std::pow(3, n));
      cells.insert({i, j});
      // No removed middle: at no level are both digits 1.
      long a = i, b = j;
      for (int d = 0; d < n; ++d, a /= 3, b /= 3) {
        ASSERT_FALSE(a % 3 == 1 && b % 3 == 1);
      }
    }
    EXPECT_EQ(cells.size(), carpet.size());
    EXPECT_NEAR(area, carpet_area(n), 1e-13);
    EXPECT_DOUBLE_EQ(carpet_area(n), std::pow(8.0 / 9.0, n));
  }
}

TEST(SelfSimilar, SierpinskiTriangleArea) {
  const double full = std::sqrt(3.0) / 4.0;
  for (int n = 0; n <= 6; ++n) {
    const auto tris = sierpinski_triangle(n);
    ASSERT_EQ(tris.size(), size_t(std::pow(3, n)));
    double area = 0;
    for (const Triangle2& t : tris) area += polygon_area({t.a, t.b, t.c});
    EXPECT_NEAR(area / full, sierpinski_triangle_fraction(n), 1e-12);
  }
}

TEST(SelfSimilar, KochLengthGrowsByFourThirds) {
  for (int n = 0; n <= 7; ++n) {
    const auto curve = koch_curve(n);
    ASSERT_EQ(curve.size(), size_t(std::pow(4, n)) + 1);
    EXPECT_NEAR(polyline_length(curve), koch_length(n), 1e-11);
    EXPECT_EQ(curve.front(), Vec2(0, 0));
    EXPECT_NEAR(curve.back().x, 1.0, 1e-15);
  }
  const auto one = koch_curve(1);  // the notes' first step: the bump points up (left of the segment)
  EXPECT_NEAR(one[2].x, 0.5, 1e-15);
  EXPECT_NEAR(one[2].y, std::sqrt(3.0) / 6.0, 1e-15);
  EXPECT_GT(koch_length(50), 1e6);  // infinite length in the limit
}

TEST(SelfSimilar, SnowflakeAreaTendsToEightFifths) {
  const double triangle = std::sqrt(3.0) / 4.0;
  for (int n = 0; n <= 7; ++n) {
    const auto flake = koch_snowflake(n);
    ASSERT_EQ(flake.size(), 3 * size_t(std::pow(4, n)));
    EXPECT_NEAR(polygon_area(flake) / triangle, snowflake_area_ratio(n), 1e-11);  // positive: counterclockwise
    EXPECT_NEAR(polyline_length(flake) + glm::distance(flake.back(), flake.front()), 3 * koch_length(n), 1e-10);
  }
  EXPECT_NEAR(snowflake_area_ratio(60), 1.6, 1e-15);
}

void expect_space_filling(const std::vector<Vec2>& curve, int cells_per_side) {
  ASSERT_EQ(curve.size(), size_t(cells_per_side) * size_t(cells_per_side));
  std::set<std::pair<long, long>> seen;
  for (size_t i = 0; i < curve.size(); ++i) {
    const long x = std::lround(curve[i].x * cells_per_side - 0.5), y = std::lround(curve[i].y * cells_per_side - 0.5);
    seen.insert({x, y});
    if (i > 0) {
      ASSERT_NEAR(glm::distance(curve[i], curve[i - 1]), 1.0 / cells_per_side, 1e-12) << i;
    }
  }
  EXPECT_EQ(seen.size(), curve.size());  // every cell exactly once
}

TEST(SelfSimilar, HilbertCurveVisitsEveryCellOnce) {
  for (int n = 0; n <= 6; ++n) {
    const auto curve = hilbert_curve(n);
    expect_space_filling(curve, 1 << n);
    if (n > 0) {
      const double c = 0.5 / (1 << n);
      EXPECT_NEAR(curve.front().x, c, 1e-15);
      EXPECT_NEAR(curve.back().x, 1 - c, 1e-15);
      EXPECT_NEAR(curve.back().y, c, 1e-15);
    }
  }
}

TEST(SelfSimilar, PeanoCurveVisitsEveryCellOnce) {
  for (int n = 0; n <= 4; ++n) {
    const int side = int(std::pow(3, n));
    const auto curve = peano_curve(n);
    expect_space_filling(curve, side);
    EXPECT_NEAR(curve.back().x, 1 - 0.5 / side, 1e-15);
    EXPECT_NEAR(curve.back().y, 1 - 0.5 / side, 1e-15);
  }
  // The notes' first level: up the first column, down the second, up the third.
  const auto one = peano_curve(1);
  EXPECT_NEAR(one[2].y, 5.0 / 6.0, 1e-15);
  EXPECT_NEAR(one[3].y, 5.0 / 6.0, 1e-15);
  EXPECT_NEAR(one[5].y, 1.0 / 6.0, 1e-15);
}

TEST(SelfSimilar, SimilarityDimensions) {
  EXPECT_NEAR(similarity_dimension(4, 3), 1.2619, 5e-5);  // Koch
  EXPECT_NEAR(similarity_dimension(8, 3), 1.8928, 5e-5);  // carpet
  EXPECT_NEAR(similarity_dimension(2, 3), 0.6309, 5e-5);  // Cantor set
  EXPECT_NEAR(similarity_dimension(3, 2), 1.5850, 5e-5);  // Sierpinski triangle
  EXPECT_NEAR(similarity_dimension(9, 3), 2.0, 1e-15);    // Peano: fills the square
  EXPECT_NEAR(similarity_dimension(4, 2), 2.0, 1e-15);    // the notes' square scaled 2x -> 4 copies
  EXPECT_THROW(similarity_dimension(4, 1), InvalidInput);
}

TEST(SelfSimilar, DepthLimits) {
  EXPECT_THROW(cantor_set(-1), InvalidInput);
  EXPECT_THROW(sierpinski_carpet(8), InvalidInput);
  EXPECT_THROW(peano_curve(8), InvalidInput);
  EXPECT_THROW(koch_curve(11), InvalidInput);
}

}  // namespace
}  // namespace tessera
