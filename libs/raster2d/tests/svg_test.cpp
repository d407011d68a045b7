// The SVG front end: value grammars, document parsing (styles, inheritance, transforms, viewBox), error messages on
// malformed input, robustness on garbage, the pixel-center rule against a point-in-polygon oracle, and antialiased
// output against rsvg-convert (librsvg) when it is installed.
#include "tessera/raster2d/svg.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "tessera/core/error.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/transform.hpp"

namespace tessera {
namespace {

using ::testing::HasSubstr;
using Kind = SvgSegment::Kind;

// ---- helpers ---------------------------------------------------------------------------------------------------------

void expect_near(const Vec2& a, const Vec2& b, double eps = 1e-12) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
}

void expect_matrix_near(const Mat3& a, const Mat3& b, double eps = 1e-12) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], eps) << "column " << c << " row " << r;
}

void expect_color(const Vec4f& c, float r, float g, float b, float a = 1) {
  EXPECT_NEAR(c.x, r, 1e-6);
  EXPECT_NEAR(c.y, g, 1e-6);
  EXPECT_NEAR(c.z, b, 1e-6);
  EXPECT_NEAR(c.w, a, 1e-6);
}

// The message of the InvalidInput that f throws (fails the test when it throws nothing or something else).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected InvalidInput";
  return {};
}

std::string svg_error(std::string_view text) { return error_of([&] { parse_svg(text, "t.svg"); }); }

