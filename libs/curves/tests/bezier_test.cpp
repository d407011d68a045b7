#include "tessera/curves/bezier.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

template <class P>
BezierCurve<P> random_curve(int degree, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  BezierCurve<P> c;
  for (int i = 0; i <= degree; ++i) {
    P p;
    for (int k = 0; k < P::length(); ++k) p[k] = u(rng);
    c.points.push_back(p);
  }
  return c;
}

template <class P>
double dist(const P& a, const P& b) {
  return glm::length(a - b);
}

const Bezier2 kNotesCubic = cubic(Vec2(0, 0), Vec2(1, 3), Vec2(4, 3), Vec2(5, 0));

TEST(Bezier, CubicBasisIsTheNotesAndBernstein) {
  for (double t = 0; t <= 1.0; t += 1.0 / 64) {
    const auto b = cubic_basis(t);
    EXPECT_NEAR(b[0] + b[1] + b[2] + b[3], 1.0, 1e-15);
    EXPECT_DOUBLE_EQ(b[0], std::pow(1 - t, 3));
    EXPECT_DOUBLE_EQ(b[3], t * t * t);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(b[size_t(i)], bernstein(3, i, t), 1e-15);
    // B1, B4 and B2, B3 are mirror images about t = 1/2.
    const auto m = cubic_basis(1 - t);
    EXPECT_NEAR(b[0], m[3], 1e-15);
    EXPECT_NEAR(b[1], m[2], 1e-15);
    for (const double w : b) EXPECT_GE(w, 0.0);
  }
  EXPECT_THROW(bernstein(3, 4, 0.5), InvalidInput);
  EXPECT_THROW(bernstein(-1, 0, 0.5), InvalidInput);
}

template <class P>
void check_evaluators_agree() {
  std::mt19937 rng(42);
  for (int degree = 0; degree <= 8; ++degree)
    for (int trial = 0; trial < 20; ++trial) {
      const BezierCurve<P> c = random_curve<P>(degree, rng);
      const std::vector<P> a = power_coefficients(c);
      const int steps = 64;
      const std::vector<P> fd = evaluate_forward_differences(c, steps);
      ASSERT_EQ(fd.size(), size_t(steps + 1));
      for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps;
        const P ref = evaluate_de_casteljau(c, t);
        EXPECT_LT(dist(evaluate_bernstein(c, t), ref), 1e-12) << "degree " << degree << " t " << t;
        EXPECT_LT(dist(evaluate_horner(std::span<const P>(a), t), ref), 1e-12) << "degree " << degree;
        EXPECT_LT(dist(fd[size_t(i)], ref), 1e-12) << "degree " << degree << " step " << i;
      }
    }
}

TEST(Bezier, AllEvaluatorsAgree2D) { check_evaluators_agree<Vec2>(); }
TEST(Bezier, AllEvaluatorsAgree3D) { check_evaluators_agree<Vec3>(); }

TEST(Bezier, CurveStaysInConvexHull) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Bezier2 c = random_curve<Vec2>(3 + trial % 4, rng);
    for (int i = 0; i <= 200; ++i)
      EXPECT_TRUE(in_convex_hull(evaluate_de_casteljau(c, i / 200.0), c.points, 1e-12)) << trial << " " << i;
  }
}

TEST(Bezier, EndpointsAndEndTangentsAsTheNotesState) {
  // The curve interpolates P1 and P4; its end derivatives are 3(P2 - P1) and 3(P4 - P3).
  const Bezier3 c = cubic(Vec3(0, 0, 0), Vec3(1, 2, 0.5), Vec3(3, 2, -1), Vec3(4, 0, 2));
  EXPECT_EQ(evaluate_de_casteljau(c, 0.0), c.points[0]);
  EXPECT_EQ(evaluate_de_casteljau(c, 1.0), c.points[3]);
  EXPECT_EQ(evaluate_bernstein(c, 0.0), c.points[0]);
  EXPECT_EQ(evaluate_bernstein(c, 1.0), c.points[3]);
  const Bezier3 d = derivative(c);
  ASSERT_EQ(d.degree(), 2);
  EXPECT_LT(dist(evaluate_de_casteljau(d, 0.0), 3.0 * (c.points[1] - c.points[0])), 1e-15);
  EXPECT_LT(dist(evaluate_de_casteljau(d, 1.0), 3.0 * (c.points[3] - c.points[2])), 1e-15);
  // The hodograph agrees with a central difference inside.
  for (const double t : {0.2, 0.5, 0.9}) {
    const double h = 1e-6;
    const Vec3 fd = (evaluate_de_casteljau(c, t + h) - evaluate_de_casteljau(c, t - h)) / (2 * h);
    EXPECT_LT(dist(evaluate_de_casteljau(d, t), fd), 1e-7);
  }
  EXPECT_LT(dist(unit_tangent(c, 0.0), glm::normalize(c.points[1] - c.points[0])), 1e-15);
}

