// The grammars of SVG attribute values (svg_syntax.cpp): path data with arcs, transform lists and colors, with the
// character each error names.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "svg_test_util.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera {
namespace {

using namespace test;
using ::testing::HasSubstr;
using Kind = SvgSegment::Kind;

// ---- path data
// -------------------------------------------------------------------------------------------------------

TEST(SvgPathData, CompactNumbers) {
  const auto p = parse_svg_path_data("M1.5.5L-1-2l1e-3.5.25-1E+1");
  ASSERT_EQ(p.size(), 1u);
  expect_near(p[0].start, {1.5, 0.5});
  ASSERT_EQ(p[0].segments.size(), 3u);
  expect_near(p[0].segments[0].end, {-1, -2});
  expect_near(p[0].segments[1].end, {-1 + 1e-3, -1.5});
  expect_near(p[0].segments[2].end, {-1 + 1e-3 + 0.25, -1.5 - 10});
}

TEST(SvgPathData, RelativeEqualsAbsoluteAndImplicitRepeats) {
  const auto abs = parse_svg_path_data("M10 10 L20 10 L20 20 L10 20 Z");
  const auto rel = parse_svg_path_data("m10,10 l10,0 0,10 -10 0z");
  const auto hv = parse_svg_path_data("M10 10 H20 V20 h-10 z");
  const auto implicit = parse_svg_path_data("M10 10 20 10 20 20 10 20z");  // pairs after M are linetos
  for (const auto* p : {&rel, &hv, &implicit}) {
    ASSERT_EQ(p->size(), 1u);
    EXPECT_TRUE((*p)[0].closed);
    expect_near((*p)[0].start, abs[0].start);
    ASSERT_EQ((*p)[0].segments.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ((*p)[0].segments[i].kind, Kind::line);
      expect_near((*p)[0].segments[i].end, abs[0].segments[i].end);
    }
  }
}

TEST(SvgPathData, SmoothCurvesReflectTheLastControlPoint) {
  const auto c = parse_svg_path_data("M0 0 C1 2 3 4 5 6 S9 10 11 12 s1 1 2 2");
  ASSERT_EQ(c[0].segments.size(), 3u);
  expect_near(c[0].segments[1].c1, {7, 8});  // 2 (5,6) - (3,4)
  expect_near(c[0].segments[1].c2, {9, 10});
  expect_near(c[0].segments[2].c1, {13, 14});  // 2 (11,12) - (9,10)
  expect_near(c[0].segments[2].c2, {12, 13});
  expect_near(c[0].segments[2].end, {13, 14});
  const auto q = parse_svg_path_data("M0 0 Q1 1 2 0 T4 0 t2 0");
  ASSERT_EQ(q[0].segments.size(), 3u);
  EXPECT_EQ(q[0].segments[1].kind, Kind::quadratic);
  expect_near(q[0].segments[1].c1, {3, -1});
  expect_near(q[0].segments[2].c1, {5, 1});
  // S and T after another command use the current point as the first control point.
  const auto s = parse_svg_path_data("M1 1 L2 2 S3 3 4 4 M0 0 T5 5");
  expect_near(s[0].segments[1].c1, {2, 2});
  expect_near(s[1].segments[0].c1, {0, 0});
}

TEST(SvgPathData, ClosePathThenDrawingStartsAtTheSubpathStart) {
  const auto p = parse_svg_path_data("M1 1 L5 1 L5 5 Z l0 8");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_TRUE(p[0].closed);
  EXPECT_FALSE(p[1].closed);
  expect_near(p[1].start, {1, 1});
  expect_near(p[1].segments[0].end, {1, 9});
  EXPECT_TRUE(parse_svg_path_data(" \n ").empty());
}

TEST(SvgPathData, ArcsFollowTheEndpointToCenterConversion) {
  // sweep-flag 1 turns toward positive angles, which is clockwise on screen (y down): the top half.
  const auto half = parse_svg_path_data("M0 0 A10 10 0 0 1 20 0");
  expect_on_ellipse(half, {10, 0}, 10, 10, 0);
  expect_near(half[0].segments.back().end, {20, 0}, 0);
  const auto lines = flatten_svg_subpaths(half, Mat3(1.0), 1e-3);
  double min_y = 0;
  for (const Vec2& q : lines[0].points) min_y = std::min(min_y, q.y);
  EXPECT_NEAR(min_y, -10, 1e-3);
  // Radii too small to reach are scaled up (F.6.6): the same half circle.
  expect_on_ellipse(parse_svg_path_data("M0 0 a1 1 0 0 1 20 0"), {10, 0}, 10, 10, 0);
  // Large arc, compact flags ("10" is large-arc 1, sweep 0): three quarters of the circle centered at (0, 10).
  expect_on_ellipse(parse_svg_path_data("M0 0A10 10 0 10 10 10"), {0, 10}, 10, 10, 0);
  // A rotated ellipse: rx 20, ry 10 at 30 degrees, centered at the origin, from its +u end to its +v end.
  const double phi = radians(30);
  const Vec2 a(20 * std::cos(phi), 20 * std::sin(phi)), b(-10 * std::sin(phi), 10 * std::cos(phi));
  expect_on_ellipse(parse_svg_path_data(fmt::format("M{} {} A20 10 30 0 1 {} {}", a.x, a.y, b.x, b.y)), {0, 0}, 20, 10,
                    phi);
  // Degenerate arcs: a zero radius is a line, equal endpoints draw nothing.
  const auto line = parse_svg_path_data("M0 0 A0 5 0 0 1 10 0 A5 5 0 0 1 10 0");
  ASSERT_EQ(line[0].segments.size(), 1u);
  EXPECT_EQ(line[0].segments[0].kind, Kind::line);
  // Finite numbers whose arc overflows (an endpoint 1e300 away from a radius 1e10 arc: fuzz_svg found the NaN piece
  // count, undefined behaviour) draw the line to the endpoint.
  const auto huge = parse_svg_path_data("M0 0 a1e10 1e10 0 1 1 1e-9 1e300");
  ASSERT_EQ(huge[0].segments.size(), 1u);
  EXPECT_EQ(huge[0].segments[0].kind, Kind::line);
  EXPECT_EQ(huge[0].segments[0].end, Vec2(1e-9, 1e300));
}

TEST(SvgPathData, ErrorsNameTheCharacterAndWhatWasExpected) {
  EXPECT_THAT(error_of([] { parse_svg_path_data("L1 2"); }),
              HasSubstr("character 1: path data must start with a moveto ('M' or 'm'), got 'L'"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M 1"); }),
              HasSubstr("character 4: expected a number for 'M' (2 per segment), got the end of the value"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M1 2 K3 4"); }),
              HasSubstr("character 6: expected a path command (M L H V C S Q T A Z or lower case), got 'K'"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M1 2 L3 4,"); }), HasSubstr("expected a number for 'L'"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M1 2 C1 2 3 4 5"); }), HasSubstr("(6 per segment)"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M0 0 A1 1 0 2 0 3 3"); }),
              HasSubstr("expected an arc flag '0' or '1', got '2'"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M0 0 L1e999 0"); }), HasSubstr("number '1e999' is out of range"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M0 0 Z 5"); }), HasSubstr("expected a path command"));
  EXPECT_THAT(error_of([] { parse_svg_path_data("M . 1"); }), HasSubstr("got '.'"));
}

