// Distribution ray tracing (the notes' "Soft Shadows" and "Glossy Reflection"): a point light against an area light of
// the same power, and a mirror against glossy reflectors.
#include "gallery.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raytrace/render.hpp"

namespace {

using namespace tessera;

/// A floor, a sphere and a post, lit from above by `light`.
RayScene shadow_scene(const Light& light) {
  RayScene scene;
  scene.camera.eye = {0, 3.5, 6.5};
  scene.camera.center = {0, 0.6, 0};
  scene.camera.fovy = radians(40);
  scene.ambient = Vec3f(0.15f);
  Material floor;
  floor.diffuse = Vec3f(0.85f);
  Material red;
  red.diffuse = {0.8f, 0.2f, 0.15f};
  red.specular = Vec3f(0.3f);
  scene.materials = {floor, red};
  scene.lights = {light};
  scene.world.add_shape(Plane{{0, 0, 0}, {0, 1, 0}}, Mat4(1.0), 0);
  scene.world.add_shape(Sphere{{-0.8f, 0.8f, 0}, 0.8f}, Mat4(1.0), 1);
  scene.world.add_shape(Cylinder{0.15f, 0.0f, 2.0f, true}, translate(1.2, 0, -0.3), 1);
  add_light_surfaces(scene);
  scene.world.build();
  return scene;
}

/// Spheres of glossiness 0 (mirror), 0.05, 0.15 and 0.35 over a checkerboard.
RayScene gloss_scene() {
  RayScene scene;
  scene.camera.eye = {0, 1.6, 6};
  scene.camera.center = {0, 0.7, 0};
  scene.camera.fovy = radians(36);
  scene.ambient = Vec3f(0.3f);
  scene.background = {0.6f, 0.75f, 0.95f};
  Light sun;
  sun.position = {3, 6, 5};
  sun.color = Vec3f(0.7f);
  scene.lights = {sun};
  Material board;
  board.diffuse = {0.9f, 0.9f, 0.9f};
  board.checker = 0.5f;
  board.checker_color = {0.15f, 0.15f, 0.2f};
  scene.materials = {board};
  scene.world.add_shape(Plane{{0, 0, 0}, {0, 1, 0}}, Mat4(1.0), 0);
  const float gloss[] = {0.0f, 0.05f, 0.15f, 0.35f};
  for (int i = 0; i < 4; ++i) {
    Material m;
    m.diffuse = Vec3f(0.05f);
    m.specular = Vec3f(0.5f);
    m.shininess = 80;
    m.reflection = {0.85f, 0.8f, 0.7f};
    m.glossiness = gloss[i];
    scene.materials.push_back(m);
    scene.world.add_shape(Sphere{{-2.1f + 1.4f * float(i), 0.6f, 0}, 0.6f}, Mat4(1.0), i + 1);
  }
  scene.world.build();
  return scene;
}

}  // namespace

TESSERA_EXAMPLE(ex73_shadows_gloss, "73_shadows_gloss", "Hard and soft shadows, mirror and glossy reflection") {
  RenderSettings s;
  s.width = 360;
  s.height = 270;
  s.samples = 16;
  s.progress = false;
  Light point;
  point.position = {-0.5f, 5, 0.5f};
  point.color = Vec3f(0.85f);
  Light area = point;
  area.type = LightType::rect;
  area.position = {-1.5f, 5, -0.5f};  // a 2 x 2 square centered over the point light, shining down
  area.edge_u = {2, 0, 0};            // edge_u x edge_v = (0, -4, 0): it shines down
  area.edge_v = {0, 0, 2};
  area.samples = 4;
  gallery.add("73_hard_soft_shadows.png",
              examples::side_by_side({render(shadow_scene(point), s), render(shadow_scene(area), s)}),
              "Left: a point light casts hard shadows (visible(P, L) is 0 or 1). Right: a 2 x 2 area light sampled "
              "by 64 shadow rays per pixel averages visible(P, L_i) into an umbra and a penumbra.");
  s.width = 640;
  s.height = 280;
  gallery.add("73_glossy_mirror.png", render(gloss_scene(), s),
              "Glossiness 0 (a mirror), 0.05, 0.15 and 0.35: each pixel's 16 reflected rays spread in a Phong lobe "
              "around the mirror direction, the notes' 1/n sum of K_refl C_Ri.");
}
