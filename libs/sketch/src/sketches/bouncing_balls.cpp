// A demo of random() (seeded by the runner's --seed), color_mode(HSB) and the mouse: balls falling under gravity and
// bouncing off the floor and the walls, each bounce keeping 90% of the speed. setup() throws eight balls with
// random() positions, speeds, radii and hues; a mouse press drops one more from rest at the pointer (then its center
// after m frames is the pointer's x and y0 + g m (m + 1) / 2 until it first bounces, g = 0.5 pixels a frame squared).
// Every frame each ball moves (semi-implicit Euler: v += g, p += v) and reflects off the edges it crossed.
#include <vector>

#include "sketches/sketches.hpp"

namespace tessera::sketches {
namespace {

class BouncingBalls : public Sketch {
 public:
  void setup() override {
    size(400, 300);
    color_mode(ColorMode::hsb, 360, 100, 100);
    no_stroke();
    for (int i = 0; i < 8; ++i) {
      const double r = random(8, 22);
      balls_.push_back({random(r, width - r), random(r, height / 2.0), random(-4, 4), random(-2, 2), r, random(360)});
    }
  }

  void draw() override {
    background(40, 10, 98);
    for (Ball& b : balls_) {
      step(b);
      fill(b.hue, 65, 90);
      ellipse(b.x, b.y, 2 * b.r, 2 * b.r);
    }
  }

  void mouse_pressed() override {
    balls_.push_back({double(mouse_x), double(mouse_y), 0, 0, random(8, 22), random(360)});
  }

 private:
  struct Ball {
    double x, y, vx, vy, r, hue;
  };
  static constexpr double kGravity = 0.5, kKeep = 0.9;

  void step(Ball& b) const {
    b.vy += kGravity;
    b.x += b.vx;
    b.y += b.vy;
    // Reflect off an edge crossed: the overshoot comes back, the speed across the edge turns and shrinks.
    if (b.y > height - b.r) b.y = 2 * (height - b.r) - b.y, b.vy = -b.vy * kKeep;
    if (b.x < b.r) b.x = 2 * b.r - b.x, b.vx = -b.vx * kKeep;
    if (b.x > width - b.r) b.x = 2 * (width - b.r) - b.x, b.vx = -b.vx * kKeep;
  }

  std::vector<Ball> balls_;
};

}  // namespace

// Three balls dropped across the top, a second apart at 60 frames per second.
const std::string_view kBouncingBallsDemo = R"(# bouncing_balls: presses drop balls
10 mouse_move 90 40
12 mouse_press left
14 mouse_release left
50 mouse_move 210 30
52 mouse_press left
54 mouse_release left
90 mouse_move 320 50
92 mouse_press left
94 mouse_release left
)";

std::unique_ptr<Sketch> make_bouncing_balls() { return std::make_unique<BouncingBalls>(); }

}  // namespace tessera::sketches
