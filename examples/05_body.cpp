// Example 05: the notes' body hierarchy through the gt layer. A person is a torso and two arms; an arm is an extent
// (the upper arm) and a hand; a hand is a palm, four fingers and a thumb. Every part is the notes' square() (GT_LINES
// from (-1, -1) to (1, 1)) or extent() (push, scale(3, 0.5), translate(1, 0), square, pop: a 6 x 1 bar starting at
// the origin along +x), placed by the matrix stack. The right arm is the left arm mirrored by gtScale(-1, 1): one
// definition, instantiated twice. Coordinates are y up; one unit is 14 pixels.
#include <cmath>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/gt2d.hpp"
#include "tessera/raster2d/lines.hpp"

namespace {

using namespace tessera::gt2d;
using tessera::kPi;

void square() {
  gtBeginShape(GT_LINES);
  gtVertex(-1, -1), gtVertex(1, -1);
  gtVertex(1, -1), gtVertex(1, 1);
  gtVertex(1, 1), gtVertex(-1, 1);
  gtVertex(-1, 1), gtVertex(-1, -1);
  gtEndShape();
}

void extent() {
  gtPushMatrix();
  gtScale(3, 0.5);
  gtTranslate(1, 0);  // written last, acts first: the square moves to [0, 2] x [-1, 1], then becomes [0, 6] x [-.5, .5]
  square();
  gtPopMatrix();
}

// A finger: a thin extent 2.4 long.
void finger() {
  gtPushMatrix();
  gtScale(0.4, 0.3);
  extent();
  gtPopMatrix();
}

// A hand at the origin pointing along +x: a palm [0, 2] x [-0.8, 0.8], four fingers from its far side, a thumb.
void hand() {
  gtPushMatrix();
  gtTranslate(1, 0);
  gtScale(1, 0.8);
  square();
  gtPopMatrix();
  for (int i = 0; i < 4; ++i) {
    gtPushMatrix();
    gtTranslate(2, -0.6 + 0.4 * i);
    finger();
    gtPopMatrix();
  }
  gtPushMatrix();  // the thumb: a shorter finger from the palm's upper side, turned 50 degrees
  gtTranslate(0.6, 0.8);
  gtRotate(50 * kPi / 180);
  gtScale(0.7, 1);
  finger();
  gtPopMatrix();
}

// An arm from the shoulder at the origin: the upper arm (an extent) and, at its end, the hand.
void arm() {
  extent();
  gtPushMatrix();
  gtTranslate(6, 0);
  hand();
  gtPopMatrix();
}

void circle() {
  const std::vector<tessera::Vec2> v = tessera::circle_segments(20);
  gtBeginShape(GT_LINES);
  for (const tessera::Vec2& p : v) gtVertex(p.x, p.y);
  gtEndShape();
}

void body() {
  gtPushMatrix();  // torso [-2, 2] x [-4, 4]
  gtScale(2, 4);
  square();
  gtPopMatrix();
  gtPushMatrix();  // head
  gtTranslate(0, 5.6);
  gtScale(1.5, 1.5);
  circle();
  gtPopMatrix();
  gtPushMatrix();  // left arm (on the viewer's right), raised 25 degrees
  gtTranslate(2, 3);
  gtRotate(25 * kPi / 180);
  arm();
  gtPopMatrix();
  gtPushMatrix();  // right arm: the same arm mirrored, lowered 20 degrees
  gtTranslate(-2, 3);
  gtScale(-1, 1);
  gtRotate(-20 * kPi / 180);
  arm();
  gtPopMatrix();
}

}  // namespace

TESSERA_EXAMPLE(ex05_body, "05_body", "The body hierarchy: torso, arms (extent + hand), fingers and thumb") {
  Context context(400, 400);
  gtMakeCurrent(&context);
  gtInitialize(400, 400);
  gtTranslate(200, 170);
  gtScale(14, 14);
  body();
  gtMakeCurrent(nullptr);
  gallery.add("05_body.png", tessera::to_rgba8(context.image()),
              "A person from square() and extent() alone: torso, head, two arms (the second a mirrored instance), "
              "each an extent and a hand of palm, four fingers and a thumb, placed by the matrix stack");
}
