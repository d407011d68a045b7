// Transparency and refraction (the notes' "Transparent Surfaces"): spheres of the notes' index table, and Snell's
// window, total internal reflection seen from under water.
#include "gallery.hpp"
#include "tessera/raytrace/render.hpp"

TESSERA_EXAMPLE(ex71_refraction, "71_refraction", "Refraction by Snell's law and total internal reflection") {
  using namespace tessera;
  RenderSettings s;
  s.width = 640;
  s.height = 240;
  s.samples = 4;
  s.max_depth = 8;
  s.progress = false;

  // Five spheres in front of a striped wall: water, ice, glass, diamond and (for contrast) air.
  {
    RayScene scene;
    scene.camera.eye = {0, 1.2, 7};
    scene.camera.center = {0, 1, 0};
    scene.camera.fovy = radians(30);
    scene.ambient = Vec3f(0.25f);
    scene.lights = {Light{}};
    scene.lights[0].position = {2, 6, 6};
    scene.lights[0].color = Vec3f(0.8f);
    Material wall;
    wall.diffuse = {0.9f, 0.9f, 0.85f};
    wall.checker = 0.25f;
    wall.checker_color = {0.1f, 0.2f, 0.5f};
    scene.materials.push_back(wall);
    scene.world.add_shape(Plane{{0, 0, -2}, {0, 0, 1}}, Mat4(1.0), 0);
    scene.world.add_shape(Plane{{0, 0, 0}, {0, 1, 0}}, Mat4(1.0), 0);
    const float indices[] = {ior::kAir, ior::kWater, ior::kIce, ior::kGlass, ior::kDiamond};
    for (int i = 0; i < 5; ++i) {
      Material m;
      m.diffuse = Vec3f(0.0f);
      m.ambient = Vec3f(0.0f);
      m.specular = Vec3f(0.8f);
      m.shininess = 150;
      m.transmission = Vec3f(1.0f);
      m.fresnel = true;
      m.ior = indices[i];
      scene.materials.push_back(m);
      scene.world.add_shape(Sphere{{-2.4f + 1.2f * float(i), 1.0f, 0.5f}, 0.5f}, Mat4(1.0), i + 1);
    }
    scene.world.build();
    gallery.add("71_refraction_indices.png", render(scene, s),
                "Spheres of index 1.0003 (air), 1.33 (water), 1.3 (ice), 1.5 (glass) and 2.4 (diamond), the notes' "
                "table: the larger the index, the stronger the bending and the smaller the inverted image.");
  }

  // Under water looking up: within the critical angle asin(1/1.33) = 48.8 degrees of the vertical the surface
  // refracts the sky and the balls above it into a disk (Snell's window); beyond it the surface is a perfect mirror
  // (total internal reflection) showing the pool's tiled floor.
  {
    RayScene scene;
    scene.camera.eye = {0, -2.5, 0};
    scene.camera.center = {0, 0, -1.6};
    scene.camera.fovy = radians(100);
    scene.ambient = Vec3f(0.6f);
    scene.background = {0.5f, 0.75f, 1.0f};
    Material water;
    water.diffuse = Vec3f(0.0f);
    water.ambient = Vec3f(0.0f);
    water.transmission = Vec3f(1.0f);
    water.ior = ior::kWater;
    Material tiles;
    tiles.diffuse = {0.2f, 0.6f, 0.7f};
    tiles.checker = 1.0f;
    tiles.checker_color = {0.9f, 0.95f, 1.0f};
    Material ball;
    ball.diffuse = {0.95f, 0.3f, 0.1f};
    scene.materials = {water, tiles, ball};
    scene.world.add_shape(Box{{-1000, -6, -1000}, {1000, 0, 1000}}, Mat4(1.0),
                          0);                                           // the pool's water; its top is the surface
    scene.world.add_shape(Plane{{0, -5, 0}, {0, 1, 0}}, Mat4(1.0), 1);  // the pool's floor, inside the water
    for (int i = 0; i < 3; ++i)
      scene.world.add_shape(Sphere{{-2.0f + 2.0f * float(i), 2.0f, -4.0f}, 0.7f}, Mat4(1.0), 2);
    scene.world.build();
    s.width = 480;
    s.height = 360;
    gallery.add("71_snells_window.png", render(scene, s),
                "Snell's window: from under water the sky and the balls above appear inside a cone of half-angle "
                "48.8 degrees; outside it the surface totally reflects the tiled floor.");
  }
}
