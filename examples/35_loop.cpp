// Loop subdivision of an icosahedron, levels 0-3 (the notes: edge points 3/8 (v1 + v2) + 1/8 (v3 + v4), vertex
// points (1 - k beta) v + beta sum(vi) with beta = 3/(8k)): 20, 80, 320 and 1280 triangles.
#include <string>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/subdiv/subdivide.hpp"

TESSERA_EXAMPLE(ex35_loop, "35_loop", "Loop subdivision of an icosahedron, levels 0-3") {
  using namespace tessera;
  const PolyMesh ico = make_icosahedron();
  examples::MeshViewOptions options;
  options.width = options.height = 320;
  for (int level = 0; level <= 3; ++level) {
    const PolyMesh mesh = loop_subdivide(ico, level);
    gallery.add("35_loop_level" + std::to_string(level) + ".png", examples::render_mesh(mesh, options),
                "Loop, level " + std::to_string(level) + ": " + std::to_string(mesh.face_count()) + " triangles.");
  }
}
