// The notes' 2D marching-squares example ("Volume Rendering", "2D Example (marching squares): each voxel has value,
// want surface at value >= 5") with a draggable iso value: a 25 x 25 grid of samples of three Gaussian hills (values
// 0 to about 10), each cell shaded by its value, each sample a dot (purple when inside, value >= iso; hollow when
// outside), and the contour value == iso in red, redrawn every frame by libs/volume's marching_squares(). The iso
// value starts at the notes' 5 and follows the mouse: iso = 10 mouse_x / width while the mouse moves or drags.
#include "sketches/marching_squares.hpp"

#include <algorithm>
#include <cmath>

#include "sketches/sketches.hpp"

namespace tessera::sketches {

void MarchingSquaresSketch::setup() {
  size(kSamples * kCell, kSamples * kCell);
  field_ = DepthImage(kSamples, kSamples);
  const auto hill = [](double x, double y, double cx, double cy, double r2) {
    return std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2);
  };
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i)
      field_(i, j) =
          float(10 * (0.95 * hill(i, j, 8, 9, 30) + 0.8 * hill(i, j, 16, 14, 20) + 0.7 * hill(i, j, 9, 18, 12)));
}

void MarchingSquaresSketch::follow_mouse() { iso_ = float(10.0 * std::clamp(mouse_x, 0, width) / width); }

void MarchingSquaresSketch::draw() {
  background(gray255(255));
  const auto at = [](double s) { return kCell * s + kCell / 2.0; };  // sample coordinate -> pixel
  no_stroke();
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i) {
      const int g = 255 - int(std::lround(std::clamp(field_(i, j), 0.0f, 10.0f) * 16));
      fill(rgb255(g, g, 255));
      rect(kCell * i, kCell * j, kCell, kCell);
    }
  contours_ = marching_squares(field_, iso_);
  stroke(rgb255(220, 30, 30));
  stroke_weight(2.5);
  no_fill();
  for (const Polyline& line : contours_) {
    begin_shape();
    for (const Vec2& p : line.points) vertex(at(p.x), at(p.y));
    end_shape(line.closed);
  }
  stroke_weight(1);
  stroke(rgb255(90, 40, 140));
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i) {
      if (field_(i, j) >= iso_)
        fill(rgb255(90, 40, 140));
      else
        fill(gray255(255));
      ellipse(at(i), at(j), 5, 5);
    }
}

// The pointer sweeps right (iso up to 8.75), left (down to 1.25) and back to the middle.
const std::string_view kMarchingSquaresDemo = R"(# marching_squares: the iso value follows the pointer's x
2 mouse_move 200 200
8 mouse_move 231 200
14 mouse_move 261 200
20 mouse_move 288 200
26 mouse_move 311 200
32 mouse_move 330 200
38 mouse_move 343 200
44 mouse_move 349 200
50 mouse_move 349 200
56 mouse_move 343 200
62 mouse_move 330 200
68 mouse_move 311 200
74 mouse_move 288 200
80 mouse_move 261 200
86 mouse_move 231 200
92 mouse_move 200 200
98 mouse_move 169 200
104 mouse_move 139 200
110 mouse_move 112 200
116 mouse_move 89 200
122 mouse_move 70 200
128 mouse_move 57 200
134 mouse_move 51 200
140 mouse_move 51 200
146 mouse_move 57 200
152 mouse_move 70 200
158 mouse_move 89 200
164 mouse_move 112 200
170 mouse_move 139 200
176 mouse_move 169 200
)";

std::unique_ptr<Sketch> make_marching_squares() { return std::make_unique<MarchingSquaresSketch>(); }

}  // namespace tessera::sketches
