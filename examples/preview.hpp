#pragma once
// A small z-buffered, flat-shaded mesh preview with an optional wireframe overlay, for the gallery's pictures of
// meshes, subdivision surfaces, patches and terrains until the 3D pipeline (raster3d) exists.
#include <optional>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera::examples {

struct PreviewOptions {
  int width = 400, height = 400;
  std::optional<Camera> camera;              ///< default: frame the mesh's bounding sphere from (1, 0.8, 1.6)
  Vec3f color{0.75f, 0.78f, 0.85f};          ///< surface color
  Vec3f background{1.0f, 1.0f, 1.0f};
  Vec3 light_dir{0.4, 0.8, 0.6};             ///< toward the light, world space (headlight-ish default)
  bool wireframe = true;                     ///< draw the polygon edges over the surface
  Vec3f wire_color{0.1f, 0.1f, 0.2f};
  std::vector<Vec3f> face_colors;            ///< optional per-face colors (overrides `color`)
};

/// Renders a polygon mesh: flat shading, z-buffer, back faces shaded darker, wireframe edges with depth test; polygons
/// are fan-triangulated, faces with a vertex outside the near/far range are skipped. The camera's aspect is set from
/// width / height. Rendered with 2 x 2 samples per pixel.
ImageRGB render_preview(const PolyMesh& mesh, const PreviewOptions& options = {});

}  // namespace tessera::examples
