#pragma once
// The marching-squares sketch's class, private to the sketch module and its tests (which read its field, iso value
// and contours to count the segments independently).
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/sketch/sketch.hpp"
#include "tessera/volume/marching_squares.hpp"

namespace tessera::sketches {

/// The notes' 2D marching-squares example with a draggable iso value (marching_squares.cpp says what it draws).
class MarchingSquaresSketch : public Sketch {
 public:
  static constexpr int kSamples = 16;  ///< samples per side, one per cell of a kSamples^2 grid over the canvas

  /// The pixel of sample coordinate (x, y): the center of cell (x, y) of the grid over the canvas (400 x 400 unless
  /// the runner's --size says otherwise).
  Vec2 to_pixel(const Vec2& p) const { return {(p.x + 0.5) * width / kSamples, (p.y + 0.5) * height / kSamples}; }

  void setup() override;
  void draw() override;
  void mouse_moved() override { follow_mouse(); }
  void mouse_dragged() override { follow_mouse(); }

  /// The field: kSamples^2 values from 0 to about 10, three Gaussian hills.
  const DepthImage& field() const { return field_; }
  /// The iso value: 5 (the notes' "value >= 5") until the mouse moves, then 10 mouse_x / width.
  float iso() const { return iso_; }
  /// The contours drawn by the last draw(), in sample coordinates.
  const std::vector<Polyline>& contours() const { return contours_; }

 private:
  void follow_mouse();

  DepthImage field_;
  float iso_ = 5;
  std::vector<Polyline> contours_;
};

}  // namespace tessera::sketches