// ---- transforms and colors
// ---------------------------------------------------------------------------------------------

TEST(SvgTransform, ListsComposeAsTheMatrixStack) {
  expect_matrix_near(parse_svg_transform("translate(10,20) rotate(30) scale(2 3)"),
                     translate2d(10, 20) * rotate2d(radians(30)) * scale2d(2, 3));
  expect_matrix_near(parse_svg_transform("rotate(45 10 20)"), rotate2d_about(radians(45), 10, 20));
  expect_matrix_near(parse_svg_transform("rotate(45 10 20)"),
                     translate2d(10, 20) * rotate2d(radians(45)) * translate2d(-10, -20));
  expect_matrix_near(parse_svg_transform("skewX(30)"), shear2d(std::tan(radians(30)), 0));
  expect_matrix_near(parse_svg_transform("skewY(-20)"), shear2d(0, std::tan(radians(-20))));
  expect_matrix_near(parse_svg_transform("translate(5)"), translate2d(5, 0));
  expect_matrix_near(parse_svg_transform("scale(2)"), scale2d(2, 2));
  expect_matrix_near(parse_svg_transform(" "), Mat3(1.0));
  // matrix(a b c d e f) is [a c e; b d f; 0 0 1]; transform lists may be separated by commas.
  const Mat3 m = parse_svg_transform("matrix(1 2 3 4 5 6), translate(1 1)");
  expect_near(transform_point(m, {0, 0}), {1 + 3 + 5, 2 + 4 + 6});
  expect_near(transform_point(m, {1, 0}), {2 + 3 + 5, 4 + 4 + 6});
  // SVG's rotate turns +x toward +y: clockwise on a y-down screen.
  expect_near(transform_point(parse_svg_transform("rotate(90)"), {1, 0}), {0, 1}, 1e-15);
}

