// Example 51: Julia sets (the notes: z0 comes from the screen position, one c for the whole picture, in the box
// (-1.5, -1.5)..(1.5, 1.5)). The notes' test: the Julia set of c is connected when the orbit of z0 = 0 stays near the
// origin (c is then in the Mandelbrot set), otherwise it is "fractal dust". Two of each, labelled by c.
#include <fmt/format.h>

#include <string>

#include "gallery.hpp"
#include "tessera/fractal/coloring.hpp"
#include "tessera/fractal/escape_time.hpp"

TESSERA_EXAMPLE(ex51_julia, "51_julia", "Julia sets: two connected, two dust") {
  using namespace tessera;
  struct Case {
    std::complex<double> c;
    const char* name;
    Palette palette;
  };
  const Case cases[] = {{{-0.123, 0.745}, "rabbit", Palette::classic},
                        {{-1.0, 0.0}, "basilica", Palette::ocean},
                        {{-0.8, 0.156}, "spiral_dust", Palette::fire},
                        {{0.285, 0.01}, "seahorse_dust", Palette::classic}};
  const int side = 400;
  ImageRGB mosaic(2 * side, 2 * side);
  EscapeOptions options;
  options.max_iterations = 2000;
  for (int i = 0; i < 4; ++i) {
    const Case& k = cases[i];
    ColorOptions colors;
    colors.palette = k.palette;
    colors.period = 6;
    const ImageRGB picture = colorize(julia(k.c, ComplexView{{0.0, 0.0}, 3.0, side, side}, options), colors);
    const bool connected = julia_is_connected(k.c);
    gallery.add(fmt::format("51_julia_{}.png", k.name), picture,
                fmt::format("c = {} {} {}i: {} (orbit of 0 {})", k.c.real(), k.c.imag() < 0 ? '-' : '+',
                            std::abs(k.c.imag()), connected ? "connected" : "dust", connected ? "bounded" : "escapes"));
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) mosaic(x + (i % 2) * side, y + (i / 2) * side) = picture(x, y);
  }
  gallery.add("51_julia_four.png", mosaic,
              "Top: c = -0.123 + 0.745i (rabbit) and c = -1 (basilica), connected; bottom: c = -0.8 + 0.156i and "
              "c = 0.285 + 0.01i, dust");
}
