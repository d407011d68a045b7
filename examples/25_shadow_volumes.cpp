// Example 25: shadow volumes, the notes' first way to shadows with rasterization (Crow 1977, counted in the stencil
// buffer). Each caster's silhouette, seen from the light, is extruded away from it to infinity; the stencil buffer
// counts how many volumes hold each visible point (left: white 0, then darker per volume), and the lit pass draws
// where the count is 0: shadows exact to the pixel, with no map resolution and no bias (second). With the eye inside
// a shadow, z-pass counting is off by one wherever the near plane cuts the volume (third: lit and shadowed swap);
// z-fail counting, behind the surface and with the volumes capped, is right wherever the eye is (right).
#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster3d/surface_shader.hpp"

using namespace tessera;

TESSERA_EXAMPLE(ex25_shadow_volumes, "25_shadow_volumes",
                "Shadow volumes: stencil counts, exact shadows, z-pass against z-fail with the eye in shadow") {
  const std::vector<examples::SceneObject> objects = examples::shadow_scene();
  const Vec3 to_light = glm::normalize(Vec3(-0.7, 1.0, 0.5));
  const std::vector<raster3d::ShadowVolume> shadow = examples::caster_volumes(objects, Vec4f(Vec3f(to_light), 0));
  const int w = 300, h = 240, s = 2;
  // Renders the scene from `eye` with the volumes counted by `count`; the stencil counts come back too.
  const auto render = [&](const Vec3& eye, const Vec3& center, raster3d::ShadowCount count, Image<uint8_t>* counts) {
    const Mat4 projection = infinite_perspective(radians(50), double(w) / h, 0.02);
    const Mat4 view = look_at(eye, center, {0, 1, 0});
    raster3d::Framebuffer fb(w * s, h * s);
    fb.clear({1, 1, 1});
    raster3d::draw_with_shadow_volumes(
        fb, shadow, Mat4f(projection * view), count, [&](const raster3d::RasterState& state, float light0) {
          for (const examples::SceneObject& o : objects) {
            raster3d::SurfaceUniforms u;
            u.set_camera(projection, view, o.model);
            u.lighting = raster3d::PreparedLighting(examples::surface_lighting(to_light, view, 0.25f));
            u.color = o.color;
            u.light0 = light0;
            raster3d::draw_surface(fb, state, o.arrays, u);
          }
        });
    if (counts) *counts = fb.stencil();
    return examples::downsample(fb.color_rgb(), s);
  };
  const Vec3 eye(1.2, 3.4, 5.6), center(0, 0.3, 0);
  Image<uint8_t> counts;
  const ImageRGB shadows = render(eye, center, raster3d::ShadowCount::zfail, &counts);
  ImageRGB count_picture(counts.width(), counts.height());
  for (int y = 0; y < counts.height(); ++y)
    for (int x = 0; x < counts.width(); ++x) count_picture(x, y) = Vec3f(1.0f - 0.3f * std::min<int>(counts(x, y), 3));
  // The eye low behind the sphere, in its shadow, looking across the scene.
  const Vec3 shadowed_eye(-0.5, 0.12, 0.12), across(2, 0.3, -1.5);
  gallery.add("25_shadow_volumes.png",
              examples::side_by_side({examples::downsample(count_picture, s), shadows,
                                      render(shadowed_eye, across, raster3d::ShadowCount::zpass, nullptr),
                                      render(shadowed_eye, across, raster3d::ShadowCount::zfail, nullptr)}),
              "Shadow volumes: the stencil counts (how many volumes hold each visible point, white 0); the lit pass "
              "where the count is 0 (exact edges, no map); the eye inside the sphere's shadow: z-pass counting (the "
              "near plane cuts the volume open: lit and shadowed swap) and z-fail counting (right).");
}
