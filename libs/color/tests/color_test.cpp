// Color-model conversions: round trips, the notes' edge cases, Python's colorsys as a reference (HSV, HLS, YIQ),
// the IEC 61966-2-1 matrix and white point, and the CIE 1931 data.
#include "tessera/color/color.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "tessera/color/chromaticity.hpp"
#include "tessera/color/colormap.hpp"
#include "tessera/color/model.hpp"
#include "tessera/color/srgb.hpp"
#include "tessera/core/error.hpp"

namespace tessera {
namespace {

// RGB test colors: a 22^3 grid over [0, 1] (grays, black, white and every face of the cube included) and random
// values: more than 10^4 in all.
std::vector<Vec3> test_colors() {
  std::vector<Vec3> colors;
  const int n = 21;
  for (int r = 0; r <= n; ++r)
    for (int g = 0; g <= n; ++g)
      for (int b = 0; b <= n; ++b) colors.emplace_back(r / double(n), g / double(n), b / double(n));
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) colors.emplace_back(u(rng), u(rng), u(rng));
  return colors;
}

// Distance between two hues in turns, around the circle.
double hue_distance(double a, double b) {
  const double d = std::abs(a - b) - std::floor(std::abs(a - b));
  return std::min(d, 1.0 - d);
}

void expect_near3(const Vec3& a, const Vec3& b, double tolerance, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], tolerance) << what << " component " << c;
}

TEST(ColorRoundTrip, EveryModelThroughRgb) {
  const auto colors = test_colors();
  for (ColorModel model : kColorModels) {
    for (const Vec3& rgb : colors) {
      const Vec4 there = convert(ColorModel::rgb, model, Vec4(rgb, 0.0));
      const Vec4 back = convert(model, ColorModel::rgb, there);
      expect_near3(Vec3(back), rgb, 1e-12, std::string(model_name(model)));
      if (HasFailure()) return;
    }
  }
}

TEST(ColorRoundTrip, EveryPairOfModels) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 rgb(u(rng), u(rng), u(rng));
    for (ColorModel a : kColorModels)
      for (ColorModel b : kColorModels) {
        const Vec4 in_a = convert(ColorModel::rgb, a, Vec4(rgb, 0.0));
        const Vec4 back = convert(b, a, convert(a, b, in_a));
        expect_near3(Vec3(convert(a, ColorModel::rgb, back)), rgb, 1e-12,
                     fmt::format("{} -> {} -> {}", model_name(a), model_name(b), model_name(a)));
      }
    if (HasFailure()) return;
  }
}

TEST(ColorEdgeCases, GraysHaveHueAndSaturationZero) {
  for (double v : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    EXPECT_EQ(rgb_to_hsv(Vec3(v)), Vec3(0.0, 0.0, v));
    EXPECT_EQ(rgb_to_hls(Vec3(v)), Vec3(0.0, v, 0.0));
    EXPECT_EQ(hsv_to_rgb(Vec3(0.4, 0.0, v)), Vec3(v));
    EXPECT_EQ(hls_to_rgb(Vec3(0.4, v, 0.0)), Vec3(v));
  }
}

TEST(ColorEdgeCases, BlackAndWhite) {
  EXPECT_EQ(rgb_to_cmyk(Vec3(0.0)), Vec4(0.0, 0.0, 0.0, 1.0));  // black: K = 1, C = M = Y = 0
  EXPECT_EQ(rgb_to_cmyk(Vec3(1.0)), Vec4(0.0, 0.0, 0.0, 0.0));
  EXPECT_EQ(rgb_to_cmy(Vec3(0.0)), Vec3(1.0));
  EXPECT_EQ(rgb_to_hsv(Vec3(1.0)), Vec3(0.0, 0.0, 1.0));
  EXPECT_EQ(rgb_to_hls(Vec3(1.0)), Vec3(0.0, 1.0, 0.0));
  // xyY of black: the white point's chromaticity, Y = 0; and back to black whatever the chromaticity.
  EXPECT_EQ(rgb_to_xyy(Vec3(0.0)), Vec3(0.3127, 0.3290, 0.0));
  EXPECT_EQ(xyy_to_xyz(Vec3(0.0, 0.0, 0.0)), Vec3(0.0));
  EXPECT_THROW(xyy_to_xyz(Vec3(0.3, 0.0, 0.5)), InvalidInput);
  // CMYK: K carries the gray, C'M'Y' the color.
  const Vec4 dark_red = rgb_to_cmyk(Vec3(0.5, 0.0, 0.0));
  EXPECT_NEAR(dark_red.w, 0.5, 1e-15);
  // Back from CMYK: C = C'(1 - K) + K, and R = (1 - C')(1 - K) (hand-computed for (0.2, 0.4, 0.6, 0.5)).
  expect_near3(cmyk_to_cmy(Vec4(0.2, 0.4, 0.6, 0.5)), Vec3(0.6, 0.7, 0.8), 1e-15, "CMY of a CMYK");
  expect_near3(cmyk_to_rgb(Vec4(0.2, 0.4, 0.6, 0.5)), Vec3(0.4, 0.3, 0.2), 1e-15, "RGB of a CMYK");
  expect_near3(cmyk_to_rgb(dark_red), Vec3(0.5, 0.0, 0.0), 1e-15, "dark red round trip");
  expect_near3(cmyk_to_rgb(Vec4(0.7, 0.1, 0.3, 1.0)), Vec3(0.0), 0.0, "K = 1 is black whatever C'M'Y'");
}

