#include <gtest/gtest.h>

#include "tessera/raster2d/path.hpp"

namespace tessera {
namespace {

// The antialiased area of a stroke outline filled with the nonzero rule.
double stroke_area(const std::vector<Vec2>& line, bool closed, const StrokeStyle& style, int size = 128) {
  ImageRGBA img(size, size, Vec4f(0));
  fill_path(img, stroke_path(line, closed, style), FillRule::non_zero, Vec4f(1), true);
  double area = 0;
  for (const Vec4f& p : img.pixels()) area += p.w;
  return area;
}

StrokeStyle style(double width, LineJoin join, LineCap cap, double miter_limit = 4) {
  return StrokeStyle{width, join, cap, miter_limit};
}

TEST(Stroke, ButtAndSquareCapsCoverExactRectangles) {
  for (const auto& [cap, extend] : {std::pair{LineCap::butt, 0}, std::pair{LineCap::square, 2}}) {
    ImageRGBA img(64, 64, Vec4f(0));
    fill_path(img, stroke_path({{10, 20}, {50, 20}}, false, style(4, LineJoin::miter, cap)), FillRule::non_zero,
              Vec4f(1), false);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const bool in = y >= 18 && y < 22 && x >= 10 - extend && x < 50 + extend;
        EXPECT_EQ(img(x, y).w, in ? 1.0f : 0.0f) << x << "," << y;
      }
  }
}

TEST(Stroke, RoundCapsAddADisk) {
  const double r = 5;
  EXPECT_NEAR(stroke_area({{20, 40}, {90, 40}}, false, style(2 * r, LineJoin::round, LineCap::round)),
              70 * 2 * r + kPi * r * r, 0.5);
}

TEST(Stroke, JoinAreasOfARightAngle) {
  // (20, 20) -> (80, 20) -> (80, 90), half width r: the rectangles' union is 2r(a + b) - r^2; the outer corner adds
  // r^2 (miter), r^2 / 2 (bevel) or pi r^2 / 4 (round).
  const double r = 6, a = 60, b = 70;
  const std::vector<Vec2> line{{20, 20}, {80, 20}, {80, 90}};
  const double base = 2 * r * (a + b) - r * r;
  EXPECT_NEAR(stroke_area(line, false, style(2 * r, LineJoin::miter, LineCap::butt)), base + r * r, 0.05);
  EXPECT_NEAR(stroke_area(line, false, style(2 * r, LineJoin::bevel, LineCap::butt)), base + r * r / 2, 0.05);
  EXPECT_NEAR(stroke_area(line, false, style(2 * r, LineJoin::round, LineCap::butt)), base + kPi * r * r / 4, 0.3);
}

TEST(Stroke, MiterLimitFallsBackToBevel) {
  // A 90-degree turn has miter ratio sqrt(2): a limit of 1.3 bevels it, 1.5 keeps the miter.
  const std::vector<Vec2> line{{20, 20}, {80, 20}, {80, 90}};
  const double bevel = stroke_area(line, false, style(12, LineJoin::bevel, LineCap::butt));
  const double miter = stroke_area(line, false, style(12, LineJoin::miter, LineCap::butt));
  EXPECT_NEAR(stroke_area(line, false, style(12, LineJoin::miter, LineCap::butt, 1.3)), bevel, 1e-3);
  EXPECT_NEAR(stroke_area(line, false, style(12, LineJoin::miter, LineCap::butt, 1.5)), miter, 1e-3);
}

TEST(Stroke, SharpMiterReachesItsTip) {
  // A 60-degree spike: the miter tip lies r / sin(30 deg) = 2r beyond the vertex along the bisector.
  const double r = 4;
  const Vec2 p(60, 30);
  const std::vector<Vec2> line{p + Vec2(-40 * std::cos(kPi / 3), 40 * std::sin(kPi / 3)), p,
                               p + Vec2(40 * std::cos(kPi / 3), 40 * std::sin(kPi / 3))};
  const Path outline = stroke_path(line, false, style(2 * r, LineJoin::miter, LineCap::butt));
  double min_y = 1e9;
  for (const auto& c : outline.contours)
    for (const Vec2& q : c) min_y = std::min(min_y, q.y);
  EXPECT_NEAR(min_y, p.y - 2 * r, 1e-9);
}

TEST(Stroke, ClosedSquareIsARing) {
  const double r = 3, s = 60;
  const std::vector<Vec2> square{{30, 30}, {30 + s, 30}, {30 + s, 30 + s}, {30, 30 + s}};
  const double ring = (s + 2 * r) * (s + 2 * r) - (s - 2 * r) * (s - 2 * r);
  EXPECT_NEAR(stroke_area(square, true, style(2 * r, LineJoin::miter, LineCap::round)), ring, 0.05);
  // Open, the same points lose the closing side and gain caps instead of joins at the ends.
  EXPECT_LT(stroke_area(square, false, style(2 * r, LineJoin::miter, LineCap::butt)), ring - s);
}

TEST(Stroke, OutlinePiecesAreConsistentlyOriented) {
  const Path outline =
      stroke_path({{10, 10}, {50, 15}, {20, 40}, {60, 60}}, false, style(5, LineJoin::round, LineCap::round));
  for (const auto& c : outline.contours) {
    double a = 0;
    for (size_t i = 0; i < c.size(); ++i) a += c[i].x * c[(i + 1) % c.size()].y - c[i].y * c[(i + 1) % c.size()].x;
    EXPECT_GT(a, 0);
  }
}

TEST(Stroke, DegenerateInput) {
  EXPECT_TRUE(stroke_path({}, false, style(3, LineJoin::miter, LineCap::butt)).contours.empty());
  EXPECT_TRUE(stroke_path({{5, 5}, {5, 5}}, false, style(3, LineJoin::miter, LineCap::butt)).contours.empty());
  EXPECT_TRUE(stroke_path({{5, 5}, {9, 5}}, false, style(0, LineJoin::miter, LineCap::butt)).contours.empty());
  // A zero-length subpath with round caps is a dot of the stroke's diameter.
  EXPECT_NEAR(stroke_area({{30, 30}, {30, 30}}, false, style(10, LineJoin::miter, LineCap::round), 64), kPi * 25, 0.3);
  // A reversal with round joins covers the half disk beyond the turning point.
  EXPECT_NEAR(stroke_area({{20, 30}, {50, 30}, {20, 30}}, false, style(10, LineJoin::round, LineCap::butt), 64),
              30 * 10 + kPi * 25 / 2, 0.3);
}

}  // namespace
}  // namespace tessera
