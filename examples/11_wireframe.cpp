// Example 11: wireframes with GT_LINES. A cube (its 12 edges) and a sphere (latitude and longitude circles) seen
// through a parallel projection (gtOrtho: parallel edges stay parallel, far things are not smaller) and a perspective
// projection (gtPerspective: edges converge, the nearer half of the sphere's circles spreads out).
#include <cmath>
#include <vector>

#include "gallery.hpp"
#include "tessera/raster3d/gt.hpp"

namespace {

using namespace tessera::gt;
using tessera::kPi;

void cube_edges() {
  gtBeginShape(GT_LINES);
  for (int axis = 0; axis < 3; ++axis)  // 4 edges along each axis
    for (int a = -1; a <= 1; a += 2)
      for (int b = -1; b <= 1; b += 2) {
        double p[3], q[3];
        p[axis] = -1, q[axis] = 1;
        p[(axis + 1) % 3] = q[(axis + 1) % 3] = a;
        p[(axis + 2) % 3] = q[(axis + 2) % 3] = b;
        gtVertex(p[0], p[1], p[2]);
        gtVertex(q[0], q[1], q[2]);
      }
  gtEndShape();
}

// Circles of latitude every 22.5 degrees and meridians every 30 degrees, 48 segments per full circle.
void sphere_lines() {
  constexpr int kSegments = 48;
  gtBeginShape(GT_LINES);
  for (int lat = -3; lat <= 3; ++lat) {
    const double phi = lat * kPi / 8, r = std::cos(phi), y = std::sin(phi);
    for (int i = 0; i < kSegments; ++i) {
      const double a = 2 * kPi * i / kSegments, b = 2 * kPi * (i + 1) / kSegments;
      gtVertex(r * std::cos(a), y, r * std::sin(a));
      gtVertex(r * std::cos(b), y, r * std::sin(b));
    }
  }
  for (int m = 0; m < 6; ++m) {
    const double theta = m * kPi / 6;
    for (int i = 0; i < kSegments; ++i) {
      const double a = 2 * kPi * i / kSegments, b = 2 * kPi * (i + 1) / kSegments;
      gtVertex(std::cos(a) * std::cos(theta), std::sin(a), std::cos(a) * std::sin(theta));
      gtVertex(std::cos(b) * std::cos(theta), std::sin(b), std::cos(b) * std::sin(theta));
    }
  }
  gtEndShape();
}

// One panel: the cube on the left, the sphere on the right, both seen from the same eye.
tessera::ImageRGB panel(bool perspective) {
  tessera::raster3d::Context context(480, 240);
  gtMakeCurrent(&context);
  gtClear(1, 1, 1);
  if (perspective)
    gtPerspective(tessera::radians(40), 1, 20);
  else
    gtOrtho(-4, 4, -2, 2, 1, 20);
  gtLookAt(1.5, 2.0, 6.0, 0, 0, 0, 0, 1, 0);
  gtColor(0.1f, 0.2f, 0.5f);
  gtPushMatrix();
  gtTranslate(-1.9, 0, 0);
  gtRotateY(0.5);
  cube_edges();
  gtPopMatrix();
  gtColor(0.6f, 0.15f, 0.1f);
  gtPushMatrix();
  gtTranslate(1.9, 0, 0);
  gtScale(1.3, 1.3, 1.3);
  sphere_lines();
  gtPopMatrix();
  gtMakeCurrent(nullptr);
  return context.framebuffer().color_rgb();
}

}  // namespace

TESSERA_EXAMPLE(ex11_wireframe, "11_wireframe", "Wireframes (GT_LINES) under ortho and perspective projection") {
  const tessera::ImageRGB ortho = panel(false), persp = panel(true);
  tessera::ImageRGB sheet(ortho.width(), ortho.height() * 2 + 4, tessera::Vec3f(0.8f));
  tessera::examples::paste(sheet, ortho, 0, 0);
  tessera::examples::paste(sheet, persp, 0, ortho.height() + 4);
  gallery.add("11_wireframe.png", sheet,
              "A cube and a sphere drawn as GT_LINES from the same eye: parallel projection (gtOrtho, top) keeps "
              "parallel edges parallel; perspective projection (gtPerspective, bottom) makes them converge.");
}
