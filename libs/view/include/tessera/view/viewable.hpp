#pragma once
// What `tessera view` can show, and how a name is told apart: a mesh, a scene, a volume or Bezier patches.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/curves/bezier_patch.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/scene/scene.hpp"
#include "tessera/volume/volume.hpp"

namespace tessera {

/// The four kinds of viewable things.
enum class ViewableKind {
  mesh,     ///< OBJ, PLY, OFF or STL (read_mesh)
  scene,    ///< a scene file (.json) or a built-in scene's name (libs/scene)
  volume,   ///< NRRD (.nrrd, .nhdr), MetaImage (.mhd) or a procedural name such as sphere:64 (libs/volume)
  patches,  ///< Bezier patches (.bpt, libs/curves)
};

/// The kind's name as the viewer prints it ("mesh", "scene", "volume", "patches").
std::string_view kind_name(ViewableKind kind);

/// What `name` is: by its extension (case-insensitive: .obj .ply .off .stl a mesh, .json a scene, .nrrd .nhdr .mhd
/// .raw a volume, .bpt patches), else a built-in scene's name or a procedural volume ("sphere:64") when no such file
/// exists. Throws IoError for a missing file with no such meaning, InvalidInput (listing what is viewable) for an
/// existing file with another extension.
ViewableKind viewable_kind(const std::string& name);

/// A thing to view, read. Only the member of its kind is set.
struct Viewable {
  ViewableKind kind = ViewableKind::mesh;
  std::string name;                       ///< as given (for messages and the status line)
  PolyMesh mesh;                          ///< mesh
  std::optional<Scene> scene;             ///< scene
  std::shared_ptr<Volume<float>> volume;  ///< volume (shared: the volume renderer keeps a pointer to it)
  std::vector<BezierPatch> patches;       ///< patches
};

/// Reads `name` as viewable_kind() says. Throws as viewable_kind() and as the readers (IoError, InvalidInput naming
/// the file); a raw volume, which needs a layout, is refused with a pointer to its header; an empty mesh, patch set
/// or volume is refused too (nothing to show).
Viewable read_viewable(const std::string& name);

}  // namespace tessera
