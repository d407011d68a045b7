// The notes' first sketch made live: a pink (255, 150, 150) square that follows the mouse, on white. Pressing a
// button makes it darker while held; the key 's' toggles a black outline.
//
//   void setup() { size(400, 400); noStroke(); }
//   void draw() { background(255); fill(255, 150, 150); rect(mouseX - 25, mouseY - 25, 50, 50); }
#include "sketches/sketches.hpp"

namespace tessera::sketches {
namespace {

class PinkSquare : public Sketch {
 public:
  void setup() override { size(400, 400); }
  void draw() override {
    background(rgb255(255, 255, 255));
    fill(mouse_is_pressed ? rgb255(220, 90, 120) : rgb255(255, 150, 150));
    if (outlined_) {
      stroke(rgb255(0, 0, 0));
      stroke_weight(4);
    } else {
      no_stroke();
    }
    rect(mouse_x - 25, mouse_y - 25, 50, 50);
  }
  void key_pressed() override {
    if (key == 's') outlined_ = !outlined_;
  }

 private:
  bool outlined_ = false;
};

}  // namespace

// The pointer circles the canvas once in 60 frames, then presses and drags.
const std::string_view kPinkSquareDemo = R"(# pink_square: the pointer goes round, then drags
1 mouse_move 200 120
6 mouse_move 257 143
11 mouse_move 280 200
16 mouse_move 257 257
21 mouse_move 200 280
26 mouse_move 143 257
31 mouse_move 120 200
36 mouse_move 143 143
41 mouse_move 200 120
46 mouse_press left
46 mouse_move 240 160
51 mouse_move 280 200
56 mouse_release left
58 key_press s
59 key_release s
)";

std::unique_ptr<Sketch> make_pink_square() { return std::make_unique<PinkSquare>(); }

}  // namespace tessera::sketches