TEST(Bezier, TangentWhereControlPointsCoincide) {
  // P2 = P1: Q'(0) = 0 and the tangent's limit is along P3 - P1; likewise at the other end.
  const Bezier2 c = cubic(Vec2(0, 0), Vec2(0, 0), Vec2(1, 1), Vec2(2, 0));
  EXPECT_LT(dist(unit_tangent(c, 0.0), glm::normalize(Vec2(1, 1))), 1e-12);
  const Bezier2 e = cubic(Vec2(0, 0), Vec2(1, 1), Vec2(2, 0), Vec2(2, 0));
  EXPECT_LT(dist(unit_tangent(e, 1.0), glm::normalize(Vec2(1, -1))), 1e-12);
  EXPECT_LT(dist(unit_tangent(e, 1.0), unit_tangent(e, 1.0 - 1e-7)), 1e-6);
  const Bezier2 point = cubic(Vec2(1, 1), Vec2(1, 1), Vec2(1, 1), Vec2(1, 1));
  EXPECT_EQ(unit_tangent(point, 0.5), Vec2(0, 0));
}

TEST(Bezier, DeCasteljauAtHalfIsMidpointsOfMidpoints) {
  // The notes' construction: midpoints of the three legs, midpoints of those, and their midpoint is Q(1/2).
  const auto& p = kNotesCubic.points;
  const auto levels = de_casteljau_levels(kNotesCubic, 0.5);
  ASSERT_EQ(levels.size(), 4u);
  EXPECT_EQ(levels[1][0], 0.5 * (p[0] + p[1]));
  EXPECT_EQ(levels[1][2], 0.5 * (p[2] + p[3]));
  EXPECT_EQ(levels[2][0], 0.5 * (levels[1][0] + levels[1][1]));
  EXPECT_EQ(levels[3][0], Vec2(2.5, 2.25));
  EXPECT_LT(dist(levels[3][0], evaluate_bernstein(kNotesCubic, 0.5)), 1e-15);
  const auto at34 = de_casteljau_levels(kNotesCubic, 0.75);
  EXPECT_LT(dist(at34[3][0], evaluate_bernstein(kNotesCubic, 0.75)), 1e-14);
}

TEST(Bezier, SplitHalvesReproduceTheCurve) {
  std::mt19937 rng(9);
  for (const double s : {0.5, 0.75, 0.3, 0.0, 1.0})
    for (int degree = 1; degree <= 6; ++degree) {
      const Bezier3 c = random_curve<Vec3>(degree, rng);
      const auto [left, right] = split(c, s);
      EXPECT_EQ(left.degree(), degree);
      EXPECT_EQ(left.back(), right.front());
      for (int i = 0; i <= 32; ++i) {
        const double tau = i / 32.0;
        EXPECT_LT(dist(evaluate_de_casteljau(left, tau), evaluate_de_casteljau(c, s * tau)), 1e-14);
        EXPECT_LT(dist(evaluate_de_casteljau(right, tau), evaluate_de_casteljau(c, s + (1 - s) * tau)), 1e-14);
      }
    }
  EXPECT_THROW(split(kNotesCubic, 1.5), InvalidInput);
}

TEST(Bezier, DegreeElevationKeepsTheCurve) {
  std::mt19937 rng(11);
  for (int degree = 0; degree <= 6; ++degree) {
    const Bezier2 c = random_curve<Vec2>(degree, rng);
    Bezier2 e = elevate_degree(c);
    e = elevate_degree(e);
    EXPECT_EQ(e.degree(), degree + 2);
    for (int i = 0; i <= 20; ++i)
      EXPECT_LT(dist(evaluate_de_casteljau(e, i / 20.0), evaluate_de_casteljau(c, i / 20.0)), 1e-14);
  }
  // A quadratic elevated: the cubic's inner points are 2/3 of the way to the middle control point.
  const Bezier2 q = elevate_degree(quadratic(Vec2(0, 0), Vec2(3, 3), Vec2(6, 0)));
  EXPECT_LT(dist(q.points[1], Vec2(2, 2)), 1e-15);
  EXPECT_LT(dist(q.points[2], Vec2(4, 2)), 1e-15);
}

TEST(Bezier, QuadraticMidpointConstruction) {
  // The notes: midpoint subdivision of a quadratic makes one line (between the legs' midpoints) whose midpoint the
  // curve goes through.
  const Vec2 p0(0, 0), p1(2, 4), p2(4, 0);
  const Vec2 mid = 0.5 * (0.5 * (p0 + p1) + 0.5 * (p1 + p2));
  EXPECT_LT(dist(evaluate_bernstein(quadratic(p0, p1, p2), 0.5), mid), 1e-15);
}

