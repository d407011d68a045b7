// Example 04: the notes' circle_image() through the gt layer, word for word: three circles placed with
// gtPushMatrix / gtTranslate / gtScale / gtPopMatrix. The picture maps the notes' unit square [0, 1]^2 (y up) onto
// the 400 x 400 image with one gtScale(400, 400) before circle_image().
#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/gt2d.hpp"
#include "tessera/raster2d/lines.hpp"

namespace {

using namespace tessera::gt2d;

// The notes' circle(): GT_LINES pairs of the 20 segments.
void circle() {
  const std::vector<tessera::Vec2> v = tessera::circle_segments(20);
  gtBeginShape(GT_LINES);
  for (const tessera::Vec2& p : v) gtVertex(p.x, p.y);
  gtEndShape();
}

void circle_image() {
  gtPushMatrix();         // the stack is [I, I]
  gtTranslate(0.5, 0.5);  // top: I T
  gtScale(0.5, 0.5);      // top: I T S
  circle();               // centered at (0.5, 0.5), radius 0.5
  gtPopMatrix();          // back to [I]

  gtPushMatrix();
  gtTranslate(0.5, 0.25);
  gtScale(0.25, 0.25);
  circle();
  gtPopMatrix();

  gtPushMatrix();
  gtTranslate(0.5, 0.75);
  gtScale(0.25, 0.25);
  circle();
  gtPopMatrix();
}

}  // namespace

TESSERA_EXAMPLE(ex04_circle_image, "04_circle_image", "circle_image(): three circles with push and pop") {
  Context context(400, 400);
  gtMakeCurrent(&context);
  gtInitialize(400, 400);
  gtScale(400, 400);  // the unit square fills the image
  circle_image();
  gtMakeCurrent(nullptr);
  gallery.add("04_circle_image.png", tessera::to_rgba8(context.image()),
              "circle_image(): a circle of radius 0.5 at (0.5, 0.5) and two of radius 0.25 stacked inside it, each "
              "placed by push, translate, scale, circle(), pop");
}