TEST(ColorEdgeCases, NotesHueAnglesAndTheCube) {
  // The notes: red 0, yellow pi/3, green 2pi/3, cyan pi, blue 4pi/3, magenta 5pi/3 (here in turns: k/6).
  const Vec3 corners[] = {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, {1, 0, 1}};
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(rgb_to_hsv(corners[k]).x, k / 6.0, 1e-15) << k;
    EXPECT_NEAR(rgb_to_hls(corners[k]).x, k / 6.0, 1e-15) << k;
    expect_near3(hsv_to_rgb(Vec3(k / 6.0, 1.0, 1.0)), corners[k], 1e-15, "hsv corner");
    expect_near3(hls_to_rgb(Vec3(k / 6.0, 0.5, 1.0)), corners[k], 1e-15, "hls corner");
  }
  // (R, G, B) = (1, 1, 1) - (C, M, Y).
  expect_near3(cmy_to_rgb(Vec3(0.0, 1.0, 1.0)), Vec3(1.0, 0.0, 0.0), 0.0, "cyan-free ink is red");
}

TEST(ColorEdgeCases, HueWraps) {
  const Vec3 reference = hsv_to_rgb(Vec3(0.3, 0.7, 0.9));
  for (double h : {1.3, 2.3, -0.7, -1.7}) {
    expect_near3(hsv_to_rgb(Vec3(h, 0.7, 0.9)), reference, 1e-12, "hsv wrap");
    expect_near3(hls_to_rgb(Vec3(h, 0.4, 0.6)), hls_to_rgb(Vec3(0.3, 0.4, 0.6)), 1e-12, "hls wrap");
  }
  EXPECT_EQ(wrap_hue(1.0), 0.0);
  EXPECT_EQ(wrap_hue(-1e-300), 0.0);  // rounds up to 1: maps to 0, never 1
  EXPECT_DOUBLE_EQ(wrap_hue(-0.25), 0.75);
  // Hue from RGB is always in [0, 1), also when the formula gives a tiny negative number.
  const double h = rgb_to_hsv(Vec3(1.0, 0.0, 1e-300)).x;
  EXPECT_GE(h, 0.0);
  EXPECT_LT(h, 1.0);
}

// Runs Python's colorsys on the test colors; returns its output lines, or an empty vector when there is no Python.
std::vector<std::array<double, 15>> colorsys_reference(const std::vector<Vec3>& colors) {
  FILE* which = popen("command -v python3 2>/dev/null", "r");
  char buffer[4096] = {};
  const bool found = which && std::fgets(buffer, sizeof buffer, which) != nullptr;
  if (which) pclose(which);
  std::string python = found ? std::string(buffer) : std::string();
  while (!python.empty() && (python.back() == '\n' || python.back() == '\r')) python.pop_back();
  if (python.empty()) return {};

  const auto dir = std::filesystem::path(testing::TempDir()) / fmt::format("color_test_{}", ::getpid());
  std::filesystem::create_directories(dir);
  {
    std::ofstream in(dir / "in.txt");
    in.precision(17);
    for (const Vec3& c : colors) in << c.x << ' ' << c.y << ' ' << c.z << '\n';
    std::ofstream script(dir / "reference.py");
    // Per color: hsv, hls, yiq of (r, g, b); hsv_to_rgb and hls_to_rgb of (r, g, b) read as (h, s, v) and (h, l, s);
    // yiq_to_rgb of colorsys's own yiq (inside the cube's image, so colorsys's clamping does not act).
    script << "import colorsys, sys\n"
              "out = open(sys.argv[2], 'w')\n"
              "for line in open(sys.argv[1]):\n"
              "    r, g, b = map(float, line.split())\n"
              "    yiq = colorsys.rgb_to_yiq(r, g, b)\n"
              "    vals = colorsys.rgb_to_hsv(r, g, b) + colorsys.rgb_to_hls(r, g, b) + yiq\n"
              "    vals += colorsys.hsv_to_rgb(r, g, b) + colorsys.hls_to_rgb(r, g, b)\n"
              "    out.write(' '.join(repr(v) for v in vals) + '\\n')\n";
  }
  const std::string command = fmt::format("'{}' '{}' '{}' '{}'", python, (dir / "reference.py").string(),
                                          (dir / "in.txt").string(), (dir / "out.txt").string());
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::vector<std::array<double, 15>> rows;
  std::ifstream out(dir / "out.txt");
  std::array<double, 15> row;
  while (true) {
    for (double& v : row) out >> v;
    if (!out) break;
    rows.push_back(row);
  }
  std::filesystem::remove_all(dir);
  return rows;
}

