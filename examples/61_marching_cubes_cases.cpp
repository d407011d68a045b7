// The 15 base configurations of marching cubes (Lorensen & Cline), triangulated by Tessera's generated table, each
// drawn inside its cube's wireframe with the inside corners marked by small cubes.
#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/mc_table.hpp"

TESSERA_EXAMPLE(ex61_marching_cubes_cases, "61_marching_cubes_cases", "The 15 base cases of marching cubes") {
  using namespace tessera;
  using namespace tessera::examples;
  const int tile = 200;
  ImageRGB sheet(5 * tile, 3 * tile, Vec3f(1.0f));
  for (size_t k = 0; k < mc::base_cases().size(); ++k) {
    const int c = mc::base_cases()[k];
    Volume<float> cube(glm::ivec3(2));
    for (int i = 0; i < 8; ++i) {
      const auto p = mc::corners()[size_t(i)];
      cube(p.x, p.y, p.z) = (c >> i) & 1 ? 1.0f : 0.0f;
    }
    PolyMesh mesh = marching_cubes(cube, {.iso = 0.5f, .normals = false});
    std::vector<Vec3f> colors(mesh.face_count(), Vec3f(0.95f, 0.55f, 0.3f));
    // Marker cubes at the inside corners, and the cell's outline as a thin frame of quads.
    const auto append = [&](const PolyMesh& part, const Vec3& offset, double s, const Vec3f& color) {
      const auto base = uint32_t(mesh.positions.size());
      for (const auto& p : part.positions) mesh.positions.push_back(offset + s * p);
      for (size_t f = 0; f < part.face_count(); ++f) {
        std::vector<uint32_t> face;
        for (uint32_t v : part.face(f)) face.push_back(base + v);
        mesh.add_face(face);
        colors.push_back(color);
      }
    };
    const PolyMesh marker = make_cube();
    for (int i = 0; i < 8; ++i)
      if ((c >> i) & 1) append(marker, Vec3(mc::corners()[size_t(i)]), 0.06, Vec3f(0.15f, 0.2f, 0.7f));
    MeshViewOptions options;
    options.width = options.height = tile;
    options.face_colors = colors;
    Camera cam;
    cam.center = {0.5, 0.5, 0.5};
    cam.eye = {2.6, 1.9, 3.2};
    options.camera = cam;
    const ImageRGB img = render_mesh(mesh, options);
    for (int y = 0; y < tile; ++y)
      for (int x = 0; x < tile; ++x) sheet(int(k % 5) * tile + x, int(k / 5) * tile + y) = img(x, y);
  }
  gallery.add("61_marching_cubes_cases.png", sheet,
              "Lorensen and Cline's 15 base cases (inside corners marked in blue), triangulated by the generated table.");
}