TEST(SvgTransform, Errors) {
  EXPECT_THAT(error_of([] { parse_svg_transform("rotate(1 2)"); }),
              HasSubstr("character 1: rotate() takes 1 or 3 numbers, got 2"));
  EXPECT_THAT(error_of([] { parse_svg_transform("translate(1) spin(3)"); }),
              HasSubstr("character 14: unknown transform function 'spin'"));
  EXPECT_THAT(error_of([] { parse_svg_transform("scale 2"); }), HasSubstr("expected '(' after 'scale'"));
  EXPECT_THAT(error_of([] { parse_svg_transform("translate(1"); }), HasSubstr("got the end of the value"));
  EXPECT_THAT(error_of([] { parse_svg_transform("matrix(1 2 3 4 5)"); }), HasSubstr("takes 6 numbers, got 5"));
}

TEST(SvgColor, Syntaxes) {
  expect_color(parse_svg_color("#f80"), 1, 0x88 / 255.f, 0);
  expect_color(parse_svg_color("#FF8000"), 1, 0x80 / 255.f, 0);
  expect_color(parse_svg_color(" rgb(255, 128 ,0) "), 1, 128 / 255.f, 0);
  expect_color(parse_svg_color("rgb(100%,50%,0%)"), 1, 0.5f, 0);
  expect_color(parse_svg_color("rgb(300,-5,0)"), 1, 0, 0);
  expect_color(parse_svg_color("rgba(0,0,255,0.5)"), 0, 0, 1, 0.5f);
  expect_color(parse_svg_color("red"), 1, 0, 0);
  expect_color(parse_svg_color("Lime"), 0, 1, 0);
  expect_color(parse_svg_color("green"), 0, 128 / 255.f, 0);
  expect_color(parse_svg_color("gray"), 128 / 255.f, 128 / 255.f, 128 / 255.f);
  expect_color(parse_svg_color("grey"), 128 / 255.f, 128 / 255.f, 128 / 255.f);
  expect_color(parse_svg_color("orange"), 1, 165 / 255.f, 0);
  expect_color(parse_svg_color("aliceblue"), 240 / 255.f, 248 / 255.f, 1);
  expect_color(parse_svg_color("yellowgreen"), 154 / 255.f, 205 / 255.f, 50 / 255.f);
  EXPECT_THAT(error_of([] { parse_svg_color("#12"); }), HasSubstr("expected a color #rgb or #rrggbb, got '#12'"));
  EXPECT_THAT(error_of([] { parse_svg_color("rgb(1,2)"); }), HasSubstr("expected ','"));
  EXPECT_THAT(error_of([] { parse_svg_color("bleu"); }), HasSubstr("unknown color 'bleu'"));
  // The CLI's --color values reach these messages: control bytes are escaped (printable()).
  EXPECT_THAT(error_of([] { parse_svg_color("#\x1b[2J"); }), HasSubstr("got '#\\x1b[2J'"));
  EXPECT_THAT(error_of([] { parse_svg_color("re\x1b[2Jd"); }), HasSubstr("unknown color 're\\x1b[2Jd'"));
  EXPECT_THAT(error_of([] { parse_svg_color("red blue"); }), HasSubstr("unexpected 'blue' after the value"));
  // What follows the value is quoted through printable(): escaped, and cut after 60 characters.
  EXPECT_THAT(error_of([] { parse_svg_color("#abc\x1b]0;x\x07"); }), HasSubstr("unexpected '\\x1b]0;x\\x07'"));
  EXPECT_THAT(error_of([] { parse_svg_color("red " + std::string(100000, 'x')); }), HasSubstr("... (100000 bytes)"));
}

}  // namespace
}  // namespace tessera
