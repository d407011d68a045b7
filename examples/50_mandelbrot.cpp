// Example 50: the Mandelbrot set (the notes: fix z0 = 0, take c from the pixel, iterate z -> z^2 + c and ask whether
// the orbit stays near the origin). Escape times are colored with the continuous count nu = n + 1 - log2(log|z|/log R)
// through a cyclic palette; points that never escape are black.
//   (a) the overview of the notes' window, (b) Seahorse Valley between the cardioid and the period-2 bulb,
//   (c) a deep zoom 1e-9 wide near -0.7436 + 0.1318i (plain double precision still resolves it).
#include "gallery.hpp"
#include "tessera/fractal/coloring.hpp"
#include "tessera/fractal/escape_time.hpp"

TESSERA_EXAMPLE(ex50_mandelbrot, "50_mandelbrot", "Mandelbrot set: overview, Seahorse Valley and a deep zoom") {
  using namespace tessera;
  EscapeOptions options;
  options.max_iterations = 1000;
  ColorOptions colors;
  gallery.add("50_mandelbrot_overview.png",
              colorize(mandelbrot(ComplexView{{-0.65, 0.0}, 3.2, 800, 600}, options), colors),
              "The Mandelbrot set, -2.25..0.95 wide: the main cardioid, the period-2 bulb and the antenna");

  options.max_iterations = 3000;
  colors.palette = Palette::ocean;
  gallery.add("50_mandelbrot_seahorse.png",
              colorize(mandelbrot(ComplexView{{-0.7453, 0.1127}, 0.02, 800, 600}, options), colors),
              "Seahorse Valley: 0.02 wide around -0.7453 + 0.1127i, 3000 iterations");

  options.max_iterations = 12000;
  colors.palette = Palette::classic;
  colors.period = 20;
  gallery.add(
      "50_mandelbrot_deep_zoom.png",
      colorize(mandelbrot(ComplexView{{-0.743643887037151, 0.131825904205330}, 2e-9, 800, 600}, options), colors),
      "A deep zoom: 2e-9 wide around -0.743643887037151 + 0.131825904205330i, 12000 iterations");
}