TEST(Bezier, ForwardDifferenceStartIsTheNotesClosedForm) {
  // f(t) = a t^3 + b t^2 + c t + d: Δf = ah^3 + bh^2 + ch, Δ²f = 6ah^3 + 2bh^2, Δ³f = 6ah^3 (x coordinate).
  const auto coeff = power_coefficients(kNotesCubic);
  const double d = coeff[0].x, c = coeff[1].x, b = coeff[2].x, a = coeff[3].x;
  const double h = 0.1;
  const auto start = forward_difference_start(kNotesCubic, h);
  ASSERT_EQ(start.size(), 4u);
  EXPECT_NEAR(start[0].x, d, 1e-15);
  EXPECT_NEAR(start[1].x, a * h * h * h + b * h * h + c * h, 1e-15);
  EXPECT_NEAR(start[2].x, 6 * a * h * h * h + 2 * b * h * h, 1e-15);
  EXPECT_NEAR(start[3].x, 6 * a * h * h * h, 1e-15);
  EXPECT_THROW(evaluate_forward_differences(kNotesCubic, 0), InvalidInput);
}

// The largest distance between forward differences and de Casteljau over all `steps` + 1 samples.
double forward_difference_error(const Bezier2& c, int steps) {
  const auto fd = evaluate_forward_differences(c, steps);
  double worst = 0;
  for (int i = 0; i <= steps; ++i)
    worst = std::max(worst, dist(fd[size_t(i)], evaluate_de_casteljau(c, double(i) / steps)));
  return worst;
}

TEST(Bezier, ForwardDifferenceErrorGrowth) {
  // Rounding errors accumulate in the running sums. The start values are exact to a few ulps of h^k, so the error
  // is dominated by the N additions into f: expect at most about N ulps, here 4 N eps (coordinates within [-1, 1]).
  const Bezier2 c = cubic(Vec2(0.1, 0.2), Vec2(0.35, 0.95), Vec2(0.8, -0.3), Vec2(0.95, 0.6));
  std::printf("forward differences, cubic in [0,1]^2: steps, max error, bound 4 N eps\n");
  for (const int steps : {10, 100, 1000, 10000, 100000}) {
    const double error = forward_difference_error(c, steps);
    const double bound = 4.0 * steps * std::numeric_limits<double>::epsilon();
    std::printf("  %6d  %.3g  %.3g\n", steps, error, bound);
    EXPECT_LT(error, bound) << "N = " << steps;
  }
}

TEST(Bezier, ContinuityOfChains) {
  const Bezier2 a = cubic(Vec2(0, 0), Vec2(1, 2), Vec2(3, 2), Vec2(4, 0));
  const Bezier2 c1 = c1_continuation(a, Vec2(6, 1), Vec2(7, 3));
  EXPECT_EQ(c1.front(), a.back());
  EXPECT_EQ(c1.points[1], Vec2(5, -2));  // 2 P4 - P3
  EXPECT_EQ(joint_continuity(a, c1), Continuity::c1);
  const Bezier2 g1 = g1_continuation(a, 0.5, Vec2(6, 1), Vec2(7, 3));
  EXPECT_EQ(joint_continuity(a, g1), Continuity::g1);
  Bezier2 kinked = c1;
  kinked.points[1] = Vec2(5, 0);
  EXPECT_EQ(joint_continuity(a, kinked), Continuity::c0);
  Bezier2 gap = c1;
  gap.points[0] += Vec2(0.1, 0);
  EXPECT_EQ(joint_continuity(a, gap), Continuity::none);
  const std::vector<Bezier2> chain{a, c1, c1_continuation(c1, Vec2(9, 0), Vec2(10, 0))};
  EXPECT_EQ(chain_continuity<Vec2>(chain), Continuity::c1);
  const std::vector<Bezier2> mixed{a, g1, c1_continuation(g1, Vec2(9, 0), Vec2(10, 0))};
  EXPECT_EQ(chain_continuity<Vec2>(mixed), Continuity::g1);
  // C1 across degrees: a quadratic continued by a cubic matches derivatives 2 (P2 - P1) = 3 (Q1 - Q0).
  const Bezier2 q = quadratic(Vec2(0, 0), Vec2(1, 1), Vec2(2, 0));
  EXPECT_EQ(joint_continuity(q, c1_continuation(q, Vec2(3, 0), Vec2(4, 1))), Continuity::c1);
  EXPECT_THROW(g1_continuation(a, -1.0, Vec2(0, 0), Vec2(1, 1)), InvalidInput);
}

TEST(Bezier, EmptyCurvesAreRejected) {
  const Bezier2 empty;
  EXPECT_THROW(evaluate_de_casteljau(empty, 0.5), InvalidInput);
  EXPECT_THROW(evaluate_bernstein(empty, 0.5), InvalidInput);
  EXPECT_THROW(split(empty, 0.5), InvalidInput);
  std::vector<Vec2> out;
  EXPECT_THROW(flatten(empty, 0.1, out), InvalidInput);
}

}  // namespace
}  // namespace tessera
