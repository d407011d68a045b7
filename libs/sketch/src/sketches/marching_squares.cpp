// The notes' 2D marching-squares example ("Volume Rendering", "2D Example (marching squares): each voxel has value,
// want surface at value >= 5") with a draggable iso value: a 16 x 16 grid of samples of three Gaussian hills (values
// 0 to about 10) over the canvas, each cell shaded by its value's band (one shade per unit), each sample a dot
// (a large purple one when inside, value >= iso; a small gray one outside), and the contour value == iso in red,
// redrawn every frame by libs/volume's marching_squares(). The iso value starts at the notes' 5 and follows the mouse:
// iso = 10 mouse_x / width while the mouse moves or drags.
#include "sketches/marching_squares.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "sketches/sketches.hpp"

namespace tessera::sketches {

void MarchingSquaresSketch::setup() {
  size(400, 400);
  no_smooth();  // aliased edges: a frame keeps a few dozen colors (an exact GIF palette, no dithering)
  field_ = DepthImage(kSamples, kSamples);
  const auto hill = [](double x, double y, double cx, double cy, double r2) {
    return std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2);
  };
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i)
      field_(i, j) = float(10 * (hill(i, j, 5, 6, 12) + 0.8 * hill(i, j, 10.5, 9, 8) + 0.7 * hill(i, j, 5.5, 11.5, 5)));
}

void MarchingSquaresSketch::follow_mouse() { iso_ = float(10.0 * std::clamp(mouse_x, 0, width) / width); }

void MarchingSquaresSketch::draw() {
  background(gray255(255));
  const double cell_w = double(width) / kSamples, cell_h = double(height) / kSamples;
  no_stroke();
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i) {
      // One shade per unit of value (11 bands): the cells read as a height map, and frames keep few colors.
      const int g = 255 - 16 * int(std::clamp(field_(i, j), 0.0f, 10.0f));
      fill(rgb255(g, g, 255));
      rect(cell_w * i, cell_h * j, cell_w, cell_h);
    }
  contours_ = marching_squares(field_, iso_);
  stroke(rgb255(220, 30, 30));
  stroke_weight(2.5);
  no_fill();
  for (const Polyline& line : contours_) {
    begin_shape();
    for (const Vec2& p : line.points) {
      const Vec2 q = to_pixel(p);
      vertex(q.x, q.y);
    }
    end_shape(line.closed);
  }
  no_stroke();
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i) {
      const bool inside = field_(i, j) >= iso_;
      fill(inside ? rgb255(90, 40, 140) : gray255(120));
      const Vec2 q = to_pixel(Vec2(i, j));
      const double d = inside ? 8 : 3;
      ellipse(q.x, q.y, d, d);
    }
  // The iso value, on a white box.
  fill(gray255(255));
  rect(4, 4, 136, 24);
  fill(gray255(30));
  text_size(16);
  text(fmt::format("iso = {:.2f}", iso_), 10, 22);
}

// The pointer sweeps from x = 150 right to 250, left to 50 and back (iso 3.75, 6.25, 1.25, 3.75 at the default
// width 400; the gallery's 260 x 260 recording sweeps 5.8, 9.6, 1.9, 5.8).
const std::string_view kMarchingSquaresDemo = R"(# marching_squares: the iso value follows the pointer's x
2 mouse_move 150 130
6 mouse_move 171 130
10 mouse_move 191 130
14 mouse_move 209 130
18 mouse_move 224 130
22 mouse_move 237 130
26 mouse_move 245 130
30 mouse_move 249 130
34 mouse_move 249 130
38 mouse_move 245 130
42 mouse_move 237 130
46 mouse_move 224 130
50 mouse_move 209 130
54 mouse_move 191 130
58 mouse_move 171 130
62 mouse_move 150 130
66 mouse_move 129 130
70 mouse_move 109 130
74 mouse_move 91 130
78 mouse_move 76 130
82 mouse_move 63 130
86 mouse_move 55 130
90 mouse_move 51 130
94 mouse_move 51 130
98 mouse_move 55 130
102 mouse_move 63 130
106 mouse_move 76 130
110 mouse_move 91 130
114 mouse_move 109 130
118 mouse_move 129 130
)";

std::unique_ptr<Sketch> make_marching_squares() { return std::make_unique<MarchingSquaresSketch>(); }

}  // namespace tessera::sketches
