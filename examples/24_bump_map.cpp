// Example 24: bump mapping (Blinn 1978; the notes: "add bumps to surface -> normals get changed", N' = N - (B_u P_s +
// B_v P_t)). The geometry stays flat or smooth, only the normal is tilted by the slopes of a height map B(u, v), so
// the silhouette keeps its shape ("fake bumps"). A sphere without and with dimples, and a wall of bricks: the shared
// data's brick texture as the height map (Gallery::data_file), else procedural bricks (and the caption says so).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/surface_shader.hpp"

namespace {

using namespace tessera;

/// Round dimples: height 1, lowered in disks on a grid (20 around the sphere, 10 pole to pole).
ImageRGBA dimples() {
  const int w = 512, h = 256;
  ImageRGBA image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float cx = std::fmod(x * 20.0f / w, 1.0f) - 0.5f, cy = std::fmod(y * 10.0f / h, 1.0f) - 0.5f;
      const float r = std::sqrt(cx * cx + cy * cy);
      const float value = r < 0.35f ? 1 - 0.6f * std::cos(r / 0.35f * 1.5707964f) : 1.0f;
      image(x, y) = glm::vec4(value, value, value, 1);
    }
  return image;
}

/// Bricks of 64 x 32 texels in running bond, vertical as in the shared brick photo; the joints bright (as the
/// photo's mortar) and the bricks darker toward their beveled middles.
ImageRGBA procedural_bricks() {
  ImageRGBA image(256, 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const int column = x / 32, by = (y + (column % 2) * 32) % 64, bx = x % 32;
      const int edge = std::min({bx, 31 - bx, by, 63 - by});
      const float value = edge < 2 ? 1.0f : std::max(0.0f, 0.6f - 0.2f * float(edge - 2));
      image(x, y) = glm::vec4(value, value, value, 1);
    }
  return image;
}

// The brick heights and whether they are the shared data's photo (else the stand-in).
std::pair<Texture2D, bool> brick_heights(examples::Gallery& gallery) {
  const auto png = gallery.data_file("textures/brick.png", "procedural bricks");
  return png ? std::pair(load_texture(*png), true) : std::pair(Texture2D(procedural_bricks()), false);
}

}  // namespace

TESSERA_EXAMPLE(ex24_bump_map, "24_bump_map", "Bump mapping: normals tilted by a height map's slopes") {
  const auto [brick_map, real_bricks] = brick_heights(gallery);
  const Texture2D dimple_map(dimples());
  const raster3d::VertexArrays sphere = raster3d::VertexArrays::from_mesh(to_tri_mesh(make_uv_sphere(128, 64)));
  const raster3d::UvTangents sphere_tangents = raster3d::uv_tangents(sphere.positions, sphere.uvs, sphere.indices);
  const raster3d::VertexArrays wall = raster3d::VertexArrays::from_mesh(to_tri_mesh(make_grid(1, 1)));
  const raster3d::UvTangents wall_tangents = raster3d::uv_tangents(wall.positions, wall.uvs, wall.indices);

  const int w = 260, h = 240, s = 2;
  const Mat4 projection = perspective(radians(40), double(w) / h, 0.5, 20);
  const Vec3 to_light(-0.6, 0.7, 0.5);
  struct Panel {
    const raster3d::VertexArrays* arrays;
    const raster3d::UvTangents* tangents;
    const Texture2D* bumps;
    float bump_scale;
    Mat4 model, view;
    Vec3f color;
  };
  const Mat4 front = look_at({0, 0.3, 3.4}, {0, 0, 0}, {0, 1, 0});
  // The wall: the xz grid stood up facing +z and turned a quarter so that the photo's vertical bricks lie
  // horizontally, seen from the front-right. The photo's mortar is bright: a negative scale sets it back.
  const Mat4 wall_model = rotate_z(radians(90)) * rotate_x(radians(90)) * scale(0.95, 1, 0.95);
  const Panel panels_spec[] = {{&sphere, nullptr, nullptr, 0, Mat4(1.0), front, {0.85f, 0.8f, 0.7f}},
                               {&sphere, &sphere_tangents, &dimple_map, 0.015f, Mat4(1.0), front, {0.85f, 0.8f, 0.7f}},
                               {&wall,
                                &wall_tangents,
                                &brick_map,
                                -0.015f,
                                wall_model,
                                look_at({1.3, 0.5, 3.0}, {0, 0, 0}, {0, 1, 0}),
                                {0.75f, 0.35f, 0.25f}}};
  std::vector<ImageRGB> panels;
  for (const Panel& p : panels_spec) {
    raster3d::SurfaceUniforms u;
    u.set_camera(projection, p.view, p.model);
    u.lighting = raster3d::PreparedLighting(examples::surface_lighting(to_light, p.view, 0.15f, 0.35f));
    u.color = p.color;
    u.maps.bump = p.bumps;
    u.maps.bump_scale = p.bump_scale;
    raster3d::Framebuffer fb(w * s, h * s);
    fb.clear({1, 1, 1});
    raster3d::draw_surface(fb, raster3d::RasterState{}, *p.arrays, u, p.tangents);
    panels.push_back(examples::downsample(fb.color_rgb(), s));
  }
  const std::string caption =
      "Bump mapping: a smooth sphere; the same sphere with dimples from a height map (its outline stays round: only "
      "the normals change); a flat wall with bricks (the brick texture as heights).";
  gallery.add("24_bump_map.png", examples::side_by_side(panels),
              real_bricks ? caption : examples::stand_in_caption("procedural bricks", "the brick photo", caption));
}