TEST(ColorReference, MatchesPythonColorsys) {
  const auto colors = test_colors();
  ASSERT_GE(colors.size(), 10000u);
  const auto reference = colorsys_reference(colors);
  if (reference.empty() && !HasFailure()) GTEST_SKIP() << "python3 not found";
  ASSERT_EQ(reference.size(), colors.size());
  const double tolerance = 1e-6;
  for (size_t i = 0; i < colors.size(); ++i) {
    const Vec3& c = colors[i];
    const auto& ref = reference[i];
    const Vec3 hsv = rgb_to_hsv(c), hls = rgb_to_hls(c), yiq = rgb_to_yiq(c);
    EXPECT_LE(hue_distance(hsv.x, ref[0]), tolerance) << "hsv hue of " << i;
    EXPECT_NEAR(hsv.y, ref[1], tolerance) << i;
    EXPECT_NEAR(hsv.z, ref[2], tolerance) << i;
    EXPECT_LE(hue_distance(hls.x, ref[3]), tolerance) << "hls hue of " << i;
    EXPECT_NEAR(hls.y, ref[4], tolerance) << i;
    EXPECT_NEAR(hls.z, ref[5], tolerance) << i;
    expect_near3(yiq, Vec3(ref[6], ref[7], ref[8]), tolerance, "rgb_to_yiq");
    expect_near3(yiq_to_rgb(Vec3(ref[6], ref[7], ref[8])), c, tolerance, "yiq_to_rgb");
    expect_near3(hsv_to_rgb(c), Vec3(ref[9], ref[10], ref[11]), tolerance, "hsv_to_rgb");
    expect_near3(hls_to_rgb(c), Vec3(ref[12], ref[13], ref[14]), tolerance, "hls_to_rgb");
    if (HasFailure()) return;
  }
}

