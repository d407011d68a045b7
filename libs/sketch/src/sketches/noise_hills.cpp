// A demo of Processing's noise() (Perlin noise as PApplet computes it, seeded by the runner's --seed): three ridges
// of hills scrolling past with parallax, the farthest palest. Ridge k = 0, 1, 2 (back to front) at column x is
//   y_k(x) = height (0.45 + 0.17 k) + height (0.3 - 0.05 k) (0.5 - noise((x + offset_k) 0.006 (1 + 0.5 k), 7.3 k)),
// a polygon closed along the bottom with a vertex every 4 pixels; offset_k grows by (0.5 + k) speed pixels a frame.
// The speed is 1 until the mouse moves, then 4 mouse_x / width (the pointer's x steers the scrolling).
#include <array>

#include "sketches/sketches.hpp"

namespace tessera::sketches {
namespace {

class NoiseHills : public Sketch {
 public:
  void setup() override {
    size(400, 300);
    no_stroke();
  }

  void draw() override {
    background(rgb255(250, 235, 215));
    fill(rgb255(250, 190, 120));  // the sun
    ellipse(width * 0.72, height * 0.28, 60, 60);
    for (int k = 0; k < 3; ++k) {
      offset_[size_t(k)] += (0.5 + k) * speed_;
      fill(kColors[k]);
      begin_shape();
      vertex(width, height);
      vertex(0, height);
      for (int x = 0; x <= width; x += 4) {
        const double u = (x + offset_[size_t(k)]) * 0.006 * (1 + 0.5 * k);
        vertex(x, height * (0.45 + 0.17 * k) + height * (0.3 - 0.05 * k) * (0.5 - noise(u, 7.3 * k)));
      }
      end_shape(true);
    }
  }

  void mouse_moved() override { speed_ = 4.0 * mouse_x / width; }

 private:
  inline static const Vec4f kColors[3] = {rgb255(170, 180, 200), rgb255(100, 125, 150), rgb255(40, 60, 80)};
  std::array<double, 3> offset_{};
  double speed_ = 1;
};

}  // namespace

// The pointer speeds the hills up, slows them almost to a stop, then sets them to the middle speed.
const std::string_view kNoiseHillsDemo = R"(# noise_hills: the pointer's x steers the scrolling
30 mouse_move 320 150
70 mouse_move 30 150
100 mouse_move 200 150
)";

std::unique_ptr<Sketch> make_noise_hills() { return std::make_unique<NoiseHills>(); }

}  // namespace tessera::sketches
