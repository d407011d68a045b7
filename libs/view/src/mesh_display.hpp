#pragma once
// A surface drawn through scene's MeshView with the viewer's shading keys (private to the view module): shared by the
// mesh, patch and iso-surface modes.
#include <memory>
#include <optional>
#include <string>

#include "tessera/glsl/program_files.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/scene/mesh_view.hpp"
#include "tessera/view/viewer.hpp"

namespace tessera::detail {

class MeshDisplay {
 public:
  /// The viewer's first shading, texture image (empty: a checkerboard of the uvs), up axis (the floor's) and GLSL
  /// program (compiled here: throws as ProgramFiles).
  explicit MeshDisplay(const ViewerOptions& o);
  /// Shows `mesh` (prepared once for every camera until the next call).
  void set_mesh(PolyMesh mesh);
  /// Renders the surface through `camera` into `out`.
  void render(const Camera& camera, ImageRGBA8& out) const;
  /// 1-6 (shading), w (edges), d (shadows), t (texture); true when the picture changes.
  bool key(int key);
  /// "gouraud, edges, shadows, texture" (or "program a.frag" and its last compile error) and the last refusal (a
  /// texture without uvs).
  std::string describe() const;
  /// Recompiles the program when its files changed (ViewerOptions::watch_shaders); true when the picture or the
  /// message changed.
  bool poll();
  size_t triangles() const { return view_ ? view_->triangle_count() : 0; }

 private:
  MeshViewOptions options() const;

  std::optional<MeshView> view_;
  ViewShading shading_;
  bool edges_ = false, shadows_ = false, textured_ = false, has_uvs_ = false;
  std::string texture_path_;
  int up_axis_;
  mutable std::shared_ptr<const Texture2D> texture_;  // read or made on first use
  std::unique_ptr<glsl::ProgramFiles> program_;       // the GLSL program, if any
  bool watch_ = false;
  std::string note_;
};

}  // namespace tessera::detail