SvgDocument parse(std::string_view body, std::string_view root = R"~(width="100" height="100")~") {
  return parse_svg(fmt::format(R"~(<svg xmlns="http://www.w3.org/2000/svg" {}>{}</svg>)~", root, body), "t.svg");
}

// ---- path data -------------------------------------------------------------------------------------------------------

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
      EXPECT_EQ((*p)[0].segments[i].kind, Kind::Line);
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
  EXPECT_EQ(q[0].segments[1].kind, Kind::Quadratic);
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

// Every flattened point of an arc lies on its ellipse.
void expect_on_ellipse(const std::vector<SvgSubpath>& p, const Vec2& center, double rx, double ry, double phi) {
  const auto lines = flatten_svg_subpaths(p, Mat3(1.0), 1e-4);
  ASSERT_EQ(lines.size(), 1u);
  for (const Vec2& q : lines[0].points) {
    const Vec2 d = q - center;
    const double u = (std::cos(phi) * d.x + std::sin(phi) * d.y) / rx;
    const double v = (-std::sin(phi) * d.x + std::cos(phi) * d.y) / ry;
    EXPECT_NEAR(u * u + v * v, 1.0, 1e-4) << q.x << "," << q.y;
  }
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
  EXPECT_EQ(line[0].segments[0].kind, Kind::Line);
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

// ---- transforms and colors ---------------------------------------------------------------------------------------------

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
}

// ---- documents ---------------------------------------------------------------------------------------------------------

TEST(SvgDocument, StyleAttributeBeatsPresentationAttributes) {
  const auto d = parse(R"~(<rect width="5" height="5" fill="red" style="fill: #0000ff ;stroke:lime;stroke-width:2px"
                               stroke="black" stroke-width="7"/>)~");
  ASSERT_EQ(d.shapes.size(), 1u);
  const SvgStyle& s = d.shapes[0].style;
  expect_color(*s.fill, 0, 0, 1);
  expect_color(*s.stroke, 0, 1, 0);
  EXPECT_EQ(s.stroke_style.width, 2);
}

TEST(SvgDocument, InheritanceThroughGroups) {
  const auto d = parse(R"~(
    <g fill="green" stroke="red" stroke-width="3" fill-rule="evenodd" opacity="0.5" stroke-linejoin="round">
      <g fill-opacity="0.25" style="stroke-linecap: square" color="#00f">
        <rect width="1" height="1" opacity="0.5"/>
        <circle r="2" fill="none" stroke-width="1" stroke="currentColor"/>
        <rect width="1" height="1" fill="inherit" fill-rule="nonzero" visibility="hidden"/>
      </g>
    </g>
    <rect width="1" height="1" display="none"/>
    <g display="none"><rect width="1" height="1"/></g>
    <rect width="1" height="1" stroke-miterlimit="9" stroke-linejoin="bevel"/>)~");
  ASSERT_EQ(d.shapes.size(), 3u);
  const SvgStyle& a = d.shapes[0].style;
  expect_color(*a.fill, 0, 128 / 255.f, 0);
  expect_color(*a.stroke, 1, 0, 0);
  EXPECT_EQ(a.stroke_style.width, 3);
  EXPECT_EQ(a.fill_rule, FillRule::EvenOdd);
  EXPECT_EQ(a.stroke_style.join, LineJoin::Round);
  EXPECT_EQ(a.stroke_style.cap, LineCap::Square);
  EXPECT_FLOAT_EQ(a.fill_opacity, 0.25f);
  EXPECT_FLOAT_EQ(a.opacity, 0.25f);  // group opacity multiplied down
  const SvgStyle& b = d.shapes[1].style;
  EXPECT_EQ(d.shapes[1].element, "circle");
  EXPECT_FALSE(b.fill.has_value());
  expect_color(*b.stroke, 0, 0, 1);  // currentColor
  EXPECT_EQ(b.stroke_style.width, 1);
  EXPECT_FLOAT_EQ(b.opacity, 0.5f);
  // Outside the groups the defaults hold again.
  const SvgStyle& c = d.shapes[2].style;
  expect_color(*c.fill, 0, 0, 0);
  EXPECT_FALSE(c.stroke.has_value());
  EXPECT_EQ(c.fill_rule, FillRule::NonZero);
  EXPECT_EQ(c.stroke_style.miter_limit, 9);
  EXPECT_EQ(c.stroke_style.join, LineJoin::Bevel);
  EXPECT_EQ(d.shapes[2].line, 11);
}

TEST(SvgDocument, TransformsComposeDownTheTree) {
  const auto d = parse(R"~(<g transform="translate(10 20)"><g transform="rotate(30) scale(2)">
      <rect width="1" height="1" transform="skewX(10)"/></g><circle r="1"/></g>)~");
  ASSERT_EQ(d.shapes.size(), 2u);
  expect_matrix_near(d.shapes[0].transform,
                     translate2d(10, 20) * rotate2d(radians(30)) * scale2d(2, 2) * shear2d(std::tan(radians(10)), 0));
  expect_matrix_near(d.shapes[1].transform, translate2d(10, 20));
}

TEST(SvgDocument, ShapesBecomeSubpaths) {
  const auto d = parse(R"~(<rect x="1" y="2" width="10" height="6"/><rect x="0" y="0" width="10" height="6" rx="2"/>
      <circle cx="5" cy="5" r="3"/><ellipse cx="5" cy="5" rx="3" ry="2"/><line x1="1" y1="2" x2="3" y2="4"/>
      <polyline points="0,0 1,1 2,0"/><polygon points="0 0 1 1 2 0"/><rect width="0" height="5"/><circle r="0"/>)~");
  ASSERT_EQ(d.shapes.size(), 7u);
  const auto& rect = d.shapes[0].subpaths;
  ASSERT_EQ(rect.size(), 1u);
  EXPECT_TRUE(rect[0].closed);
  expect_near(rect[0].start, {1, 2});
  expect_near(rect[0].segments[1].end, {11, 8});
  const auto rounded = flatten_svg_subpaths(d.shapes[1].subpaths, Mat3(1.0), 1e-3)[0].points;
  for (const Vec2& p : rounded) {  // the corners are quarter circles of radius 2 (ry takes rx's value)
    const Vec2 c(std::clamp(p.x, 2.0, 8.0), std::clamp(p.y, 2.0, 4.0));
    EXPECT_NEAR(glm::length(p - c), 2, 1e-3);
  }
  expect_on_ellipse(d.shapes[2].subpaths, {5, 5}, 3, 3, 0);
  expect_on_ellipse(d.shapes[3].subpaths, {5, 5}, 3, 2, 0);
  EXPECT_FALSE(d.shapes[4].subpaths[0].closed);
  EXPECT_FALSE(d.shapes[5].subpaths[0].closed);
  EXPECT_TRUE(d.shapes[6].subpaths[0].closed);
  EXPECT_EQ(d.shapes[6].subpaths[0].segments.size(), 2u);
}

TEST(SvgDocument, ViewBoxMapping) {
  const auto meet = parse("", R"~(width="200" height="100" viewBox="0 0 50 50")~");
  EXPECT_EQ(*meet.width, 200);
  const Mat3 m = svg_viewport_transform(meet, 200, 100);  // scale 2, centered horizontally
  expect_near(transform_point(m, {0, 0}), {50, 0});
  expect_near(transform_point(m, {50, 50}), {150, 100});
  const auto slice = parse("", R"~(width="200" height="100" viewBox="10 10 50 50" preserveAspectRatio="xMinYMax slice")~");
  const Mat3 s = svg_viewport_transform(slice, 200, 100);  // scale 4, bottom aligned
  expect_near(transform_point(s, {10, 60}), {0, 100});
  expect_near(transform_point(s, {60, 10}), {200, -100});
  const auto none = parse("", R"~(width="200" height="100" viewBox="0 0 50 50" preserveAspectRatio="none")~");
  expect_near(transform_point(svg_viewport_transform(none, 200, 100), {50, 50}), {200, 100});
  // A different output size scales the whole viewport (centered, aspect kept); without a viewBox the same holds.
  expect_near(transform_point(svg_viewport_transform(meet, 400, 400), {50, 50}), {300, 300});
  const auto plain = parse("", R"~(width="20" height="10")~");
  expect_near(transform_point(svg_viewport_transform(plain, 20, 10), {3, 4}), {3, 4});
  expect_near(transform_point(svg_viewport_transform(plain, 40, 20), {3, 4}), {6, 8});
  // Output sizes: the root's, the viewBox's when width/height are missing, one side derived from the other.
  EXPECT_EQ(svg_output_size(meet, {}).width, 200);
  EXPECT_EQ(svg_output_size(parse("", R"~(viewBox="0 0 30.5 12")~"), {}).width, 31);
  SvgRenderOptions half;
  half.width = 100;
  EXPECT_EQ(svg_output_size(meet, half).height, 50);
  EXPECT_THAT(error_of([] { svg_output_size(parse("", ""), {}); }), HasSubstr("the SVG has no size"));
}

TEST(SvgDocument, UnsupportedContentIsCountedOnce) {
  const auto d = parse(R"~(<title>t</title><desc>d</desc>
      <text>a</text><text>b</text><defs><linearGradient id="g"/></defs><text>c</text>
      <rect width="1" height="1" fill="url(#g) red" stroke-dasharray="1 2"/><rect width="1" height="1" fill="url(#g)"/>
      <circle r="1" clip-path="none"><animate/></circle>)~");
  ASSERT_EQ(d.warnings.size(), 3u);
  EXPECT_EQ(d.warnings[0], "unsupported SVG elements ignored: text (3), defs (1), animate (1)");
  EXPECT_EQ(d.warnings[1], "unsupported SVG attributes ignored: stroke-dasharray (1)");
  EXPECT_EQ(d.warnings[2], "unsupported paint servers (url(...)) replaced by their fallback color or none: url(#g) (2)");
  ASSERT_EQ(d.shapes.size(), 3u);
  expect_color(*d.shapes[0].style.fill, 1, 0, 0);
  EXPECT_FALSE(d.shapes[1].style.fill.has_value());
}

TEST(SvgDocument, XmlFeatures) {
  const auto d = parse_svg(
      "\xef\xbb\xbf<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" \"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\" [\n"
      "  <!ENTITY x \"<>\">\n]>\n<!-- a comment -->\n"
      "<svg width='10' height=\"10\"><![CDATA[ <rect/> ]]><g><!-- <rect/> --></g>\n"
      "<path d='M&#48; 0 L&#x35; 5 5 0' fill='&#x72;&#101;d' stroke=\"rgb(0,0,0)\" data-x=\"&lt;&amp;&gt;&quot;&apos;\"/>"
      "</svg>\n<!-- trailing -->\n",
      "t.svg");
  ASSERT_EQ(d.shapes.size(), 1u);
  expect_near(d.shapes[0].subpaths[0].segments[0].end, {5, 5});
  expect_color(*d.shapes[0].style.fill, 1, 0, 0);
}

// ---- error messages -----------------------------------------------------------------------------------------------------

TEST(SvgErrors, MalformedDocumentsNameLineColumnAndWhatWasExpected) {
  EXPECT_EQ(svg_error("<svg>\n  <g>\n</svg>"), "t.svg:3:1: expected </g> to close <g> from line 2, got </svg>");
  EXPECT_EQ(svg_error("<svg>\n<rect x='1'"),
            "t.svg:2:12: unexpected end of file inside the <rect> tag (expected '>' or '/>')");
  EXPECT_EQ(svg_error("<svg>\n<g>\n"), "t.svg:3:1: unexpected end of file: expected </g> to close <g> from line 2");
  EXPECT_EQ(svg_error("<svg><rect x=\"1x\"/></svg>"),
            "t.svg:1:16: attribute 'x' of <rect>: unit 'x' is not supported (lengths are px or unitless)");
  EXPECT_EQ(svg_error("<svg><rect width='2mm'/></svg>"),
            "t.svg:1:20: attribute 'width' of <rect>: unit 'mm' is not supported (lengths are px or unitless)");
  EXPECT_EQ(svg_error("<svg>\n  <path d=\"M 0 0 L 5 5 K\"/></svg>"),
            "t.svg:2:24: attribute 'd' of <path>: expected a path command (M L H V C S Q T A Z or lower case), got 'K'");
  EXPECT_EQ(svg_error("<svg><rect style='fill: red; stroke: #12'/></svg>"),
            "t.svg:1:38: property 'stroke' in style of <rect>: expected a color #rgb or #rrggbb, got '#12'");
  EXPECT_EQ(svg_error("<svg><rect style='fill red'/></svg>"),
            "t.svg:1:19: style of <rect>: expected 'property: value', got 'fill red'");
  EXPECT_EQ(svg_error("<svg><g transform='rotate(1,2)'/></svg>"),
            "t.svg:1:20: attribute 'transform' of <g>: rotate() takes 1 or 3 numbers, got 2");
  EXPECT_EQ(svg_error("<svg><rect width='-3'/></svg>"),
            "t.svg:1:19: attribute 'width' of <rect> must not be negative, got -3");
  EXPECT_EQ(svg_error("<svg><polygon points='1 2 3'/></svg>"),
            "t.svg:1:23: attribute 'points' of <polygon>: expected pairs of coordinates, got 3 numbers");
  EXPECT_EQ(svg_error("<svg><rect fill-rule='odd'/></svg>"),
            "t.svg:1:23: attribute 'fill-rule' of <rect>: expected one of nonzero, evenodd, got 'odd'");
  EXPECT_EQ(svg_error("<svg viewBox='0 0 10'/>"),
            "t.svg:1:15: attribute 'viewBox' of <svg>: expected 4 numbers (min-x min-y width height), got 3");
  EXPECT_EQ(svg_error("<html/>"), "t.svg:1:1: expected <svg> as the root element, got <html>");
  EXPECT_EQ(svg_error(""), "t.svg:1:1: no root element: expected <svg>");
  EXPECT_EQ(svg_error("hello <svg/>"), "t.svg:1:1: text before the root element");
  EXPECT_EQ(svg_error("<svg/><svg/>"), "t.svg:1:7: content after the end of the root element");
  EXPECT_EQ(svg_error("<svg a='1' a='2'/>"), "t.svg:1:12: duplicate attribute 'a'");
  EXPECT_EQ(svg_error("<svg a=1/>"), "t.svg:1:8: expected a quoted value for attribute 'a'");
  EXPECT_EQ(svg_error("<svg a='1'b='2'/>"), "t.svg:1:11: expected white space, '>' or '/>' in the <svg> tag, got 'b'");
  EXPECT_EQ(svg_error("<svg a='x < y'/>"), "t.svg:1:11: '<' in the value of attribute 'a' (write &lt;)");
  EXPECT_EQ(svg_error("<svg a='&nbsp;'/>"),
            "t.svg:1:9: unknown entity '&nbsp;' (XML knows &amp; &lt; &gt; &quot; &apos; and &#N;)");
  EXPECT_EQ(svg_error("<svg a='&#0;'/>"), "t.svg:1:9: invalid character reference '&#0;'");
  EXPECT_EQ(svg_error("<svg>a & b</svg>"),
            "t.svg:1:8: expected an entity such as '&amp;' (an '&' must be written '&amp;')");
  EXPECT_EQ(svg_error("<svg><!-- never closed </svg>"), "t.svg:1:6: unterminated comment (expected '-->')");
  EXPECT_EQ(svg_error("<svg></g>"), "t.svg:1:6: expected </svg> to close <svg> from line 1, got </g>");
  EXPECT_EQ(svg_error("<svg>< rect/></svg>"), "t.svg:1:7: expected an element name after '<', got ' '");
  EXPECT_EQ(svg_error("<svg a='1"), "t.svg:1:8: unterminated value of attribute 'a' (expected ')");
  // Entities shift columns, so errors in such values point at the value's start.
  EXPECT_EQ(svg_error("<svg><path d='M&#48; 0 L'/></svg>"),
            "t.svg:1:15: attribute 'd' of <path>: expected a number for 'L' (2 per segment), got the end of the value");
}

// Garbage and mutated documents either parse or throw tessera::Error; rendering what parses never crashes.
TEST(SvgErrors, NoCrashOnGarbage) {
  const std::string seed = R"~(<svg width="24" height="16" viewBox="0 0 12 8"><g transform="rotate(10 6 4) skewX(5)"
    style="fill:#f80;stroke:rgb(10%,20%,30%);stroke-width:0.5"><path d="M1 1c2-1 4 1 6 0s3 2 3 4q-2 2-4 0t-4 0a3 2 15 1 0 2-2z"/>
    <rect x="1" y="1" width="5" height="3" rx="1" opacity=".5"/><polyline points="0,0 3,4 6,1" stroke-linejoin="round"/>
    <circle cx="6" cy="4" r="2" fill-rule="evenodd"/></g></svg>)~";
  std::mt19937 rng(12345);
  SvgRenderOptions tiny;
  tiny.width = 8;
  tiny.height = 8;
  const std::string alphabet = "<>/=\"' &#;x0123456789.-eMmLlCcAaZz(),gsvr";
  for (int i = 0; i < 3000; ++i) {
    std::string text = seed;
    const int edits = 1 + int(rng() % 4);
    for (int k = 0; k < edits && !text.empty(); ++k) {
      const size_t pos = rng() % text.size();
      switch (rng() % 4) {
        case 0: text[pos] = char(rng() % 256); break;
        case 1: text[pos] = alphabet[rng() % alphabet.size()]; break;
        case 2: text.erase(pos, 1 + rng() % 8); break;
        default: text.resize(std::max<size_t>(pos, 1)); break;
      }
    }
    try {
      render_svg(parse_svg(text, "fuzz.svg"), tiny);
    } catch (const Error&) {
    }
  }
  for (int i = 0; i < 300; ++i) {
    std::string bytes(rng() % 200, '\0');
    for (char& c : bytes) c = char(rng() % 256);
    EXPECT_THROW(parse_svg(bytes, "garbage"), Error);
  }
}

TEST(SvgErrors, OverflowingTransformsAndSizes) {
  const auto d = parse(R"~(<g transform="scale(1e300)"><rect width="1e300" height="1" /></g>)~");
  EXPECT_THAT(error_of([&] { render_svg(d, {}); }), HasSubstr("t.svg:1: <rect>: coordinates overflow"));
  SvgRenderOptions bad;
  bad.width = 70000;
  bad.height = 5;
  EXPECT_THAT(error_of([&] { render_svg(d, bad); }), HasSubstr("output size 70000x5 is invalid"));
}

// ---- rendering: the pixel-center rule ------------------------------------------------------------------------------------

// Winding number of the pixel center p around the (implicitly closed) polylines, counting a crossing when the edge is
// strictly right of p and spans [y0, y1): centers on left and top edges are inside, on right and bottom edges outside.
int winding(const std::vector<SvgPolyline>& lines, const Vec2& p) {
  int w = 0;
  for (const SvgPolyline& line : lines) {
    const auto& pts = line.points;
    for (size_t i = 0; i < pts.size(); ++i) {
      const Vec2 a = pts[i], b = pts[(i + 1) % pts.size()];
      if ((a.y <= p.y) == (b.y <= p.y)) continue;
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (x > p.x) w += b.y > a.y ? 1 : -1;
    }
  }
  return w;
}

// The shapes avoid pixel centers exactly on an edge: the scanline fill steps x by the notes' increments, whose
// rounding decides such ties (its own tests cover them).
TEST(SvgRender, WithoutAntialiasingCoverageIsThePixelCenterRule) {
  const auto d = parse(R"~(
    <rect x="3" y="4" width="30" height="20" fill-rule="evenodd"/>
    <g transform="translate(60 40) rotate(17) scale(1.3 0.7)">
      <path d="M-30-20 C10-60 40 10 20 20 S-20 60-30 10 Q-60 0-30-20z M-10-5 L10-5 10 5-10 5z" fill-rule="evenodd"/>
      <path d="M-30-20 C10-60 40 10 20 20 S-20 60-30 10 Q-60 0-30-20z M-10-5 L10-5 10 5-10 5z"/>
    </g>
    <polygon points="50.3,5 61.3,38 33.3,17 67.3,17 39.3,38" fill-rule="nonzero"/>
    <polygon points="50.3,5 61.3,38 33.3,17 67.3,17 39.3,38" fill-rule="evenodd"/>
    <ellipse cx="20" cy="70" rx="18.3" ry="9.1" transform="skewX(-20)"/>
    <path d="M90 80 A25 12 30 1 1 140 70 L300 -200 L-300 90 C-500 -400 500 900 90 80z"/>)~",
                       R"~(width="120" height="96")~");
  ASSERT_EQ(d.shapes.size(), 7u);
  SvgRenderOptions options;
  options.antialias = false;
  const Mat3 view = svg_viewport_transform(d, 120, 96);
  for (const SvgShape& shape : d.shapes) {
    SvgDocument one = d;
    one.shapes = {shape};
    one.shapes[0].style.fill = Vec4f(1, 1, 1, 1);
    const ImageRGBA image = render_svg(one, options);
    const auto lines = flatten_svg_subpaths(shape.subpaths, view * shape.transform, options.tolerance);
    int mismatches = 0, inside_count = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        const int w = winding(lines, {x + 0.5, y + 0.5});
        const bool inside = shape.style.fill_rule == FillRule::NonZero ? w != 0 : (w & 1) != 0;
        inside_count += inside;
        if (inside == (image(x, y).w == 1.0f) && (image(x, y).w == 0 || image(x, y).w == 1)) continue;
        if (++mismatches <= 5)
          ADD_FAILURE() << "pixel (" << x << ", " << y << "): winding " << w << ", alpha " << image(x, y).w;
      }
    EXPECT_EQ(mismatches, 0) << "shape at line " << shape.line;
    EXPECT_GT(inside_count, 50) << "shape at line " << shape.line;
  }
}

