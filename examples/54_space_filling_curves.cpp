// Example 54: space-filling curves (the notes: a snakelike curve through the unit square; subdivide into 9 squares,
// draw the curve through each and connect them, and so on: 9 -> 81 -> ... cells; in the limit it passes through every
// point of the square). Peano's curve at depths 1-4 and Hilbert's (4 squares per step) at depths 1-6.
#include <fmt/format.h>

#include "gallery.hpp"
#include "tessera/color/color.hpp"
#include "tessera/fractal/draw.hpp"
#include "tessera/fractal/self_similar.hpp"
#include "tessera/image/image_io.hpp"

namespace {

// Several depths of one curve side by side, one square cell each, the line thinner as the curve gets finer.
tessera::ImageRGB depths(std::vector<tessera::Vec2> (*curve)(int), int first, int last, int side,
                         const tessera::Vec3f& ink) {
  using namespace tessera;
  const int count = last - first + 1;
  ImageRGBA strip(count * side, side, Vec4f(1.0f));
  for (int d = first; d <= last; ++d) {
    const std::vector<Vec2> points = curve(d);
    ImageRGBA cell(side, side, Vec4f(1.0f));
    const double cells = std::sqrt(double(points.size()));
    add_curve(cell, points, false, {side, side, 8}, ink, std::clamp(0.35 * side / cells, 1.0, 4.0), true);
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) strip((d - first) * side + x, y) = cell(x, y);
  }
  return to_rgb(strip);
}

}  // namespace

TESSERA_EXAMPLE(ex54_space_filling_curves, "54_space_filling_curves", "Peano and Hilbert space-filling curves") {
  using namespace tessera;
  gallery.add("54_peano_depths.png", depths(peano_curve, 1, 4, 300, {0.55f, 0.15f, 0.1f}),
              "Peano curve, depths 1-4: 9, 81, 729, 6561 cells, from the bottom-left corner to the top-right one");
  gallery.add("54_hilbert_depths.png", depths(hilbert_curve, 1, 6, 250, {0.1f, 0.2f, 0.55f}),
              "Hilbert curve, depths 1-6: 4^n cells, from the bottom-left corner to the bottom-right one");
  // One large Hilbert curve colored along its length: neighbours on the curve are neighbours in the square.
  const std::vector<Vec2> h = hilbert_curve(6);
  ImageRGBA big(600, 600, Vec4f(1.0f));
  const PictureFrame frame{600, 600, 6};
  for (size_t i = 1; i < h.size(); ++i) {
    const double hue = 0.75 * double(i) / double(h.size());  // violet -> red along the curve (hue in turns)
    add_curve(big, {h[i - 1], h[i]}, false, frame, Vec3f(hsv_to_rgb({0.75 - hue, 0.85, 0.85})), 3.0, true);
  }
  gallery.add("54_hilbert_colored.png", to_rgb(big),
              "Hilbert curve, depth 6, colored from start (violet) to end (red): close on the curve means close in "
              "the square");
}
