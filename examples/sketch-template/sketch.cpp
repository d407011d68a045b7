// My sketch: a ball bounces around the window; click to throw it from the mouse, press space to pause.
// Processing's names in Tessera's lower_case spelling (tessera/sketch/sketch.hpp lists them all).
#include "tessera/sketch/runner.hpp"

using namespace tessera;

class Bounce : public Sketch {
 public:
  void setup() override {
    size(400, 300);
    frame_rate(60);
    x_ = width / 2.0;
    y_ = height / 2.0;
    vx_ = random(-4, 4);  // the same numbers on every run with the same --seed
    vy_ = random(-4, 4);
  }

  void draw() override {
    background(rgb255(250, 245, 235));
    x_ += vx_;
    y_ += vy_;
    if (x_ < kRadius || x_ > width - kRadius) vx_ = -vx_;
    if (y_ < kRadius || y_ > height - kRadius) vy_ = -vy_;
    no_stroke();
    fill(rgb255(255, 150, 150));  // the notes' pink
    ellipse(x_, y_, 2 * kRadius, 2 * kRadius);
    stroke(rgb255(60, 60, 60));
    line(pmouse_x, pmouse_y, mouse_x, mouse_y);
  }

  void mouse_pressed() override {
    x_ = mouse_x;
    y_ = mouse_y;
    vx_ = random(-6, 6);
    vy_ = random(-6, 6);
  }

  void key_pressed() override {
    if (key != ' ') return;
    if (is_looping())
      no_loop();
    else
      loop();
  }

 private:
  static constexpr double kRadius = 20;
  double x_ = 0, y_ = 0, vx_ = 0, vy_ = 0;
};

TESSERA_SKETCH_MAIN(Bounce)