// ---- rendering: comparison with rsvg-convert --------------------------------------------------------------------------

struct Difference {
  double rmse = 0;        // over the RGB channels, values in [0, 1]
  double max = 0;         // largest channel difference
  double bad_pixels = 0;  // fraction of pixels with a channel off by more than 0.25
};

Difference compare(const ImageRGBA& a, const ImageRGBA& b) {
  double sum = 0, max = 0;
  size_t bad = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      double worst = 0;
      for (int c = 0; c < 3; ++c) {
        const double d = double(a(x, y)[c]) - double(b(x, y)[c]);
        sum += d * d;
        worst = std::max(worst, std::abs(d));
      }
      bad += worst > 0.25;
      max = std::max(max, worst);
    }
  const double n = double(a.width()) * a.height();
  return {std::sqrt(sum / (3 * n)), max, double(bad) / n};
}

bool have_rsvg() { return std::system("command -v rsvg-convert >/dev/null 2>&1") == 0; }

// Renders `svg` with Tessera (antialiased, on white) and with rsvg-convert at the document's size; returns both.
std::pair<ImageRGBA, ImageRGBA> render_both(const std::string& name, const std::string& svg) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "tessera_svg_test";
  std::filesystem::create_directories(dir);
  const auto in = dir / (name + ".svg"), out = dir / (name + ".rsvg.png");
  std::ofstream(in) << svg;
  const SvgDocument doc = parse_svg(svg, name);
  EXPECT_TRUE(doc.warnings.empty()) << doc.warnings[0];
  SvgRenderOptions options;
  options.background = Vec4f(1, 1, 1, 1);
  ImageRGBA ours = render_svg(doc, options);
  const std::string command = fmt::format("rsvg-convert -b white -w {} -h {} -o '{}' '{}'", ours.width(),
                                          ours.height(), out.string(), in.string());
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  ImageRGBA theirs = read_image(out);
  if (std::getenv("TESSERA_SVG_KEEP")) write_image(dir / (name + ".tessera.png"), ours);
  return {std::move(ours), std::move(theirs)};
}

