// The 15 base configurations of marching cubes (Lorensen & Cline), triangulated by Tessera's generated table, drawn
// as the textbook figure: each cell's surface (lit triangles with their edges; the side facing the inside corners is
// the darker back face), the cube's twelve edges over it (the three hidden behind the cube dashed), and every corner
// marked on top, the inside ones as filled blue dots, the outside ones as open circles. Cases left to right, top to
// bottom, in Lorensen and Cline's order (0 to 14).
#include <array>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/mc_table.hpp"

namespace {

using namespace tessera;

// The figure's camera: the unit cell [0, 1]^3 seen from beyond its corner (1, 1, 1), so corner (0, 0, 0) is the hidden
// one. examples/tests/gallery_test.cpp projects the corners with the same camera.
Camera cell_camera() {
  Camera cam;
  cam.center = {0.5, 0.5, 0.5};
  cam.eye = {2.6, 1.9, 3.2};
  cam.aspect = 1;
  cam.fovy = radians(32);
  return cam;
}

// A corner's pixel position in a size x size picture of cell_camera().
Vec2 project(const Mat4& view_projection, const glm::ivec3& corner, int size) {
  const glm::dvec4 clip = view_projection * glm::dvec4(Vec3(corner), 1.0);
  return {(clip.x / clip.w + 1) * 0.5 * size, (1 - clip.y / clip.w) * 0.5 * size};
}

// A dashed line of dashes and gaps `dash` pixels long.
void dashed_line(Canvas& canvas, const Vec2& a, const Vec2& b, double dash) {
  const double length = glm::length(b - a);
  for (double s = 0; s < length; s += 2 * dash) {
    const Vec2 p = a + (b - a) * (s / length), q = a + (b - a) * (std::min(s + dash, length) / length);
    canvas.line(p.x, p.y, q.x, q.y);
  }
}

// One case: the surface rendered by raster3d, then the cube's edges and corner markers drawn over it with the canvas.
ImageRGB case_picture(int cube_case, int size) {
  Volume<float> cube(glm::ivec3(2));
  for (int i = 0; i < 8; ++i) {
    const auto p = mc::corners()[size_t(i)];
    cube(p.x, p.y, p.z) = (cube_case >> i) & 1 ? 1.0f : 0.0f;
  }
  examples::MeshViewOptions options;
  options.width = options.height = size;
  options.color = {0.95f, 0.6f, 0.35f};
  options.camera = cell_camera();
  options.light_dir = {1.6, 2.2, 2.7};  // from over the viewer's shoulder: no face of the surface turns black
  const ImageRGB surface = examples::render_mesh(marching_cubes(cube, {.iso = 0.5f, .normals = false}), options);

  Canvas canvas(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) canvas.write_pixel(x, y, Vec4f(surface(x, y), 1.0f));
  const Mat4 view_projection = cell_camera().projection() * cell_camera().view();
  std::array<Vec2, 8> corner;
  for (int i = 0; i < 8; ++i) corner[size_t(i)] = project(view_projection, mc::corners()[size_t(i)], size);
  canvas.no_fill();
  canvas.stroke({0.05f, 0.05f, 0.05f, 1.0f});
  canvas.stroke_weight(2);
  for (const auto& [a, b] : mc::edges()) {
    const auto hidden = [](const glm::ivec3& c) { return c == glm::ivec3(0); };
    const Vec2 p = corner[size_t(a)], q = corner[size_t(b)];
    if (hidden(mc::corners()[size_t(a)]) || hidden(mc::corners()[size_t(b)]))
      dashed_line(canvas, p, q, 5);
    else
      canvas.line(p.x, p.y, q.x, q.y);
  }
  for (int i = 0; i < 8; ++i) {
    const Vec2 p = corner[size_t(i)];
    const bool inside = (cube_case >> i) & 1;
    canvas.stroke({0.05f, 0.05f, 0.05f, 1.0f});
    canvas.stroke_weight(1.5);
    canvas.fill(inside ? Vec4f(0.1f, 0.25f, 0.85f, 1.0f) : Vec4f(1.0f));
    canvas.ellipse(p.x, p.y, inside ? 15 : 9, inside ? 15 : 9);
  }
  ImageRGB picture(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) picture(x, y) = Vec3f(canvas.image()(x, y));
  return picture;
}

}  // namespace

TESSERA_EXAMPLE(ex61_marching_cubes_cases, "61_marching_cubes_cases", "The 15 base cases of marching cubes") {
  const int tile = 200;
  ImageRGB sheet(5 * tile, 3 * tile, Vec3f(1.0f));
  for (size_t k = 0; k < mc::base_cases().size(); ++k)
    examples::paste(sheet, case_picture(mc::base_cases()[k], tile), int(k % 5) * tile, int(k / 5) * tile);
  gallery.add("61_marching_cubes_cases.png", sheet,
              "Lorensen and Cline's 15 base cases, 0 to 14 left to right and top to bottom, triangulated by the "
              "generated table (the surface orange on its outer side, dark brown on the side facing the inside "
              "corners): each cube's edges in black (the three behind it dashed), inside corners as filled blue "
              "dots, outside corners as open circles.");
}
