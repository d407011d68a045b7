// Example 41: the notes' parametric surfaces, (s, t) -> point, tessellated on a grid: the parallelogram
// p1 + s (p2 - p1) + t (p3 - p1), the cylinder (cos s, sin s, t) and the sphere (cos t cos s, cos t sin s, sin t).
// The grid lines are the curves s = const and t = const.
#include <vector>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/curves/surface.hpp"

namespace tessera::examples {
namespace {

// The tessellation as quads (its triangles come in pairs a b c, a c d per grid cell), turned from the notes' z-up
// frame to the renderer's y-up one.
PolyMesh grid_quads(const TriMesh& tris) {
  PolyMesh quads;
  for (const Vec3& p : tris.positions) quads.positions.emplace_back(p.x, p.z, -p.y);
  for (size_t t = 0; t + 1 < tris.triangle_count(); t += 2) {
    const uint32_t* i = &tris.indices[3 * t];
    quads.add_face({i[0], i[1], i[2], i[5]});
  }
  return quads;
}

}  // namespace
}  // namespace tessera::examples

TESSERA_EXAMPLE(ex41_parametric_surfaces, "41_parametric_surfaces",
                "Parametric surfaces: parallelogram, cylinder, "
                "sphere") {
  using namespace tessera;
  const std::vector<TriMesh> surfaces{
      tessellate(parallelogram(Vec3(-1, -0.8, 0), Vec3(1.2, -0.8, 0.3), Vec3(-0.4, 0.9, 0)), 8, 8),
      tessellate(cylinder(1, 2), 24, 6), tessellate(sphere(1), 24, 12)};
  const int size = 300;
  ImageRGB sheet(3 * size, size, Vec3f(1.0f));
  examples::MeshViewOptions options;
  options.width = options.height = size;
  for (size_t i = 0; i < surfaces.size(); ++i)
    examples::paste(sheet, examples::render_mesh(examples::grid_quads(surfaces[i]), options), int(i) * size);
  gallery.add("41_parametric_surfaces.png", sheet,
              "Parametric surfaces of the notes on (s, t) grids: a parallelogram (8 x 8), a cylinder with s the "
              "angle and t the height (24 x 6, open, its inside darker), a sphere with s the longitude and t the "
              "latitude (24 x 12; the rows at the poles collapse to a point).");
}
