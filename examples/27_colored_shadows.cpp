// Example 27: shadow volumes for several lights, drawn as GPUs draw them: a first pass with what casts no shadow
// (the ambient light) writes depth; then, for each light, the stencil buffer counts that light's volumes and a pass
// adds the light's own diffuse and specular terms where the count is 0, blended (one, one) onto the pixels. Two
// lights from the left, a warm one from behind and a cool one from the front: each caster throws two shadows, each
// lit by the other light only (blue and orange), and where both overlap only the ambient light is left (dark).
#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster3d/surface_shader.hpp"

using namespace tessera;

TESSERA_EXAMPLE(ex27_colored_shadows, "27_colored_shadows",
                "Shadow volumes for two lights: one stencil count and one additive pass per light") {
  const std::vector<examples::SceneObject> objects = examples::shadow_scene();
  struct ColoredLight {
    Vec3 to_light;
    Vec3f color;
  };
  const ColoredLight lights[] = {{glm::normalize(Vec3(-0.9, 0.9, -0.6)), {0.75f, 0.5f, 0.25f}},
                                 {glm::normalize(Vec3(-0.5, 0.9, 0.9)), {0.2f, 0.35f, 0.65f}}};
  std::vector<std::vector<raster3d::ShadowVolume>> volumes;
  for (const ColoredLight& l : lights)
    volumes.push_back(examples::caster_volumes(objects, Vec4f(Vec3f(l.to_light), 0)));

  const int w = 480, h = 360, s = 2;
  const Mat4 projection = infinite_perspective(radians(50), double(w) / h, 0.02);
  const Mat4 view = look_at({0.9, 2.8, 4.6}, {0, 0.2, -0.2}, {0, 1, 0});
  raster3d::Framebuffer fb(w * s, h * s);
  fb.clear({1, 1, 1});
  raster3d::draw_lights_with_shadow_volumes(fb, volumes, Mat4f(projection * view), raster3d::ShadowCount::zfail,
                                            [&](const raster3d::RasterState& state, int light) {
                                              // The ambient pass: no lights. A light's pass: that light alone, no
                                              // ambient.
                                              raster3d::Lighting lighting;
                                              if (light < 0) {
                                                lighting = examples::surface_lighting(Vec3(0, 1, 0), view, 0.2f, 0.3f);
                                                lighting.light_count = 0;
                                              } else {
                                                const ColoredLight& l = lights[size_t(light)];
                                                lighting = examples::surface_lighting(l.to_light, view, 0.0f, 0.3f);
                                                lighting.lights[0].diffuse = lighting.lights[0].specular = l.color;
                                              }
                                              for (const examples::SceneObject& o : objects) {
                                                raster3d::SurfaceUniforms u;
                                                u.set_camera(projection, view, o.model);
                                                u.lighting = raster3d::PreparedLighting(lighting);
                                                u.color = o.color;
                                                raster3d::draw_surface(fb, state, o.arrays, u);
                                              }
                                            });
  gallery.add(
      "27_colored_shadows.png", examples::downsample(fb.color_rgb(), s),
      "Shadow volumes for two lights from the left, a warm one from behind and a cool one from the front: an ambient "
      "pass, then per light a stencil count of its volumes and an additive pass (blending one, one) where the "
      "count is 0. Each caster's two shadows are lit by the other light only; where they overlap, only the "
      "ambient light is left.");
}
