#pragma once
// The mesh-writing options shared by `mesh ...`, `mesh subdivide` and `patch`: -o, --ascii, --double, and the
// warning when the output format cannot hold a property of the mesh (docs/mesh.md).
#include <fmt/format.h>

#include <cstdio>
#include <string>

#include "command.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera::cli {

/// Where and how a command writes its mesh.
struct MeshOutput {
  std::string path;
  bool ascii = false;             ///< --ascii
  bool double_precision = false;  ///< --double
};

/// Adds -o/--output (required), --ascii and --double.
inline void add_mesh_output(CLI::App& command, MeshOutput& out) {
  command.add_option("-o,--output", out.path, "Output mesh (.obj, .ply, .off, .stl); the extension picks the format")
      ->required();
  command.add_flag("--ascii", out.ascii, "Write PLY and STL as text instead of binary");
  command.add_flag("--double", out.double_precision,
                   "PLY: store coordinates, normals and uvs as double (default float, as most tools write)");
}

/// Writes the mesh (atomically); first warns on stderr, by name, about every property the format cannot hold.
inline void write_mesh_output(const MeshOutput& out, const PolyMesh& mesh) {
  const MeshFormat format = mesh_format_from_path(out.path);
  for (const std::string& property : unsupported_properties(mesh, format))
    fmt::print(stderr, "tessera: warning: {}: the format cannot hold {}; they are dropped\n", out.path, property);
  write_mesh(out.path, mesh, {.binary = !out.ascii, .double_precision = out.double_precision});
}

}  // namespace tessera::cli
