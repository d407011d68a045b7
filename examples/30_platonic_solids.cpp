// The five platonic solids and Tessera's other primitives, each flat-shaded with its edges, on one contact sheet.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"

namespace tessera::examples {
namespace {

/// Copies `tile` into `sheet` with its top-left corner at (x0, y0).
/// Renders meshes into a grid of `columns` tiles of size x size pixels.
ImageRGB contact_sheet(const std::vector<PolyMesh>& meshes, int columns, int size) {
  const int rows = int((meshes.size() + size_t(columns) - 1) / size_t(columns));
  ImageRGB sheet(columns * size, rows * size, Vec3f(1.0f));
  MeshViewOptions options;
  options.width = options.height = size;
  for (size_t i = 0; i < meshes.size(); ++i)
    paste(sheet, render_mesh(meshes[i], options), int(i % size_t(columns)) * size, int(i / size_t(columns)) * size);
  return sheet;
}

}  // namespace
}  // namespace tessera::examples

TESSERA_EXAMPLE(ex30_platonic_solids, "30_platonic_solids", "Platonic solids and primitive meshes") {
  using namespace tessera;
  gallery.add(
      "30_platonic_solids.png",
      examples::contact_sheet(
          {make_tetrahedron(), make_cube(), make_octahedron(), make_dodecahedron(), make_icosahedron()}, 5, 240),
      "The five platonic solids (tetrahedron, cube, octahedron, dodecahedron, icosahedron), circumradius 1.");
  gallery.add("30_primitives.png",
              examples::contact_sheet({make_uv_sphere(24, 12), make_quad_sphere(6), make_cylinder(24), make_cone(24),
                                       make_torus(1.0, 0.35, 32, 16), make_grid(8, 8)},
                                      3, 240),
              "Primitives: UV sphere (fans at the poles), quad sphere, cylinder, cone, torus and grid.");
}
