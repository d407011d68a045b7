// A cube with six colored faces turning in 3D (the notes' double buffering: draw() paints the back buffer, the
// runner swaps it to the front after each frame, so the window never shows a half-drawn cube). Space pauses and
// resumes (no_loop / loop); the mouse's x tilts the view.
#include <numbers>

#include "sketches/sketches.hpp"
#include "tessera/raster3d/gt.hpp"

namespace tessera::sketches {
namespace {

using namespace tessera::gt;

class RotatingCube : public Sketch {
 public:
  void setup() override { size(400, 400, Renderer::p3d); }

  void draw() override {
    gtClear(0.1f, 0.1f, 0.15f);
    gtPerspective(std::numbers::pi / 4, 0.5, 20);
    gtLoadIdentity();
    gtLookAt(0, 2, 7, 0, 0, 0, 0, 1, 0);
    // Half a turn every 2 seconds (millis() is the frames' time when headless, so recordings are exact).
    const double angle = millis() * std::numbers::pi / 2000.0;
    gtRotateX(0.4 + (mouse_x - width / 2.0) * 0.002);
    gtRotateY(angle);
    gtRotateZ(angle * 0.3);
    draw_cube();
  }

  void key_pressed() override {
    if (key != ' ') return;
    if (is_looping())
      no_loop();
    else
      loop();
  }

 private:
  // Unit cube centered at the origin, each face counter-clockwise seen from outside, one color per face.
  static void draw_cube() {
    struct Face {
      float r, g, b;
      int corners[4];
    };
    static constexpr double kCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    static constexpr Face kFaces[6] = {
        {0.95f, 0.35f, 0.35f, {4, 5, 6, 7}},  // +z red
        {0.35f, 0.8f, 0.4f, {1, 0, 3, 2}},    // -z green
        {0.3f, 0.5f, 0.95f, {5, 1, 2, 6}},    // +x blue
        {0.95f, 0.85f, 0.3f, {0, 4, 7, 3}},   // -x yellow
        {0.9f, 0.5f, 0.9f, {7, 6, 2, 3}},     // +y magenta
        {0.4f, 0.9f, 0.9f, {0, 1, 5, 4}},     // -y cyan
    };
    gtBeginShape(GT_QUADS);
    for (const Face& f : kFaces) {
      gtColor(f.r, f.g, f.b);
      for (int c : f.corners) gtVertex(kCorner[c][0], kCorner[c][1], kCorner[c][2]);
    }
    gtEndShape();
  }
};

}  // namespace

std::unique_ptr<Sketch> make_rotating_cube() { return std::make_unique<RotatingCube>(); }

}  // namespace tessera::sketches
