// Example 22: shadow mapping, the notes' 2-pass z-buffer (Williams 1978). Pass 1 renders the scene's depth from the
// light (left: near is dark); pass 2 renders from the camera and compares each visible point's depth in the light's
// view with the stored one. A coarse map gives hard, stair-stepped shadow edges (second); percentage-closer
// filtering of the same map averages the test over 5 x 5 texels (third): soft edges. A point light among the casters
// needs a map all around it: six faces, as for an environment cube map (right).
#include <algorithm>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster3d/surface_shader.hpp"

using namespace tessera;

TESSERA_EXAMPLE(ex22_shadow_map, "22_shadow_map", "Shadow mapping: the light's depth map, hard and filtered shadows") {
  const std::vector<examples::SceneObject> objects = examples::shadow_scene();
  const Vec3 to_light = glm::normalize(Vec3(-0.7, 1.0, 0.5));
  const Mat4 light = raster3d::ShadowMap::directional(to_light, {-3, 0, -3}, {3, 1.5, 3});
  raster3d::ShadowMap map(128, light);  // coarse on purpose: its texels show at the shadow edges
  for (const examples::SceneObject& o : objects) map.draw(o.arrays, o.model);

  const int w = 300, h = 240, s = 2;
  std::vector<ImageRGB> panels;
  // The light's depths over the range they cover, near dark.
  const DepthImage depth = map.depth_image();
  float lo = 1, hi = 0;
  for (const float d : depth.pixels())
    if (d < 1) lo = std::min(lo, d), hi = std::max(hi, d);
  ImageRGB depth_picture(h, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < h; ++x) {
      const float d = depth(x * depth.width() / h, y * depth.height() / h);
      depth_picture(x, y) = Vec3f(d < 1 ? 0.1f + 0.9f * (d - lo) / std::max(hi - lo, 1e-6f) : 1.0f);
    }
  panels.push_back(depth_picture);

  const Mat4 projection = perspective(radians(45), double(w) / h, 0.5, 30);
  const Mat4 view = look_at({1.2, 3.4, 5.6}, {0, 0.3, 0}, {0, 1, 0});
  // The scene lit by `lighting` (light 0 shadowed by `shadows` with filter radius pcf).
  const auto render = [&](const raster3d::Lighting& lighting, const raster3d::ShadowMap& shadows, int pcf) {
    raster3d::Framebuffer fb(w * s, h * s);
    fb.clear({1, 1, 1});
    for (const examples::SceneObject& o : objects) {
      raster3d::SurfaceUniforms u;
      u.set_camera(projection, view, o.model);
      u.lighting = raster3d::PreparedLighting(lighting);
      u.color = o.color;
      u.maps.shadows[0] = &shadows;
      u.maps.shadow_pcf = pcf;
      raster3d::draw_surface(fb, raster3d::RasterState{}, o.arrays, u);
    }
    return examples::downsample(fb.color_rgb(), s);
  };
  for (const int pcf : {0, 2}) panels.push_back(render(examples::surface_lighting(to_light, view, 0.25f), map, pcf));

  // A point light low among the casters (the floor only receives): six faces of 256 x 256 around it.
  const Vec3 bulb(0.1, 0.5, 0.3);
  raster3d::ShadowMap around = raster3d::ShadowMap::point(512, bulb, {-1.5, 0, -1.7}, {1.6, 1.3, 1.0});
  for (size_t k = 1; k < objects.size(); ++k) around.draw(objects[k].arrays, objects[k].model);
  raster3d::Lighting point_light = examples::surface_lighting(to_light, view, 0.2f);
  point_light.lights[0].position = Vec4f(Vec3f(view * Vec4(bulb, 1.0)), 1.0f);
  panels.push_back(render(point_light, around, 1));
  gallery.add(
      "22_shadow_map.png", examples::side_by_side(panels),
      "Shadow mapping: pass 1, the light's depth map (128 x 128, near dark); pass 2 with the plain depth test "
      "(hard, stair-stepped edges from the map's texels) and with percentage-closer filtering over 5 x 5 texels "
      "(soft edges); a point light among the casters, shadowing all around through a map of six faces.");
}
