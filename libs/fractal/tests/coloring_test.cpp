#include "tessera/fractal/coloring.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

TEST(Coloring, SmoothIterationIsContinuousAcrossBands) {
  const double r = 256;
  // Escaping at n with |z_n| = R^2 (just after |z_{n-1}| = R) gives nu = n; escaping at n-1 with |z| = R gives n too.
  EXPECT_NEAR(smooth_iteration(7, std::pow(r, 4), r), 7.0, 1e-12);
  EXPECT_NEAR(smooth_iteration(6, std::pow(r, 2) * (1 + 1e-12), r), 7.0, 1e-9);
  // Monotone in |z| within a band.
  EXPECT_GT(smooth_iteration(5, 1e6, r), smooth_iteration(5, 1e8, r));
}

TEST(Coloring, PalettesAreCyclicAndNamed) {
  for (Palette p : {Palette::classic, Palette::fire, Palette::ocean, Palette::gray}) {
    EXPECT_EQ(parse_palette(palette_name(p)), p);
    const Vec3f a = palette_color(p, 0.0), b = palette_color(p, 1.0), c = palette_color(p, 3.0);
    EXPECT_EQ(a, b);
    EXPECT_EQ(a, c);
    for (double t = 0; t < 1; t += 0.01) {
      const Vec3f v = palette_color(p, t);
      for (int i = 0; i < 3; ++i) EXPECT_TRUE(v[i] >= 0 && v[i] <= 1);
    }
  }
  EXPECT_THROW(parse_palette("plaid"), InvalidInput);
}

TEST(Coloring, InsidePointsGetTheInsideColor) {
  EscapeOptions options;
  options.max_iterations = 200;
  const EscapeImage image = mandelbrot(ComplexView{{-0.5, 0.0}, 3.0, 60, 40}, options);
  ColorOptions colors;
  colors.inside = {0.2f, 0.3f, 0.4f};
  const ImageRGB picture = colorize(image, colors);
  EXPECT_EQ(picture(30, 20), colors.inside);  // c = -0.45 - 0.0375i, inside the cardioid
  EXPECT_NE(picture(0, 0), colors.inside);    // c = -1.975 + 0.975i escapes
  colors.period = 0;
  EXPECT_THROW(colorize(image, colors), InvalidInput);
}

}  // namespace
}  // namespace tessera
