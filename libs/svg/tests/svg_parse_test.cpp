// The SVG document parser (svg_parse.cpp): styles, inheritance, transforms, viewBox, unsupported content counted, error
// messages on malformed documents naming line and column, and robustness on garbage.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "svg_test_util.hpp"
#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera {
namespace {

using namespace test;
using ::testing::HasSubstr;

std::string svg_error(std::string_view text) {
  return error_of([&] { parse_svg(text, "t.svg"); });
}

// ---- documents
// ---------------------------------------------------------------------------------------------------------

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
  EXPECT_EQ(a.fill_rule, FillRule::even_odd);
  EXPECT_EQ(a.stroke_style.join, LineJoin::round);
  EXPECT_EQ(a.stroke_style.cap, LineCap::square);
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
  EXPECT_EQ(c.fill_rule, FillRule::non_zero);
  EXPECT_EQ(c.stroke_style.miter_limit, 9);
  EXPECT_EQ(c.stroke_style.join, LineJoin::bevel);
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
  const auto slice =
      parse("", R"~(width="200" height="100" viewBox="10 10 50 50" preserveAspectRatio="xMinYMax slice")~");
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
  EXPECT_EQ(d.warnings[2],
            "unsupported paint servers (url(...)) replaced by their fallback color or none: url(#g) (2)");
  ASSERT_EQ(d.shapes.size(), 3u);
  expect_color(*d.shapes[0].style.fill, 1, 0, 0);
  EXPECT_FALSE(d.shapes[1].style.fill.has_value());
}

// ---- error messages
// -----------------------------------------------------------------------------------------------------

TEST(SvgErrors, MalformedDocumentsNameLineColumnAndWhatWasExpected) {
  EXPECT_EQ(svg_error("<svg>\n  <g>\n</svg>"), "t.svg:3:1: expected </g> to close <g> from line 2, got </svg>");
  EXPECT_EQ(svg_error("<svg>\n<rect x='1'"),
            "t.svg:2:12: unexpected end of file inside the <rect> tag (expected '>' or '/>')");
  EXPECT_EQ(svg_error("<svg>\n<g>\n"), "t.svg:3:1: unexpected end of file: expected </g> to close <g> from line 2");
  EXPECT_EQ(svg_error("<svg><rect x=\"1x\"/></svg>"),
            "t.svg:1:16: attribute 'x' of <rect>: unit 'x' is not supported (lengths are px or unitless)");
  EXPECT_EQ(svg_error("<svg><rect width='2mm'/></svg>"),
            "t.svg:1:20: attribute 'width' of <rect>: unit 'mm' is not supported (lengths are px or unitless)");
  EXPECT_EQ(
      svg_error("<svg>\n  <path d=\"M 0 0 L 5 5 K\"/></svg>"),
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
        case 0:
          text[pos] = char(rng() % 256);
          break;
        case 1:
          text[pos] = alphabet[rng() % alphabet.size()];
          break;
        case 2:
          text.erase(pos, 1 + rng() % 8);
          break;
        default:
          text.resize(std::max<size_t>(pos, 1));
          break;
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

}  // namespace
}  // namespace tessera
