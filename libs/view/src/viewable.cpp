#include "tessera/view/viewable.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>

#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/curves/bpt.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/volume/volume_io.hpp"

namespace tessera {
namespace {

std::string lower_extension(const std::string& name) {
  std::string ext = std::filesystem::path(name).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::optional<ViewableKind> kind_of_extension(const std::string& ext) {
  if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl") return ViewableKind::mesh;
  if (ext == ".json") return ViewableKind::scene;
  if (ext == ".nrrd" || ext == ".nhdr" || ext == ".mhd" || ext == ".raw") return ViewableKind::volume;
  if (ext == ".bpt") return ViewableKind::patches;
  return std::nullopt;
}

/// Whether `name` has the form of make_procedural()'s names ("sphere:64"); the size is checked when it is made.
bool is_procedural_volume(const std::string& name) {
  constexpr std::array<std::string_view, 5> kShapes = {"sphere:", "torus:", "gyroid:", "metaballs:", "noise:"};
  return std::any_of(kShapes.begin(), kShapes.end(), [&](std::string_view s) { return name.starts_with(s); });
}

constexpr std::string_view kViewable =
    "a mesh (.obj .ply .off .stl), a scene (.json or a built-in scene's name), a volume (.nrrd .nhdr .mhd, or "
    "sphere:N torus:N gyroid:N metaballs:N noise:N) or Bezier patches (.bpt)";

}  // namespace

std::string_view kind_name(ViewableKind kind) {
  switch (kind) {
    case ViewableKind::mesh:
      return "mesh";
    case ViewableKind::scene:
      return "scene";
    case ViewableKind::volume:
      return "volume";
    case ViewableKind::patches:
      return "patches";
  }
  return "?";
}

ViewableKind viewable_kind(const std::string& name) {
  if (const auto kind = kind_of_extension(lower_extension(name))) return *kind;
  std::error_code ec;
  const bool exists = std::filesystem::exists(name, ec);
  if (!exists) {
    const std::vector<std::string> scenes = builtin_scene_names();
    if (std::find(scenes.begin(), scenes.end(), name) != scenes.end()) return ViewableKind::scene;
    if (is_procedural_volume(name)) return ViewableKind::volume;
    throw IoError(
        fmt::format("{}: no such file, built-in scene or procedural volume (expected {}; built-in scenes: "
                    "{})",
                    printable(name), kViewable, fmt::join(scenes, ", ")));
  }
  throw InvalidInput(
      fmt::format("{}: cannot tell what to view from its extension: expected {}", printable(name), kViewable));
}

Viewable read_viewable(const std::string& name) {
  Viewable v;
  v.kind = viewable_kind(name);
  v.name = name;
  switch (v.kind) {
    case ViewableKind::mesh:
      v.mesh = read_mesh(name);
      if (v.mesh.face_count() == 0)
        throw InvalidInput(fmt::format("{}: the mesh has no faces to view", printable(name)));
      break;
    case ViewableKind::scene:
      v.scene = load_scene_or_builtin(name);
      break;
    case ViewableKind::volume: {
      if (lower_extension(name) == ".raw")
        throw InvalidInput(
            fmt::format("{}: raw voxels have no layout; view the .mhd or .nhdr header that describes "
                        "them (tessera volume --dims reads bare raw files)",
                        printable(name)));
      Volume<float> volume = to_float(read_volume(name));
      const glm::ivec3 d = volume.dims();
      if (d.x < 2 || d.y < 2 || d.z < 2)
        throw InvalidInput(fmt::format("{}: a volume of {}x{}x{} voxels has no inside to view (at least 2 per axis)",
                                       printable(name), d.x, d.y, d.z));
      v.volume = std::make_shared<Volume<float>>(std::move(volume));
      break;
    }
    case ViewableKind::patches:
      v.patches = read_bpt(name);
      if (v.patches.empty()) throw InvalidInput(fmt::format("{}: no patches to view", printable(name)));
      break;
  }
  return v;
}

}  // namespace tessera
