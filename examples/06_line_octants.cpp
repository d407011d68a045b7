// Example 06: lines in every octant with the three line algorithms side by side: the notes' DDA line(), Bresenham's
// integer line and Xiaolin Wu's antialiased line. Each panel is a 41 x 41 image with 16 lines from the center at
// angles 2 pi k / 16 + 0.2 (two per octant), magnified 8x so single pixels show.
#include <cmath>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/lines.hpp"

namespace {

using namespace tessera;

constexpr int kPanel = 41, kZoom = 8, kGap = 16;

ImageRGBA panel(LineAlgorithm algorithm) {
  ImageRGBA image(kPanel, kPanel, Vec4f(0.05f, 0.05f, 0.1f, 1));
  const Vec2 c(20, 20);
  for (int k = 0; k < 16; ++k) {
    const double a = 2 * kPi * k / 16 + 0.2;
    draw_line(image, c, c + 19.0 * Vec2(std::cos(a), std::sin(a)), Vec4f(1, 0.9f, 0.4f, 1), algorithm);
  }
  return image;
}

}  // namespace

TESSERA_EXAMPLE(ex06_line_octants, "06_line_octants", "Lines in every octant: DDA, Bresenham and Wu") {
  const LineAlgorithm algorithms[] = {LineAlgorithm::dda, LineAlgorithm::bresenham, LineAlgorithm::wu};
  const int w = 3 * kPanel * kZoom + 2 * kGap, h = kPanel * kZoom;
  ImageRGBA out(w, h, Vec4f(1, 1, 1, 1));
  for (int p = 0; p < 3; ++p) {
    const ImageRGBA image = panel(algorithms[p]);
    const int x0 = p * (kPanel * kZoom + kGap);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < kPanel * kZoom; ++x) {
        // Nearest-neighbor magnification with a faint grid line between pixels.
        const bool grid = x % kZoom == 0 || y % kZoom == 0;
        const Vec4f v = image(x / kZoom, y / kZoom);
        out(x0 + x, y) = grid ? Vec4f(Vec3f(v) * 0.8f + 0.1f, 1) : v;
      }
  }
  gallery.add("06_line_octants.png", to_rgba8(out),
              "16 lines from the center, two per octant, magnified 8x: the notes' DDA line() (left), Bresenham "
              "(middle), Wu's antialiased line (right)");
}
