// Catmull-Clark subdivision of a cube, levels 0-3 (the notes: face points, edge points, the vertex rule
// v' = (E + F + (k-2) v)/k with E the mean of the neighbouring vertices): the cube rounds toward a sphere-like blob.
#include <string>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/subdiv/subdivide.hpp"

TESSERA_EXAMPLE(ex33_catmull_clark, "33_catmull_clark", "Catmull-Clark subdivision of a cube, levels 0-3") {
  using namespace tessera;
  const PolyMesh cube = make_cube();
  examples::MeshViewOptions options;
  options.width = options.height = 320;
  for (int level = 0; level <= 3; ++level) {
    const PolyMesh mesh = catmull_clark_subdivide(cube, level);
    gallery.add("33_catmull_clark_level" + std::to_string(level) + ".png", examples::render_mesh(mesh, options),
                "Catmull-Clark, level " + std::to_string(level) + ": " + std::to_string(mesh.face_count()) + " quads.");
  }
}
