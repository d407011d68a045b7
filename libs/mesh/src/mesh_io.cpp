// Format dispatch by extension, and file access for the mesh readers and writers.
#include "tessera/mesh/mesh_io.hpp"

#include <algorithm>
#include <array>
#include <cctype>

#include <fmt/format.h>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"

namespace tessera {

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  static constexpr std::array<std::pair<std::string_view, MeshFormat>, 4> kFormats{
      {{".obj", MeshFormat::Obj}, {".ply", MeshFormat::Ply}, {".off", MeshFormat::Off}, {".stl", MeshFormat::Stl}}};
  for (const auto& [e, format] : kFormats)
    if (e == ext) return format;
  throw InvalidInput(fmt::format("'{}': unknown mesh format (expected .obj, .ply, .off or .stl)", path.string()));
}

PolyMesh read_mesh(std::string_view data, MeshFormat format, const std::string& name) {
  switch (format) {
    case MeshFormat::Obj: return read_obj(data, name);
    case MeshFormat::Ply: return read_ply(data, name);
    case MeshFormat::Off: return read_off(data, name);
    case MeshFormat::Stl: return read_stl(data, name);
  }
  throw InvalidInput(fmt::format("{}: unknown mesh format", name));
}

PolyMesh read_mesh(const std::filesystem::path& path) {
  const MeshFormat format = mesh_format_from_path(path);
  return read_mesh(read_file(path), format, path.string());
}

void write_mesh(std::ostream& out, const PolyMesh& mesh, MeshFormat format, const MeshWriteOptions& options) {
  switch (format) {
    case MeshFormat::Obj: write_obj(out, mesh); return;
    case MeshFormat::Ply: write_ply(out, mesh, options.binary); return;
    case MeshFormat::Off: write_off(out, mesh); return;
    case MeshFormat::Stl: write_stl(out, mesh, options.binary); return;
  }
}

void write_mesh(const std::filesystem::path& path, const PolyMesh& mesh, const MeshWriteOptions& options) {
  const MeshFormat format = mesh_format_from_path(path);
  write_file_atomic(path, [&](std::ostream& out) { write_mesh(out, mesh, format, options); });
}

}  // namespace tessera