TEST(ColorXyz, MatchesIec61966Matrix) {
  // IEC 61966-2-1:1999 equation (F.7): the sRGB -> XYZ matrix to four decimals, and its inverse (5.2).
  const double published[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  const double inverse[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  for (int col = 0; col < 3; ++col) {
    Vec3 unit(0.0);
    unit[col] = 1.0;
    const Vec3 xyz = rgb_to_xyz(unit), rgb = xyz_to_rgb(unit);
    for (int row = 0; row < 3; ++row) {
      EXPECT_NEAR(xyz[row], published[row][col], 5e-5) << row << "," << col;
      EXPECT_NEAR(rgb[row], inverse[row][col], 5e-4) << row << "," << col;
    }
  }
  // White (1, 1, 1) is D65 at Y = 1; the primaries sit at the gamut's corners.
  const Vec3 white = rgb_to_xyy(Vec3(1.0));
  EXPECT_NEAR(white.x, 0.3127, 1e-12);
  EXPECT_NEAR(white.y, 0.3290, 1e-12);
  EXPECT_NEAR(white.z, 1.0, 1e-12);
  const RgbGamut g = srgb_gamut();
  const Vec2 corners[] = {g.red, g.green, g.blue};
  for (int c = 0; c < 3; ++c) {
    Vec3 unit(0.0);
    unit[c] = 1.0;
    const Vec3 xyy = rgb_to_xyy(unit);
    EXPECT_NEAR(xyy.x, corners[c].x, 1e-12);
    EXPECT_NEAR(xyy.y, corners[c].y, 1e-12);
  }
  EXPECT_THROW(rgb_to_xyz_matrix({{0.1, 0.1}, {0.2, 0.2}, {0.3, 0.3}, d65_white()}), InvalidInput);
}

TEST(ColorSrgb, CurveValuesAndPrecisions) {
  EXPECT_NEAR(srgb_encode(0.5), 0.7353569830524495, 1e-15);
  EXPECT_NEAR(srgb_decode(0.5), 0.21404114048223255, 1e-15);
  EXPECT_EQ(srgb_encode(0.002), 12.92 * 0.002);  // the linear toe
  for (double v = 0.0; v <= 1.0; v += 1.0 / 64) {
    EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-14);
    EXPECT_NEAR(srgb_encode(float(v)), srgb_encode(v), 1e-6);
  }
  EXPECT_EQ(srgb_encode(-0.5), 0.0);
  EXPECT_EQ(srgb_encode(2.0), 1.0);
}

TEST(ColorChromaticity, Cie1931Table) {
  const auto table = cie1931_cmf_table();
  ASSERT_EQ(table.size(), 81u);
  Vec3 sum(0.0);
  for (size_t i = 0; i < table.size(); ++i) {
    EXPECT_EQ(table[i].wavelength_nm, 380.0 + 5.0 * double(i));
    sum += table[i].xyz_bar;
  }
  // Equal-energy white: the three columns have (almost) equal sums, 21.3715 at 5 nm steps (CIE 15:2004).
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], 21.3715, 5e-4);
  EXPECT_EQ(cie1931_cmf(555.0).y, 1.0);  // y-bar is the photopic luminosity function, peak 1 at 555 nm
  EXPECT_EQ(cie1931_cmf(300.0), Vec3(0.0));
  EXPECT_NEAR(cie1931_cmf(557.5).y, 0.5 * (1.0 + 0.995), 1e-15);
  // Published spectral-locus chromaticities (CIE 15:2004 table T.4, x(lambda), y(lambda)).
  const struct {
    double nm, x, y;
  } locus[] = {{380, 0.1741, 0.0050}, {450, 0.1566, 0.0177}, {500, 0.0082, 0.5384}, {520, 0.0743, 0.8338},
               {550, 0.3016, 0.6923}, {600, 0.6270, 0.3725}, {700, 0.7347, 0.2653}};
  for (const auto& p : locus) {
    const Vec2 xy = spectral_locus(p.nm);
    EXPECT_NEAR(xy.x, p.x, 1e-4) << p.nm;
    EXPECT_NEAR(xy.y, p.y, 1e-4) << p.nm;
  }
  EXPECT_THROW(spectral_locus(800.0), InvalidInput);
}

TEST(ColorChromaticity, VisibleRegionAndGamut) {
  const RgbGamut srgb = srgb_gamut();
  EXPECT_TRUE(is_visible_chromaticity(d65_white()));
  for (const Vec2& p : {srgb.red, srgb.green, srgb.blue}) {
    EXPECT_TRUE(is_visible_chromaticity(p));
    EXPECT_TRUE(in_gamut(p, srgb));  // corners and edges count as inside
  }
  EXPECT_TRUE(is_visible_chromaticity(spectral_locus(520.0)));  // the boundary itself
  EXPECT_TRUE(is_visible_chromaticity({0.3, 0.1}));             // above the line of purples
  EXPECT_FALSE(is_visible_chromaticity({0.3, 0.05}));           // below it
  EXPECT_FALSE(is_visible_chromaticity({0.8, 0.8}));
  EXPECT_FALSE(is_visible_chromaticity({0.0, 0.0}));
  EXPECT_TRUE(in_gamut(d65_white(), srgb));
  EXPECT_TRUE(in_gamut((srgb.red + srgb.green) / 2.0, srgb));
  EXPECT_FALSE(in_gamut(spectral_locus(520.0), srgb));  // spectral green is outside sRGB
  // A color is in gamut exactly when its linear RGB has no negative component.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 0.8);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 xy(u(rng), u(rng));
    if (xy.y <= 0.01) continue;
    const Vec3 rgb = xyy_to_rgb(Vec3(xy, 0.5));
    const double lowest = std::min({rgb.x, rgb.y, rgb.z});
    if (std::abs(lowest) > 1e-9) {
      EXPECT_EQ(in_gamut(xy, srgb), lowest > 0) << xy.x << "," << xy.y;
    }
  }
}

