// Example 10: the notes' body hierarchy (example 05) in 3D through the gt layer. A person is a torso, a head and two
// arms; an arm is an extent (the upper arm), a forearm bent at the elbow and a hand; a hand is a palm, four fingers
// and a thumb. Every part is one unit cube ([-1, 1]^3, GT_QUADS with a normal per face) or a sphere placed by the
// matrix stack: push, transform, draw, pop. The right arm is the left arm mirrored by gtScale(-1, 1, 1): one
// definition, instantiated twice. Lit by one directional light, Gouraud shading, z-buffer.
#include <cmath>

#include "gallery.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/gt.hpp"

namespace {

using namespace tessera::gt;
using tessera::kPi;
using tessera::radians;

// The unit cube [-1, 1]^3: six quads, counterclockwise seen from outside, one normal each.
void cube() {
  struct Face {
    double n[3];
    double corners[4][3];
  };
  static const Face faces[6] = {
      {{1, 0, 0}, {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}}},
      {{-1, 0, 0}, {{-1, -1, -1}, {-1, -1, 1}, {-1, 1, 1}, {-1, 1, -1}}},
      {{0, 1, 0}, {{-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}}},
      {{0, -1, 0}, {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}}},
      {{0, 0, 1}, {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}},
      {{0, 0, -1}, {{-1, -1, -1}, {-1, 1, -1}, {1, 1, -1}, {1, -1, -1}}},
  };
  gtBeginShape(GT_QUADS);
  for (const Face& f : faces) {
    gtNormal(f.n[0], f.n[1], f.n[2]);
    for (const auto& c : f.corners) gtVertex(c[0], c[1], c[2]);
  }
  gtEndShape();
}

// The unit sphere as triangles with their vertex normals (a head).
void sphere() {
  static const tessera::TriMesh mesh = tessera::to_tri_mesh(tessera::make_uv_sphere(24, 12));
  gtBeginShape(GT_TRIANGLES);
  for (const uint32_t i : mesh.indices) {
    const tessera::Vec3& p = mesh.positions[i];
    gtNormal(p.x, p.y, p.z);
    gtVertex(p.x, p.y, p.z);
  }
  gtEndShape();
}

// The notes' extent(): a 6 x 1 x 1 bar starting at the origin along +x.
void extent() {
  gtPushMatrix();
  gtScale(3, 0.5, 0.5);
  gtTranslate(1, 0, 0);  // written last, acts first: the cube moves to [0, 2] along x, then stretches to [0, 6]
  cube();
  gtPopMatrix();
}

void finger(double curl) {
  gtPushMatrix();
  gtRotateZ(-curl);  // fingers bend down a little, about their base
  gtScale(0.4, 0.3, 0.3);
  extent();
  gtPopMatrix();
}

// A hand at the origin pointing along +x: a palm [0, 2] x [-0.8, 0.8] x [-0.25, 0.25], four fingers across its far
// side, a thumb.
void hand() {
  gtColor(0.95f, 0.75f, 0.6f);
  gtPushMatrix();
  gtTranslate(1, 0, 0);
  gtScale(1, 0.8, 0.25);
  cube();
  gtPopMatrix();
  for (int i = 0; i < 4; ++i) {
    gtPushMatrix();
    gtTranslate(2, -0.6 + 0.4 * i, 0);
    finger(radians(10 + 8 * i));
    gtPopMatrix();
  }
  gtPushMatrix();  // the thumb: a shorter finger from the palm's upper side, turned 50 degrees
  gtTranslate(0.6, 0.8, 0);
  gtRotateZ(radians(50));
  gtScale(0.7, 1, 1);
  finger(0);
  gtPopMatrix();
}

// An arm from the shoulder at the origin (three quarters of the notes' size): the upper arm, the forearm bent at the
// elbow, the hand turned at the wrist.
void arm(double shoulder, double elbow, double wrist) {
  gtPushMatrix();
  gtRotateZ(shoulder);
  gtScale(0.75, 0.75, 0.75);
  gtColor(0.25f, 0.45f, 0.8f);
  extent();
  gtTranslate(6, 0, 0);
  gtRotateZ(elbow);
  gtRotateY(radians(-25));  // the forearm also comes toward the viewer
  gtColor(0.3f, 0.55f, 0.85f);
  gtPushMatrix();
  gtScale(0.9, 0.9, 0.9);
  extent();
  gtPopMatrix();
  gtTranslate(5.4, 0, 0);
  gtRotateX(wrist);
  hand();
  gtPopMatrix();
}

void body() {
  gtColor(0.85f, 0.35f, 0.3f);  // the torso: 6 wide, 10 tall, 3 deep
  gtPushMatrix();
  gtScale(3, 5, 1.5);
  cube();
  gtPopMatrix();
  gtColor(0.95f, 0.75f, 0.6f);  // the head
  gtPushMatrix();
  gtTranslate(0, 7.2, 0);
  gtScale(1.8, 2.1, 1.8);
  sphere();
  gtPopMatrix();
  gtPushMatrix();  // the left arm (viewer's right) waves: upper arm out, forearm up
  gtTranslate(3, 4, 0);
  arm(radians(10), radians(75), radians(30));
  gtPopMatrix();
  gtPushMatrix();  // the right arm: the same arm mirrored, hanging
  gtTranslate(-3, 4, 0);
  gtScale(-1, 1, 1);
  arm(radians(-60), radians(20), radians(-20));
  gtPopMatrix();
}

}  // namespace

TESSERA_EXAMPLE(ex10_body_3d, "10_body_3d", "The body hierarchy in 3D (matrix stack, push/pop)") {
  tessera::raster3d::Context context(560, 480);
  gtMakeCurrent(&context);
  context.shading(tessera::raster3d::ShadingModel::gouraud);
  context.color_material(true);  // gtColor sets each part's ambient and diffuse color
  context.material(tessera::raster3d::Material::plastic({1, 1, 1}, 40, 0.3f));
  context.light(0, {.position = {0.4f, 0.7f, 1.0f, 0.0f}});  // eye space: set before the camera
  gtClear(0.93f, 0.94f, 0.96f);
  gtPerspective(radians(40), 1, 100);
  gtLookAt(12, 8, 36, 1.5, 2.5, 0, 0, 1, 0);
  body();
  gtMakeCurrent(nullptr);
  gallery.add("10_body_3d.png", context.framebuffer().color_rgb(),
              "The notes' person in 3D: torso, head and two arms (upper arm, bent forearm, hand with four fingers and "
              "a thumb), every part a unit cube (the head a sphere) placed by push/transform/pop; the right arm "
              "(viewer's left, hanging) is the same arm definition as the waving left one, mirrored by "
              "gtScale(-1, 1, 1) and posed with other joint angles.");
}
