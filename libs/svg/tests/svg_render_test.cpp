// The SVG renderer (svg_render.cpp): the pixel-center rule against a point-in-polygon oracle, and antialiased output
// against rsvg-convert (librsvg) when it is installed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "svg_test_util.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera {
namespace {

using namespace test;

// ---- rendering: the pixel-center rule
// ------------------------------------------------------------------------------------

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
        const bool inside = shape.style.fill_rule == FillRule::non_zero ? w != 0 : (w & 1) != 0;
        inside_count += inside;
        if (inside == (image(x, y).w == 1.0f) && (image(x, y).w == 0 || image(x, y).w == 1)) continue;
        if (++mismatches <= 5)
          ADD_FAILURE() << "pixel (" << x << ", " << y << "): winding " << w << ", alpha " << image(x, y).w;
      }
    EXPECT_EQ(mismatches, 0) << "shape at line " << shape.line;
    EXPECT_GT(inside_count, 50) << "shape at line " << shape.line;
  }
}

// ---- rendering: comparison with rsvg-convert
// --------------------------------------------------------------------------

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
  const std::string command = fmt::format("rsvg-convert -b white -w {} -h {} -o '{}' '{}'", ours.width(), ours.height(),
                                          out.string(), in.string());
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
