// Example 03: the notes' circle() from 20 line segments. circle_segments(20) returns exactly the vertex pairs the
// notes' loop hands to GT_LINES ((xold, yold), (cos theta, sin theta) for theta = 2 pi i / 20); each pair is drawn
// with the notes' DDA line() after mapping the unit circle to radius 180 about the center (y up).
#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/raster2d/lines.hpp"

TESSERA_EXAMPLE(ex03_circle_segments, "03_circle_segments", "The notes' circle() from 20 line segments") {
  using namespace tessera;
  ImageRGBA image(400, 400, rgb255(0, 0, 0));
  const std::vector<Vec2> v = circle_segments(20);
  auto map = [](const Vec2& p) { return Vec2(200 + 180 * p.x, 200 - 180 * p.y); };
  for (size_t i = 0; i + 1 < v.size(); i += 2)
    draw_line(image, map(v[i]), map(v[i + 1]), rgb255(255, 255, 255), LineAlgorithm::dda);
  gallery.add("03_circle_segments.png", to_rgba8(image),
              "circle(): 20 segments from (1, 0) around the unit circle, each drawn with the notes' DDA line()");
}