TEST(ColorModels, NamesCountsAndErrors) {
  for (ColorModel m : kColorModels) EXPECT_EQ(parse_color_model(model_name(m)), m);
  EXPECT_EQ(model_name(ColorModel::xyy), "xyy");
  EXPECT_EQ(component_count(ColorModel::cmyk), 4);
  EXPECT_EQ(component_count(ColorModel::hls), 3);
  EXPECT_EQ(hue_index(ColorModel::hsv), 0);
  EXPECT_EQ(hue_index(ColorModel::yiq), -1);
  try {
    parse_color_model("lab");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "unknown color model 'lab' (expected one of rgb, cmy, cmyk, hsv, hls, yiq, xyz, xyy, srgb)");
  }
  // Names are quoted through printable(): an escape sequence in --from/--to/--hue never reaches the terminal.
  for (const auto& parse :
       {+[](std::string_view s) { parse_color_model(s); }, +[](std::string_view s) { parse_hue_unit(s); }})
    try {
      parse("\x1b[2Jlab");
      FAIL() << "no exception";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("'\\x1b[2Jlab'"), std::string::npos) << e.what();
    }
  const std::vector<double> cmyk = convert(ColorModel::rgb, ColorModel::cmyk, std::vector<double>{1.0, 0.5, 0.0});
  ASSERT_EQ(cmyk.size(), 4u);
  EXPECT_EQ(cmyk, (std::vector<double>{0.0, 0.5, 1.0, 0.0}));
  EXPECT_THROW(convert(ColorModel::cmyk, ColorModel::rgb, std::vector<double>{1.0, 0.5, 0.0}), InvalidInput);
  std::vector<double> out(7);
  EXPECT_THROW(convert_many(ColorModel::rgb, ColorModel::hsv, std::vector<double>(6), out), InvalidInput);
  EXPECT_EQ(full_turn(HueUnit::degrees), 360.0);
  EXPECT_EQ(parse_hue_unit("radians"), HueUnit::radians);
  EXPECT_THROW(parse_hue_unit("grad"), InvalidInput);
}

TEST(ColorModels, ConvertManyMatchesOneByOne) {
  const std::vector<double> in = {0.1, 0.2, 0.3, 0.9, 0.5, 0.0, 1.0, 1.0, 1.0};
  std::vector<double> out(12);
  convert_many(ColorModel::rgb, ColorModel::cmyk, in, out);
  for (size_t i = 0; i < 3; ++i) {
    const auto one = convert(ColorModel::rgb, ColorModel::cmyk, std::span(in).subspan(3 * i, 3));
    for (size_t c = 0; c < 4; ++c) EXPECT_EQ(out[4 * i + c], one[c]);
  }
}

// The two-colors-at-a-time paths of convert_many (rgb to hsv and hls) give the one-color functions' values, on random
// colors, grays, black, white, ties between channels and an odd count.
TEST(ColorModels, ConvertManyHueModelsMatchOneByOne) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> in;
  for (int i = 0; i < 2001; ++i) in.insert(in.end(), {u(rng), u(rng), u(rng)});
  for (const Vec3 c : {Vec3(0.0), Vec3(1.0), Vec3(0.5), Vec3(0.3, 0.3, 0.1), Vec3(0.2, 0.7, 0.7), Vec3(0.9, 0.1, 0.9),
                       Vec3(0.6, 0.4, 0.6), Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.0, 1.0)})
    in.insert(in.end(), {c.x, c.y, c.z});
  std::vector<double> out(in.size());
  for (const ColorModel to : {ColorModel::hsv, ColorModel::hls}) {
    convert_many(ColorModel::rgb, to, in, out);
    for (size_t i = 0; i < in.size(); i += 3) {
      const Vec3 rgb(in[i], in[i + 1], in[i + 2]);
      const Vec3 one = to == ColorModel::hsv ? rgb_to_hsv(rgb) : rgb_to_hls(rgb);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(out[i + size_t(c)], one[c]) << model_name(to) << " row " << i / 3;
    }
  }
}

// The heat ramp at its knots, computed by hand from the three tents, and clamping outside [0, 1].
TEST(ColorMap, HeatRampKnots) {
  auto expect = [](float x, Vec3f want) {
    const Vec3f got = heat_color(x);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(got[c], want[c]) << "x=" << x << " channel " << c;
  };
  expect(0.0f, {0.0f, 0.0f, 0.5f});
  expect(0.125f, {0.0f, 0.0f, 1.0f});
  expect(0.25f, {0.0f, 0.5f, 1.0f});
  expect(0.5f, {0.5f, 1.0f, 0.5f});
  expect(0.75f, {1.0f, 0.5f, 0.0f});
  expect(1.0f, {0.5f, 0.0f, 0.0f});
  expect(-3.0f, {0.0f, 0.0f, 0.5f});
  expect(7.0f, {0.5f, 0.0f, 0.0f});
}

}  // namespace
}  // namespace tessera
