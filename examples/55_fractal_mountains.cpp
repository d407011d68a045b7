// Example 55: Carpenter's fractal mountains (the notes). 1D: split a segment, move the midpoint to a random height,
// repeat for the halves, with a range of 1/2, then 1/4, 1/8, ... 2D: split a triangle into four through its edge
// midpoints and move those up or down the same way (each midpoint made once per edge, so no cracks). Also
// diamond-square on a grid, seen as a height map.
#include <fmt/format.h>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/fractal/draw.hpp"
#include "tessera/fractal/terrain.hpp"
#include "tessera/image/image_io.hpp"

namespace {

// Per-face colors for the flat-shaded view: the mean of the face's vertex colors (colored by height).
std::vector<tessera::Vec3f> face_colors(const tessera::PolyMesh& mesh) {
  std::vector<tessera::Vec3f> colors;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    tessera::Vec3 sum(0.0);
    for (uint32_t v : mesh.face(f)) sum += mesh.colors[v];
    colors.emplace_back(sum / double(mesh.face_size(f)));
  }
  return colors;
}

}  // namespace

TESSERA_EXAMPLE(ex55_fractal_mountains, "55_fractal_mountains",
                "Fractal mountains: 1D profile, 2D mountain, height map") {
  using namespace tessera;
  // (a) 1D profiles for three roughness values, layered like ridges (rougher in front).
  ImageRGBA profile(900, 360, Vec4f(0.85f, 0.92f, 1.0f, 1.0f));
  const PictureFrame frame{900, 360, 0, {0.0, -0.45, 1.0, 0.9}};
  const double roughness[] = {0.4, 0.5, 0.6};
  const Vec3f shades[] = {{0.55f, 0.6f, 0.7f}, {0.35f, 0.42f, 0.35f}, {0.2f, 0.22f, 0.18f}};
  for (int layer = 0; layer < 3; ++layer) {
    TerrainOptions options;
    options.depth = 9;
    options.roughness = roughness[layer];
    options.seed = uint64_t(7 + layer);
    const std::vector<double> h = midpoint_displacement_1d(options);
    std::vector<Vec2> outline;
    const double base = 0.12 - 0.12 * layer;
    for (size_t i = 0; i < h.size(); ++i) outline.push_back({double(i) / double(h.size() - 1), base + h[i]});
    outline.push_back({1.0, -0.45}), outline.push_back({0.0, -0.45});
    add_polygons(profile, {outline}, frame, shades[layer], true);
  }
  gallery.add("55_mountain_profile.png", to_rgb(profile),
              "1D midpoint displacement, 2^9 segments, range halving per level; ridges with roughness 0.4, 0.5, 0.6");

  // (b) the 2D triangle mountain, flat shaded and colored by height.
  TerrainOptions options;
  options.depth = 6;
  options.initial_range = 0.5;
  options.roughness = 0.55;
  options.seed = 3;
  const PolyMesh mountain = triangle_mountain(options);
  examples::MeshViewOptions preview;
  preview.width = 800, preview.height = 600;
  preview.wireframe = false;
  preview.background = {0.85f, 0.92f, 1.0f};
  preview.face_colors = face_colors(mountain);
  // Looking at the triangle's centroid from in front of its base edge and above.
  Camera camera;
  camera.center = {0.5, 0.05, -0.32};
  camera.eye = {0.5, 1.05, 1.25};
  camera.fovy = radians(40);
  camera.aspect = 800.0 / 600.0;
  preview.camera = camera;
  gallery.add("55_triangle_mountain.png", examples::render_mesh(mountain, preview),
              fmt::format("2D midpoint subdivision of a triangle, depth 6: {} triangles, {} shared vertices, no "
                          "cracks",
                          mountain.face_count(), mountain.vertex_count()));

  // (c) diamond-square height map and its mesh.
  options.depth = 8;
  options.roughness = 0.55;
  options.seed = 11;
  const Image<float> heights = diamond_square(options);
  ImageRGB map = height_map_picture(heights);
  gallery.add("55_height_map.png", map, "Diamond-square height map, 257 x 257, roughness 0.55, colored by height");
  options.depth = 6;
  const PolyMesh grid = height_map_mesh(diamond_square(options), 0.6);
  preview.face_colors = face_colors(grid);
  camera.center = {0.5, 0.0, 0.5};
  camera.eye = {0.5, 1.0, 1.75};
  preview.camera = camera;
  gallery.add("55_diamond_square_mesh.png", examples::render_mesh(grid, preview),
              "The same method on a 65 x 65 grid as a mesh: 8192 triangles");
}
