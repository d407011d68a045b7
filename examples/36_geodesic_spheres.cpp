// Geodesic spheres (the notes' face subdivision): split every triangle of an octahedron or icosahedron into four at
// its edge midpoints and push the new vertices out onto the unit sphere, level after level.
#include <string>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/subdiv/subdivide.hpp"

TESSERA_EXAMPLE(ex36_geodesic_spheres, "36_geodesic_spheres", "Geodesic spheres from the octahedron and icosahedron") {
  using namespace tessera;
  examples::MeshViewOptions options;
  options.width = options.height = 320;
  const struct {
    const char* name;
    PolyMesh base;
  } bases[] = {{"octahedron", make_octahedron()}, {"icosahedron", make_icosahedron()}};
  for (const auto& [name, base] : bases)
    for (int level = 1; level <= 3; ++level) {
      const PolyMesh sphere = geodesic_sphere(base, level);
      gallery.add("36_geodesic_" + std::string(name) + "_level" + std::to_string(level) + ".png",
                  examples::render_mesh(sphere, options),
                  "Geodesic sphere from the " + std::string(name) + ", level " + std::to_string(level) + ": " +
                      std::to_string(sphere.face_count()) + " triangles.");
    }
}
