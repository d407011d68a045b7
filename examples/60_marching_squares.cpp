// Marching squares (the notes' 2D example): iso-lines of a smooth height field at several levels.
#include <cmath>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/volume/marching_squares.hpp"

TESSERA_EXAMPLE(ex60_marching_squares, "60_marching_squares", "Marching squares: contours of a height field") {
  using namespace tessera;
  const int n = 64, scale = 8;
  DepthImage field(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      field(x, y) = float(std::sin(x * 0.15) * std::cos(y * 0.12) +
                          0.6 * std::exp(-((x - 40.0) * (x - 40.0) + (y - 20.0) * (y - 20.0)) / 80.0));
  Canvas canvas(n * scale, n * scale);
  canvas.background(Vec4f(1.0f));
  canvas.no_stroke();
  for (int y = 0; y < n; ++y)  // the field as gray cells under the lines
    for (int x = 0; x < n; ++x) {
      const float g = 0.55f + 0.25f * field(x, y);
      canvas.fill(Vec4f(g, g, g, 1.0f));
      canvas.rect(x * scale, y * scale, scale, scale);
    }
  canvas.smooth();
  canvas.stroke_weight(1.5);
  for (float iso = -0.8f; iso <= 1.2f; iso += 0.2f) {
    canvas.stroke(iso < 0 ? Vec4f(0.1f, 0.3f, 0.8f, 1.0f) : Vec4f(0.8f, 0.2f, 0.1f, 1.0f));
    for (const auto& line : marching_squares(field, iso))
      for (size_t i = 0; i + 1 < line.points.size() + (line.closed ? 1 : 0); ++i) {
        const Vec2 a = (line.points[i] + 0.5) * double(scale),
                   b = (line.points[(i + 1) % line.points.size()] + 0.5) * double(scale);
        canvas.line(a.x, a.y, b.x, b.y);
      }
  }
  gallery.add("60_marching_squares.png", to_rgb(canvas.image()),
              "Marching squares: iso-lines every 0.2 of a height field (blue below 0, red above), saddles by the "
              "center value.");
}
