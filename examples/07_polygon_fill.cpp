// Example 07: a concave polygon with a hole, filled by the scanline algorithm under both fill rules. The shape is
// one path of three contours: a concave outline (an eight-pointed star), a square hole traced in the same direction
// as the outline, and a pentagram (a self-intersecting contour) inside the star on the right. Even-odd (left) empties
// the hole and the pentagram's points (each crossed twice: by the star and by the pentagram) but fills its center
// (crossed three times); nonzero (right) fills everything, because all windings are 1, 2 or 3, never 0.
// Aliased (pixel-center rule) on top, antialiased below.
#include <cmath>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/canvas.hpp"

namespace {

using namespace tessera;

void draw_shape(Canvas& c) {
  c.begin_shape();
  for (int i = 0; i < 16; ++i) {  // the star, clockwise on screen
    const double a = 2 * kPi * i / 16, r = i % 2 ? 115 : 180;
    c.vertex(200 + r * std::cos(a), 200 + r * std::sin(a));
  }
  c.begin_contour();  // the hole: same direction as the outline
  for (const auto& [x, y] : {std::pair{125, 170}, {180, 170}, {180, 225}, {125, 225}}) c.vertex(x, y);
  c.end_contour();
  c.begin_contour();  // the pentagram
  for (int i = 0; i < 5; ++i) {
    const double a = -kPi / 2 + 4 * kPi * i / 5;
    c.vertex(250 + 45 * std::cos(a), 205 + 45 * std::sin(a));
  }
  c.end_contour();
  c.end_shape(true);
}

}  // namespace

TESSERA_EXAMPLE(ex07_polygon_fill, "07_polygon_fill",
                "Scanline fill of a concave polygon with a hole: even-odd and nonzero") {
  Canvas canvas(800, 800);
  canvas.background(rgb255(255, 255, 255));
  canvas.stroke(rgb255(20, 20, 20));
  canvas.fill(rgb255(80, 140, 220));
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 2; ++col) {
      row == 0 ? canvas.no_smooth() : canvas.smooth();
      canvas.fill_rule(col == 0 ? FillRule::even_odd : FillRule::non_zero);
      canvas.push_matrix();
      canvas.translate(400 * col, 400 * row);
      draw_shape(canvas);
      canvas.pop_matrix();
    }
  gallery.add("07_polygon_fill.png", to_rgba8(canvas.image()),
              "One path of a concave star, a same-direction square hole and a pentagram: even-odd (left) vs nonzero "
              "(right); "
              "aliased pixel-center rule (top) and exact-area antialiasing (bottom)");
}
