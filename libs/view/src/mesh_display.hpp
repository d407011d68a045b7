#pragma once
// A surface drawn through scene's MeshView with the viewer's shading keys (private to the view module): shared by the
// mesh, patch and iso-surface modes.
#include <memory>
#include <optional>
#include <string>

#include "tessera/image/texture.hpp"
#include "tessera/scene/mesh_view.hpp"
#include "tessera/view/viewer.hpp"

namespace tessera::detail {

class MeshDisplay {
 public:
  /// The first shading, the texture image to use (empty: a checkerboard of the uvs) and the up axis (the floor's).
  MeshDisplay(ViewShading shading, const std::string& texture, int up_axis);
  /// Shows `mesh` (prepared once for every camera until the next call).
  void set_mesh(PolyMesh mesh);
  /// Renders the surface through `camera` into `out`.
  void render(const Camera& camera, ImageRGBA8& out) const;
  /// 1-6 (shading), w (edges), d (shadows), t (texture); true when the picture changes.
  bool key(int key);
  /// "gouraud, edges, shadows, texture" and the last refusal (a texture without uvs).
  std::string describe() const;
  size_t triangles() const { return view_ ? view_->triangle_count() : 0; }

 private:
  MeshViewOptions options() const;

  std::optional<MeshView> view_;
  ViewShading shading_;
  bool edges_ = false, shadows_ = false, textured_ = false, has_uvs_ = false;
  std::string texture_path_;
  int up_axis_;
  mutable std::shared_ptr<const Texture2D> texture_;  // read or made on first use
  std::string note_;
};

}  // namespace tessera::detail