struct ReferenceCase {
  const char* name;
  const char* svg;
};

const ReferenceCase kReferenceCases[] = {
    {"shapes", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">
      <rect x="10" y="10" width="50" height="30" fill="#c33"/>
      <rect x="70.5" y="8.25" width="60" height="35" rx="12" ry="8" fill="navy"/>
      <circle cx="35" cy="80" r="25.5" fill="orange"/>
      <ellipse cx="105" cy="85" rx="40" ry="18" fill="rgb(20%, 60%, 30%)"/>
      <line x1="5" y1="115" x2="155" y2="60" stroke="purple" stroke-width="3"/>
      <polyline points="140,10 150,40 130,30 155,20" fill="none" stroke="black" stroke-width="2"/>
      <polygon points="60,60 80,95 40,95" fill="teal" stroke="#222" stroke-width="1.5"/></svg>)~"},
    {"curves", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">
      <path d="M10 60 C30 0 60 0 80 60 S130 120 150 60" fill="none" stroke="#0a4" stroke-width="4"/>
      <path d="m10 100q20-30 40 0t40 0 40 0" fill="none" stroke="#a04" stroke-width="3"/>
      <path d="M90 20 a30 15 20 1 1 40 10 z" fill="#48f" fill-opacity="0.8"/>
      <path d="M20 20h30v30h-30z M25 25l10 0 0 10-10 0z" fill="#333"/>
      <path d="M60.5 80.2c5.5-10.3 20-10 25 0s-5 20-12.5 20-17.5-10-12.5-20" fill="gold" stroke="brown"/></svg>)~"},
    {"transforms", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">
      <g transform="translate(80 60)">
        <g transform="rotate(30)"><rect x="-40" y="-10" width="80" height="20" fill="#e63"/></g>
        <g transform="rotate(-45 20 20) scale(1.5 0.8)"><circle cx="20" cy="20" r="12" fill="#36e"/></g>
        <g transform="skewX(25) translate(-60 -50)"><rect width="30" height="30" fill="#3a3"/></g>
        <g transform="matrix(0.8 0.3 -0.2 0.9 30 10) skewY(10)"><ellipse rx="15" ry="8" fill="#a3a"/></g>
        <g transform="scale(3 1)"><circle cx="-15" cy="35" r="8" fill="none" stroke="#000" stroke-width="2"/></g>
      </g></svg>)~"},
    {"opacity", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">
      <rect x="10" y="10" width="80" height="60" fill="blue"/>
      <circle cx="90" cy="60" r="40" fill="red" fill-opacity="0.5"/>
      <g opacity="0.6"><rect x="20" y="75" width="120" height="30" fill="green"/></g>
      <rect x="100" y="10" width="50" height="50" fill="yellow" stroke="black" stroke-width="6" stroke-opacity="0.3"/>
      <rect x="30" y="30" width="40" height="70" style="fill:rgb(255,0,255);opacity:0.4"/></svg>)~"},
    {"fill_rules", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">
      <polygon points="40,5 63,75 3,30 77,30 17,75" fill="#c00" fill-rule="nonzero"/>
      <polygon points="120,5 143,75 83,30 157,30 97,75" fill="#c00" fill-rule="evenodd"/>
      <path d="M10 85h60v30h-60z M20 90v20h40v-20z" fill="#06c" fill-rule="nonzero"/>
      <path d="M90 85h60v30h-60z M100 90h40v20h-40z" fill="#06c" fill-rule="nonzero"/></svg>)~"},
    {"strokes", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120" fill="none" stroke="#135">
      <polyline points="10,40 30,10 50,40" stroke-width="10" stroke-linejoin="miter" stroke-linecap="butt"/>
      <polyline points="60,40 80,10 100,40" stroke-width="10" stroke-linejoin="round" stroke-linecap="round"/>
      <polyline points="110,40 130,10 150,40" stroke-width="10" stroke-linejoin="bevel" stroke-linecap="square"/>
      <polyline points="10,70 60,60 10,50" stroke-width="6" stroke-miterlimit="2"/>
      <polyline points="70,70 120,60 70,50" stroke-width="6" stroke-miterlimit="10"/>
      <path d="M20 100 Q50 70 80 100 T140 100" stroke-width="8" stroke-linecap="round" stroke="#a50"/>
      <rect x="125" y="55" width="25" height="25" stroke-width="4" stroke-linejoin="round"/></svg>)~"},
    {"viewbox", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="100" viewBox="-10 -10 20 20"
         preserveAspectRatio="xMinYMid meet">
      <circle r="9" fill="#fc0" stroke="#000" stroke-width="0.5"/>
      <path d="M-4-3v2M4-3v2M-5 3q5 5 10 0" stroke="#000" stroke-width="1" fill="none" stroke-linecap="round"/>
    </svg>)~"},
    {"colors", R"~(<svg xmlns="http://www.w3.org/2000/svg" width="160" height="40">
      <rect x="0" width="10" height="20" fill="maroon"/><rect x="10" width="10" height="20" fill="olive"/>
      <rect x="20" width="10" height="20" fill="silver"/><rect x="30" width="10" height="20" fill="fuchsia"/>
      <rect x="40" width="10" height="20" fill="aqua"/><rect x="50" width="10" height="20" fill="darkslategrey"/>
      <rect x="60" width="10" height="20" fill="lightgray"/><rect x="70" width="10" height="20" fill="cornflowerblue"/>
      <rect x="80" width="10" height="20" fill="papayawhip"/><rect x="90" width="10" height="20" fill="darkorchid"/>
      <rect x="100" width="10" height="20" fill="DarkOrange"/><rect x="110" width="10" height="20" fill="#8f8"/>
      <rect x="120" width="10" height="20" fill="rgb(10,200,30)"/><rect x="130" width="10" height="20" fill="seagreen"/>
      <rect x="140" width="10" height="20" fill="hotpink"/><rect x="150" width="10" height="20" fill="tomato"/>
      <g color="indigo"><rect y="20" width="80" height="20" fill="currentColor"/></g>
      <rect x="80" y="20" width="80" height="20" fill="dimgrey"/></svg>)~"},
};

