#pragma once
// A lit picture of a polygon mesh, for the gallery's pictures of meshes, subdivision surfaces, patches, terrains and
// shading models: the library's mesh view (scene's MeshView, mesh_view.hpp) with the gallery's defaults, a framed
// camera, one directional light, the shading model of your choice, back faces shaded darker (two-sided lighting), and
// the polygon edges drawn over the surface; supersampled and box-filtered for smooth edges.
#include <optional>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/lighting.hpp"
#include "tessera/raster3d/shadow_volume.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera::examples {

/// The gallery's mesh pictures: what the examples set (the rest of the library's MeshViewOptions as the wrapper fixes
/// it: two-sided, a light of diffuse 0.8, a plastic of highlight 0.15 and shininess 24, edges pulled 1e-3 forward).
struct MeshViewOptions {
  int width = 400, height = 400;
  std::optional<Camera> camera;      ///< default: frame the mesh's bounding sphere from direction (1, 0.8, 1.6)
  Vec3f color{0.75f, 0.78f, 0.85f};  ///< surface color (ambient and diffuse)
  std::vector<Vec3f> face_colors;    ///< optional per-face colors (override `color`)
  Vec3f background{1.0f, 1.0f, 1.0f};
  Vec3 light_dir{0.4, 0.8, 0.6};  ///< toward the light, world space
  /// flat: one normal per polygon (facets); gouraud / phong: the mesh's vertex normals (computed when absent).
  raster3d::ShadingModel shading = raster3d::ShadingModel::flat;
  std::optional<raster3d::Material> material;  ///< default: a matte plastic of `color` with a faint highlight
  raster3d::SpecularModel specular = raster3d::SpecularModel::blinn;
  bool wireframe = true;  ///< draw the polygon edges over the surface
  Vec3f wire_color{0.1f, 0.1f, 0.2f};
  int samples = 2;  ///< supersampling per axis (1 = none)
};

/// Renders the mesh through tessera::render_mesh (polygons triangulated, the z-buffer): front faces lit, back faces
/// lit with the flipped normal at 55 % brightness, edges 1 output pixel wide on top. The camera's aspect is set from
/// width / height. A mesh without faces gives the background.
ImageRGB render_mesh(const PolyMesh& mesh, const MeshViewOptions& options = {});

/// The mesh with each face's normal on its corners (corner_normals): flat faces under per-pixel shading.
PolyMesh with_face_normals(PolyMesh mesh);

/// Box-filters s x s blocks of a supersampled picture (s = 1: the picture itself): the library's.
using ::tessera::downsample;

/// Lighting for raster3d's surface shaders: one white directional light toward `to_light` (world space; the light is
/// set in the eye space of `view`), model ambient `ambient`, the surface color as C_r (color material) and a white
/// plastic highlight of strength `specular`.
raster3d::Lighting surface_lighting(const Vec3& to_light, const Mat4& view, float ambient = 0.2f,
                                    float specular = 0.3f);

/// An object of the shadow examples' scene: its arrays (normals included), model matrix and color.
struct SceneObject {
  raster3d::VertexArrays arrays;
  Mat4 model;
  Vec3f color;
};

/// The scene of the shadow examples (22, 25): a 6 x 6 floor at y = 0 (first), then a sphere, a torus and a box over it.
std::vector<SceneObject> shadow_scene();

/// The shadow volumes of shadow_scene()'s casters (all but the floor, which only receives) for a light given
/// homogeneously in world space ((p, 1) a point light, (d, 0) a directional light shining along -d).
std::vector<raster3d::ShadowVolume> caster_volumes(const std::vector<SceneObject>& objects, const Vec4f& light);

}  // namespace tessera::examples
