// The notes' 2D transformations ("Transformations", "Homogenous Coordinates") animated: four panels, each a house
// (the square [0, 2]^2 under the roof (0, 2), (2, 2), (1, 3)) drawn once in light gray where it stands and once,
// filled, under one transformation whose parameter follows frame_count (theta = 2 pi frame_count / 90, a cycle every
// 1.5 seconds at 60 frames per second). Coordinates are the notes' y-up units, 20 pixels each, origin at each panel's
// marked point:
//   top left      translate:  P' = P + T,           T = (1.5 cos theta, 1.5 sin theta)
//   top right     rotate about the pivot (1, 1):   P''' = T2 R T1 P (the notes' "translate to origin, then rotate,
//                                                  then translate back"; written T2, R, T1 since the call written
//                                                  last acts first)
//   bottom left   scale:      S = diag(1 + 0.5 sin theta, 1 + 0.5 cos theta)
//   bottom right  shear:      x' = x + a y, y' = y, a = sin theta (the notes' matrix, applied as a 3 x 3 matrix)
#include <cmath>

#include "sketches/sketches.hpp"

namespace tessera::sketches {
namespace {

class Transformations : public Sketch {
 public:
  void setup() override { size(400, 400); }

  void draw() override {
    background(gray255(255));
    const double theta = 2 * kPi * frame_count / 90.0;
    // Panel dividers.
    stroke(gray255(200));
    stroke_weight(1);
    line(200, 0, 200, 400);
    line(0, 200, 400, 200);
    for (int panel = 0; panel < 4; ++panel) {
      push_matrix();
      const int column = panel % 2, row = panel / 2;
      translate(200 * column + 80, 200 * row + 130);  // the panel's origin
      scale(kUnit, -kUnit);
      stroke_weight(1.0 / kUnit);
      // The untransformed house, and the origin.
      fill(gray255(235));
      stroke(gray255(170));
      house();
      no_stroke();
      fill(gray255(0));
      ellipse(0, 0, 0.25, 0.25);
      switch (panel) {
        case 0:
          translate(1.5 * std::cos(theta), 1.5 * std::sin(theta));
          break;
        case 1:
          translate(1, 1);    // T2: back to the pivot
          rotate(theta);      // R
          translate(-1, -1);  // T1: the pivot to the origin (acts first)
          break;
        case 2:
          scale(1 + 0.5 * std::sin(theta), 1 + 0.5 * std::cos(theta));
          break;
        default:
          apply_matrix(Mat3(1, 0, 0, std::sin(theta), 1, 0, 0, 0, 1));  // columns: x' = x + a y
          break;
      }
      fill(kColors[panel]);
      stroke(gray255(40));
      house();
      pop_matrix();
      fill(gray255(60));  // the panel's name
      text_size(16);
      text(kNames[panel], 200 * column + 10, 200 * row + 22);
      if (panel == 1) {  // the pivot, over the house
        no_stroke();
        fill(rgb255(220, 40, 40));
        ellipse(280 + kUnit, 130 - kUnit, 7, 7);
      }
    }
  }

 private:
  static constexpr double kUnit = 20;  // pixels per unit
  static constexpr const char* kNames[4] = {"translate", "rotate", "scale", "shear"};
  inline static const Vec4f kColors[4] = {rgb255(90, 150, 230), rgb255(240, 120, 90), rgb255(110, 190, 110),
                                          rgb255(190, 120, 210)};

  // The house: a closed polygon, the square [0, 2]^2 with the roof's apex at (1, 3).
  void house() {
    begin_shape();
    vertex(0, 0);
    vertex(2, 0);
    vertex(2, 2);
    vertex(1, 3);
    vertex(0, 2);
    end_shape(true);
  }
};

}  // namespace

std::unique_ptr<Sketch> make_transformations() { return std::make_unique<Transformations>(); }

}  // namespace tessera::sketches
