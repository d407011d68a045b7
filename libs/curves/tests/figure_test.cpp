#include "tessera/curves/figure.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

using ::testing::HasSubstr;

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Figure, ShowsHullPolygonConstructionAndHalves) {
  CurveFigure f;
  f.width = 300;
  f.height = 200;
  f.curves = {cubic(Vec2(20, 180), Vec2(60, 20), Vec2(240, 20), Vec2(280, 180))};
  f.construction = 0.5;
  f.show_split = true;
  const std::string svg = curve_figure_svg(f);
  EXPECT_THAT(svg, HasSubstr("viewBox=\"0 0 300 200\""));
  EXPECT_EQ(count(svg, "<polygon"), 1u);  // the hull
  // Control polygon, two construction levels, two halves and the curve.
  EXPECT_EQ(count(svg, "<polyline"), 6u);
  // Q(1/2) of this cubic is (P1 + 3 P2 + 3 P3 + P4) / 8 = (150, 60).
  EXPECT_THAT(svg, HasSubstr("cx=\"150.000\" cy=\"60.000\" r=\"5\""));
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

TEST(Figure, StepsDrawTheCurveByForwardDifferences) {
  CurveFigure f;
  f.curves = {quadratic(Vec2(0, 0), Vec2(100, 200), Vec2(200, 0))};
  f.show_hull = f.show_control_polygon = false;
  f.steps = 4;
  EXPECT_THAT(curve_figure_svg(f), HasSubstr("points=\"0.000,0.000 50.000,75.000 100.000,100.000 150.000,75.000 "
                                             "200.000,0.000\""));
}

TEST(Figure, RejectsBadInput) {
  CurveFigure f;
  f.curves = {Bezier2{}};
  EXPECT_THROW(curve_figure_svg(f), InvalidInput);
  f.curves = {quadratic(Vec2(0, 0), Vec2(1, 1), Vec2(2, 0))};
  f.construction = 1.5;
  EXPECT_THROW(curve_figure_svg(f), InvalidInput);
  f.construction.reset();
  f.width = 0;
  EXPECT_THROW(curve_figure_svg(f), InvalidInput);
}

}  // namespace
}  // namespace tessera
