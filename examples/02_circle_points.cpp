// Example 02: points on a circle. "Position on circle: (x, y) = (cos, sin) - radians": for n points,
// theta = 2 pi i / n and the point (cos theta, sin theta), scaled by 150 and moved to the canvas center (y up, as
// the notes draw it, so the canvas's y is flipped).
#include <cmath>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/canvas.hpp"

TESSERA_EXAMPLE(ex02_circle_points, "02_circle_points", "Points on a circle with cos and sin") {
  using namespace tessera;
  Canvas canvas(400, 400);
  canvas.background(rgb255(255, 255, 255));
  // 360 single pixels...
  canvas.stroke(rgb255(120, 120, 120));
  canvas.no_smooth();
  for (int i = 0; i < 360; ++i) {
    const double theta = 2 * kPi * i / 360;
    canvas.point(200 + 150 * std::cos(theta), 200 - 150 * std::sin(theta));
  }
  // ...and 20 larger dots, the first at theta = 0 in red.
  canvas.smooth();
  canvas.stroke_weight(9);
  for (int i = 0; i < 20; ++i) {
    const double theta = 2 * kPi * i / 20;
    canvas.stroke(i == 0 ? rgb255(220, 30, 30) : rgb255(30, 60, 200));
    canvas.point(200 + 150 * std::cos(theta), 200 - 150 * std::sin(theta));
  }
  gallery.add("02_circle_points.png", to_rgba8(canvas.image()),
              "(cos theta, sin theta) for theta = 2 pi i / n: n = 360 single pixels and n = 20 dots (theta = 0 in "
              "red, counterclockwise with y up)");
}