void expect_close_to_rsvg(const std::string& name, const std::string& svg) {
  const auto [ours, theirs] = render_both(name, svg);
  ASSERT_EQ(ours.width(), theirs.width());
  ASSERT_EQ(ours.height(), theirs.height());
  const Difference d = compare(ours, theirs);
  std::printf("[ rsvg     ] %-10s RMSE %.4f, max %.3f, pixels off by > 25%%: %.3f%%\n", name.c_str(), d.rmse, d.max,
              100 * d.bad_pixels);
  EXPECT_LT(d.rmse, 0.015) << name;
  EXPECT_LT(d.bad_pixels, 0.001) << name;
}

TEST(SvgReference, AntialiasedOutputMatchesRsvgConvert) {
  if (!have_rsvg()) GTEST_SKIP() << "rsvg-convert (Debian package librsvg2-bin) is not installed";
  for (const ReferenceCase& c : kReferenceCases) expect_close_to_rsvg(c.name, c.svg);
}

TEST(SvgReference, DemoDrawingMatchesRsvgConvert) {
  if (!have_rsvg()) GTEST_SKIP() << "rsvg-convert (Debian package librsvg2-bin) is not installed";
  std::ifstream in(std::string(TESSERA_SOURCE_DIR) + "/examples/data/tiger-lite.svg");
  ASSERT_TRUE(in) << "examples/data/tiger-lite.svg";
  expect_close_to_rsvg("tiger-lite", std::string(std::istreambuf_iterator<char>(in), {}));
}

}  // namespace
}  // namespace tessera
