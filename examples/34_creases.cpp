// Sharp and semi-sharp creases (the notes; DeRose, Kass and Truong 1998): the cube's top edges, one vertical edge
// and one bottom corner tagged with sharpness s, subdivided three times with Catmull-Clark. s = 0.5 and 1 soften
// quickly, s = 2 and 3 keep the crease for 2 and 3 levels, s >= 10 (infinitely sharp) keeps it forever.
#include <fmt/format.h>

#include <string>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/subdiv/subdivide.hpp"
#include "tessera/subdiv/topology.hpp"

namespace {

// The cube with the edges of its top face (largest y), one vertical edge and the lowest vertex tagged with s.
tessera::PolyMesh creased_cube(float s) {
  using namespace tessera;
  PolyMesh cube = make_cube();
  size_t top = 0;
  auto height = [&](size_t f) {
    double y = 0;
    for (uint32_t v : cube.face(f)) y += cube.positions[v].y;
    return y;
  };
  for (size_t f = 1; f < cube.face_count(); ++f)
    if (height(f) > height(top)) top = f;
  const auto face = cube.face(top);
  for (size_t i = 0; i < face.size(); ++i) cube.creases.push_back({face[i], face[(i + 1) % face.size()], s});
  const TopologyTables t(cube.face_offsets, cube.face_vertices, cube.vertex_count());
  for (uint32_t i = 0; i < t.ring_edge_count(face[0]); ++i)
    if (cube.positions[t.ring_neighbor(face[0], i)].y < cube.positions[face[0]].y)
      cube.creases.push_back({face[0], t.ring_neighbor(face[0], i), s});
  uint32_t lowest = 0;
  for (uint32_t v = 1; v < cube.vertex_count(); ++v)
    if (cube.positions[v].y < cube.positions[lowest].y - 1e-9) lowest = v;
  cube.corners.push_back({lowest, s});
  return cube;
}

}  // namespace

TESSERA_EXAMPLE(ex34_creases, "34_creases", "Sharp and semi-sharp creases and corners (Catmull-Clark, level 3)") {
  using namespace tessera;
  examples::MeshViewOptions options;
  options.width = options.height = 320;
  for (float s : {0.0f, 0.5f, 1.0f, 2.0f, 3.0f, 10.0f}) {
    const PolyMesh mesh = catmull_clark_subdivide(creased_cube(s), 3);
    const std::string name = s >= 10.0f ? "inf" : fmt::format("{:g}", s);
    gallery.add("34_creases_s" + name + ".png", examples::render_mesh(mesh, options),
                s >= 10.0f  ? std::string("Infinitely sharp creases and corner: the tagged edges never soften.")
                : s == 0.0f ? std::string("Sharpness 0: no crease, the smooth Catmull-Clark surface (level 3).")
                            : fmt::format("Crease and corner sharpness {:g}: the sharp rule {:g} time(s), then smooth "
                                          "(three Catmull-Clark levels).",
                                          s, s));
  }
}
