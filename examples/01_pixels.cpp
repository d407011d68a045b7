// Example 01: pixels and coordinates, the first page of the notes.
//
//   (a) a 400 x 400 canvas (size(400, 400): origin top-left, pixels 0..399 on each axis) with one pink pixel,
//       (255, 150, 150), written with write_pixel at (200, 200), and the notes' rect(100, 200, 10, 10) and
//       ellipse(200, 200, 20, 20) on background(255, 255, 255);
//   (b) the pink pixel's neighborhood, pixels 190..209 on both axes of picture (a) as written, magnified: each
//       pixel a 20 x 20 cell of its own color, a thin blue grid between the cells (a raster image is a grid of
//       (r, g, b) values);
//   (c) the notes' mapping of the range [-2, 2] to [0, 400] ("add 2, multiply by 100"): y = 1.5 sin(pi x / 2) plotted
//       over x in [-2, 2], with the axes, as a polyline of the notes' DDA lines (no_smooth).
#include <algorithm>
#include <cmath>
#include <vector>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/canvas.hpp"

namespace {

using namespace tessera;

// Pixels [x0, x0 + n) x [y0, y0 + n) of `image`, each a `cell` x `cell` square of its own color, with a one-pixel
// grid line of `grid` along each cell's top and left edges and the block's right and bottom edges.
ImageRGBA8 magnify(const ImageRGBA8& image, int x0, int y0, int n, int cell, glm::u8vec4 grid) {
  ImageRGBA8 zoom(n * cell + 1, n * cell + 1);
  for (int y = 0; y < zoom.height(); ++y)
    for (int x = 0; x < zoom.width(); ++x)
      zoom(x, y) =
          x % cell == 0 || y % cell == 0 ? grid : image(x0 + std::min(x / cell, n - 1), y0 + std::min(y / cell, n - 1));
  return zoom;
}

// The notes' mapping of [-2, 2] to [0, 400]: add 2, multiply by 100 (y flipped, the canvas's y points down).
double to_x(double x) { return (x + 2) * 100; }
double to_y(double y) { return 400 - (y + 2) * 100; }

}  // namespace

TESSERA_EXAMPLE(ex01_pixels, "01_pixels", "Pixels, Processing coordinates and the [-2, 2] -> [0, 400] mapping") {
  const Vec4f pink = rgb255(255, 150, 150);

  Canvas canvas(400, 400);
  canvas.background(rgb255(255, 255, 255));
  canvas.no_fill();
  canvas.stroke(rgb255(0, 0, 0));
  canvas.rect(100, 200, 10, 10);
  canvas.ellipse(200, 200, 20, 20);
  canvas.write_pixel(200, 200, pink);
  const ImageRGBA8 picture = to_rgba8(canvas.image());
  gallery.add("01_pink_pixel.png", picture,
              "size(400, 400): one pink (255, 150, 150) pixel at (200, 200), rect(100, 200, 10, 10) and "
              "ellipse(200, 200, 20, 20) on a white background");

  gallery.add("01_pink_pixel_zoom.png", magnify(picture, 190, 190, 20, 20, {110, 150, 230, 255}),
              "Pixels x, y = 190..209 of the picture above, magnified 20x (one cell per pixel, a blue grid between "
              "them): a raster image is a grid of (r, g, b) values. The circle's outline is its gray antialiased "
              "pixels on white; the pink one inside is (200, 200)");

  Canvas plot(400, 400);
  plot.background(rgb255(255, 255, 255));
  plot.no_smooth();
  plot.stroke(rgb255(160, 160, 160));
  plot.line(to_x(-2), to_y(0), to_x(2), to_y(0));
  plot.line(to_x(0), to_y(-2), to_x(0), to_y(2));
  for (int t = -2; t <= 2; ++t) {
    plot.line(to_x(t), to_y(0) - 4, to_x(t), to_y(0) + 4);
    plot.line(to_x(0) - 4, to_y(t), to_x(0) + 4, to_y(t));
  }
  plot.stroke(rgb255(200, 40, 60));
  plot.stroke_weight(1);
  std::vector<Vec2> pts;
  for (int i = 0; i <= 200; ++i) {
    const double x = -2 + 4.0 * i / 200;
    pts.push_back({to_x(x), to_y(1.5 * std::sin(kPi * x / 2))});
  }
  for (size_t i = 0; i + 1 < pts.size(); ++i) plot.line(pts[i].x, pts[i].y, pts[i + 1].x, pts[i + 1].y);
  gallery.add("01_mapping.png", to_rgba8(plot.image()),
              "y = 1.5 sin(pi x / 2) for x in [-2, 2], mapped to [0, 400] by adding 2 and multiplying by 100 "
              "(ticks at integers), drawn with the notes' DDA line");
}
