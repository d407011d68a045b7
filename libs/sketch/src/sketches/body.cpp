// The notes' body hierarchy ("Matrix Stack Uses": a person of torso + 2 arms, an arm an extent + a hand of fingers
// and a thumb; "Drawing a body (see handout)": square() and extent()), made to wave: the arms' shoulder angles and the
// raised hand's wrist angle follow frame_count (body_angles() below), so every frame redraws the same hierarchy with
// new rotations on the matrix stack. The parts are those of examples/05_body.cpp: square() draws GT_LINES from
// (-1, -1) to (1, 1), extent() is push, scale(3, 0.5), translate(1, 0), square(), pop (a 6 x 1 bar along +x).
//
//   void draw() {
//     background(255);
//     translate(200, 240); scale(14, -14);           // the notes' y-up units, 14 pixels each
//     body();                                        // torso, head, arm(raise), mirrored arm(lower)
//   }
#include <cmath>
#include <vector>

#include "sketches/sketches.hpp"
#include "tessera/raster2d/lines.hpp"

namespace tessera::sketches {
namespace {

/// The rotations of one frame (radians, counterclockwise, y up).
struct BodyAngles {
  double raise;  ///< the waving arm at the shoulder: 40 + 25 sin(phase) degrees
  double wave;   ///< its hand at the wrist: 35 sin(3 phase) degrees
  double lower;  ///< the other arm at the shoulder (before its mirror): -25 + 10 sin(phase + pi) degrees
};

/// The angles at frame f: phase = 2 pi f / 60, one swing a second at 60 frames per second.
BodyAngles body_angles(int frame_count) {
  const double phase = 2 * kPi * frame_count / 60.0;
  return {radians(40) + radians(25) * std::sin(phase), radians(35) * std::sin(3 * phase),
          radians(-25) + radians(10) * std::sin(phase + kPi)};
}

class Body : public Sketch {
 public:
  void setup() override {
    size(400, 400);
    no_fill();
  }

  void draw() override {
    background(gray255(255));
    const BodyAngles a = body_angles(frame_count);
    push_matrix();
    translate(200, 240);
    scale(kUnit, -kUnit);  // y up, as the notes' gt coordinates
    stroke_weight(1.5);    // pixels: gt_lines draws in device coordinates
    stroke(gray255(0));
    body(a);
    pop_matrix();
  }

 private:
  static constexpr double kUnit = 14;  // pixels per unit

  // The notes' GT_LINES: each vertex multiplied by the CTM (gtVertex), the pairs joined by lines drawn in pixels, so
  // every part has the same line width however the stack scales it.
  void gt_lines(const std::vector<Vec2>& vertices) {
    const Mat3 ctm = canvas().matrix();
    push_matrix();
    reset_matrix();
    begin_shape(ShapeKind::lines);
    for (const Vec2& v : vertices) {
      const Vec3 p = ctm * Vec3(v, 1.0);
      vertex(p.x, p.y);
    }
    end_shape();
    pop_matrix();
  }

  // The notes' square(): GT_LINES around (-1, -1) .. (1, 1).
  void square() { gt_lines({{-1, -1}, {1, -1}, {1, -1}, {1, 1}, {1, 1}, {-1, 1}, {-1, 1}, {-1, -1}}); }

  // The notes' circle(): 20 segments of the unit circle.
  void circle() { gt_lines(circle_segments(20)); }

  // The notes' extent(): a 6 x 1 bar from the origin along +x.
  void extent() {
    push_matrix();
    scale(3, 0.5);
    translate(1, 0);  // written last, acts first
    square();
    pop_matrix();
  }

  void finger() {
    push_matrix();
    scale(0.4, 0.3);
    extent();
    pop_matrix();
  }

  // A palm [0, 2] x [-0.8, 0.8], four fingers from its far side, a thumb turned 50 degrees.
  void hand() {
    push_matrix();
    translate(1, 0);
    scale(1, 0.8);
    square();
    pop_matrix();
    for (int i = 0; i < 4; ++i) {
      push_matrix();
      translate(2, -0.6 + 0.4 * i);
      finger();
      pop_matrix();
    }
    push_matrix();
    translate(0.6, 0.8);
    rotate(radians(50));
    scale(0.7, 1);
    finger();
    pop_matrix();
  }

  // An arm from the shoulder: the upper arm, and at its end the hand turned by `wrist`.
  void arm(double wrist) {
    extent();
    push_matrix();
    translate(6, 0);
    rotate(wrist);
    hand();
    pop_matrix();
  }

  void body(const BodyAngles& a) {
    push_matrix();  // torso [-2, 2] x [-4, 4]
    scale(2, 4);
    square();
    pop_matrix();
    push_matrix();  // head
    translate(0, 5.6);
    scale(1.5, 1.5);
    circle();
    pop_matrix();
    push_matrix();  // the waving arm (on the viewer's right)
    translate(2, 3);
    rotate(a.raise);
    arm(a.wave);
    pop_matrix();
    push_matrix();  // the other arm: the same arm mirrored by scale(-1, 1), swinging slowly
    translate(-2, 3);
    scale(-1, 1);
    rotate(a.lower);
    arm(0);
    pop_matrix();
  }
};

}  // namespace

std::unique_ptr<Sketch> make_body() { return std::make_unique<Body>(); }

}  // namespace tessera::sketches
