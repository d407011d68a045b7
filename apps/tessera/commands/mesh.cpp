// tessera mesh info|convert|normals|smooth|subdivide|triangulate
#include "command.hpp"

namespace tessera::cli {

void setup_mesh_subdivide(CLI::App& mesh, CommonOptions& common);  // commands/mesh_subdivide.cpp

void setup_mesh(CLI::App& mesh, CommonOptions& common) {
  mesh.require_subcommand(1);
  setup_mesh_subdivide(mesh, common);
}

}  // namespace tessera::cli
