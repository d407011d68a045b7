// The notes' cubic Bezier curve ("Bezier Curves", "Draw Bezier Curves") with draggable control points: P1..P4 as
// orange dots joined by the gray control polygon, the curve Q(t) = B1(t) P1 + ... + B4(t) P4 in blue, drawn through
// 64 steps of the notes' finite-difference method (curves' evaluate_forward_differences), and the notes' subdivision
// construction at a moving t (de_casteljau_levels: midpoints of midpoints; t sweeps 0 .. 1 and back every 4 seconds
// at 60 frames per second) ending in Q(t), the red dot. mouse_pressed picks the control point nearest the pointer
// (within 30 pixels), mouse_dragged moves it to the pointer, mouse_released lets it go.
#include "tessera/curves/bezier.hpp"

#include <fmt/format.h>

#include <cmath>

#include "sketches/sketches.hpp"

namespace tessera::sketches {
namespace {

class BezierSketch : public Sketch {
 public:
  void setup() override {
    size(400, 400);
    curve_.points = {Vec2(60, 320), Vec2(110, 80), Vec2(290, 60), Vec2(340, 300)};
  }

  void draw() override {
    background(gray255(255));
    no_fill();
    stroke_weight(1);
    stroke(gray255(160));  // the control polygon
    for (int i = 0; i < 3; ++i) line(p(i).x, p(i).y, p(i + 1).x, p(i + 1).y);

    const double t = 0.5 - 0.5 * std::cos(2 * kPi * frame_count / 240.0);
    const auto levels = de_casteljau_levels(curve_, t);
    stroke(rgb255(110, 190, 110));  // the construction: level 1 and 2 polygons
    for (size_t level = 1; level + 1 < levels.size(); ++level)
      for (size_t i = 0; i + 1 < levels[level].size(); ++i)
        line(levels[level][i].x, levels[level][i].y, levels[level][i + 1].x, levels[level][i + 1].y);

    stroke(rgb255(40, 90, 220));  // the curve
    stroke_weight(3);
    begin_shape();
    for (const Vec2& q : evaluate_forward_differences(curve_, kSteps)) vertex(q.x, q.y);
    end_shape();

    no_stroke();
    fill(rgb255(220, 40, 40));  // Q(t)
    ellipse(levels.back()[0].x, levels.back()[0].y, 10, 10);
    fill(gray255(60));
    text_size(16);
    text(fmt::format("t = {:.2f}", t), 10, 390);
    for (int i = 0; i < 4; ++i) {  // the control points, the dragged one darker
      fill(i == dragged_ ? rgb255(200, 100, 0) : rgb255(250, 160, 40));
      ellipse(p(i).x, p(i).y, 14, 14);
    }
  }

  void mouse_pressed() override {
    double best = kPickRadius * kPickRadius;
    dragged_ = -1;
    for (int i = 0; i < 4; ++i) {
      const double dx = p(i).x - mouse_x, dy = p(i).y - mouse_y, d = dx * dx + dy * dy;
      if (d <= best) best = d, dragged_ = i;
    }
  }

  void mouse_dragged() override {
    if (dragged_ >= 0) curve_.points[size_t(dragged_)] = Vec2(mouse_x, mouse_y);
  }

  void mouse_released() override { dragged_ = -1; }

 private:
  static constexpr int kSteps = 64;
  static constexpr double kPickRadius = 30;

  const Vec2& p(int i) const { return curve_.points[size_t(i)]; }

  Bezier2 curve_;
  int dragged_ = -1;  // the control point being dragged, or -1
};

}  // namespace

// P2 dragged down and right, then P3 down and left, while the construction sweeps.
const std::string_view kBezierDemo = R"(# bezier: drag P2, then P3
1 mouse_move 110 80
8 mouse_press left
10 mouse_move 127 92
13 mouse_move 143 104
16 mouse_move 159 116
19 mouse_move 173 129
22 mouse_move 185 141
25 mouse_move 196 153
28 mouse_move 205 165
31 mouse_move 212 177
34 mouse_move 217 189
37 mouse_move 220 201
40 mouse_move 221 214
43 mouse_move 222 226
46 mouse_move 221 238
49 mouse_move 220 250
54 mouse_release left
62 mouse_move 290 60
64 mouse_press left
66 mouse_move 278 66
69 mouse_move 266 73
72 mouse_move 254 80
75 mouse_move 241 90
78 mouse_move 229 102
81 mouse_move 217 117
84 mouse_move 205 135
87 mouse_move 193 156
90 mouse_move 181 180
93 mouse_move 169 206
96 mouse_move 156 235
99 mouse_move 144 265
102 mouse_move 132 297
105 mouse_move 120 330
110 mouse_release left
)";

std::unique_ptr<Sketch> make_bezier() { return std::make_unique<BezierSketch>(); }

}  // namespace tessera::sketches
