#include "tessera/curves/flatten.hpp"

#include <gtest/gtest.h>

#include "tessera/curves/bezier.hpp"

namespace tessera {
namespace {

// The largest distance from dense samples of the curve to the polyline p0 + out.
template <class P>
double max_deviation(const BezierCurve<P>& curve, const std::vector<P>& polyline) {
  double worst = 0;
  for (int i = 0; i <= 2000; ++i) {
    const P q = evaluate_de_casteljau(curve, i / 2000.0);
    double best = INFINITY;
    for (size_t k = 1; k < polyline.size(); ++k)
      best = std::min(best, distance_to_segment(q, polyline[k - 1], polyline[k]));
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(Flatten, CubicWithinTolerance) {
  const Vec2 p0(10, 10), p1(60, 200), p2(250, -80), p3(300, 120);
  for (const double tolerance : {2.0, 0.25, 0.01}) {
    std::vector<Vec2> out;
    flatten_cubic(p0, p1, p2, p3, tolerance, out);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.back(), p3);
    std::vector<Vec2> polyline{p0};
    polyline.insert(polyline.end(), out.begin(), out.end());
    EXPECT_LE(max_deviation(cubic(p0, p1, p2, p3), polyline), tolerance);
  }
}

TEST(Flatten, FinerToleranceGivesMorePoints) {
  std::vector<Vec2> coarse, fine;
  flatten_cubic(Vec2(0, 0), Vec2(0, 100), Vec2(100, 100), Vec2(100, 0), 1.0, coarse);
  flatten_cubic(Vec2(0, 0), Vec2(0, 100), Vec2(100, 100), Vec2(100, 0), 0.01, fine);
  EXPECT_GT(fine.size(), 4 * coarse.size());
  // A straight cubic is already flat: just its end point.
  std::vector<Vec2> line;
  flatten_cubic(Vec2(0, 0), Vec2(1, 1), Vec2(2, 2), Vec2(3, 3), 0.1, line);
  EXPECT_EQ(line, std::vector<Vec2>{Vec2(3, 3)});
}

TEST(Flatten, QuadraticWithinToleranceAndAppends) {
  const Vec2 p0(0, 0), p1(50, 100), p2(100, 0);
  std::vector<Vec2> out{Vec2(-1, -1)};  // appends, keeps what is there
  flatten_quadratic(p0, p1, p2, 0.1, out);
  EXPECT_EQ(out.front(), Vec2(-1, -1));
  EXPECT_EQ(out.back(), p2);
  std::vector<Vec2> polyline{p0};
  polyline.insert(polyline.end(), out.begin() + 1, out.end());
  EXPECT_LE(max_deviation(quadratic(p0, p1, p2), polyline), 0.1);
}

TEST(Flatten, AnyDegreeIn3D) {
  const Bezier3 c{{Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(2, -1, 1), Vec3(3, 2, 2), Vec3(4, 0, 0)}};
  std::vector<Vec3> out;
  flatten(c, 1e-3, out);
  std::vector<Vec3> polyline{c.front()};
  polyline.insert(polyline.end(), out.begin(), out.end());
  EXPECT_LE(max_deviation(c, polyline), 1e-3);
}

TEST(Flatten, DepthLimitBoundsOutput) {
  // A tolerance of 0 is clamped to 1e-9 and the depth to 16, so the output stays finite.
  std::vector<Vec2> out;
  flatten_cubic(Vec2(0, 0), Vec2(0, 1e6), Vec2(1e6, 1e6), Vec2(1e6, 0), 0.0, out);
  EXPECT_LE(out.size(), size_t(1) << 16);
}

}  // namespace
}  // namespace tessera
