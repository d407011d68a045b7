// The gallery's mesh pictures through the library's mesh view, and the shadow examples' scene.
#include "mesh_view.hpp"

#include <algorithm>

#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"

namespace tessera::examples {
namespace {

/// A camera looking at the mesh's bounding sphere from direction (1, 0.8, 1.6), the sphere filling the view.
Camera frame_mesh(const PolyMesh& mesh) {
  const Bounds3 box = bounding_box(mesh);
  const Vec3 center = 0.5 * (box.lo + box.hi);
  double radius = 0;
  for (const Vec3& p : mesh.positions) radius = std::max(radius, glm::distance(p, center));
  return frame_sphere(Camera{}, center, std::max(radius, 1e-9), Vec3(1, 0.8, 1.6), 1.08);
}

MeshShading mesh_shading(raster3d::ShadingModel model) {
  switch (model) {
    case raster3d::ShadingModel::flat:
      return MeshShading::flat;
    case raster3d::ShadingModel::gouraud:
      return MeshShading::gouraud;
    case raster3d::ShadingModel::phong:
      return MeshShading::phong;
    default:
      return MeshShading::unlit;
  }
}

}  // namespace

ImageRGB render_mesh(const PolyMesh& mesh, const MeshViewOptions& o) {
  if (mesh.face_count() == 0) return ImageRGB(o.width, o.height, o.background);  // e.g. marching-cubes case 0
  Camera camera = o.camera ? *o.camera : frame_mesh(mesh);
  camera.aspect = double(o.width) / o.height;
  tessera::MeshViewOptions v;
  v.shading = mesh_shading(o.shading);
  v.color = o.color;
  v.face_colors = o.face_colors;
  v.specular = 0.15f;
  v.shininess = 24;
  v.material = o.material;
  v.specular_model = o.specular;
  v.background = o.background;
  v.light = {MeshLightKind::directional, o.light_dir, 0.8f};
  v.wireframe = o.wireframe ? MeshWireframe::over : MeshWireframe::none;
  v.wire_color = o.wire_color;
  v.wire_depth_offset = 1e-3;  // edges win over the surface they lie on (normalized device depth)
  v.two_sided = true;
  v.supersample = std::max(1, o.samples);
  v.turn_outward = false;  // the back faces show as such
  return tessera::render_mesh(mesh, camera, o.width, o.height, v).color;
}

PolyMesh with_face_normals(PolyMesh mesh) {
  mesh.corner_normals.clear();
  for (size_t f = 0; f < mesh.face_count(); ++f)
    mesh.corner_normals.insert(mesh.corner_normals.end(), mesh.face(f).size(), face_normal(mesh, f));
  return mesh;
}

raster3d::Lighting surface_lighting(const Vec3& to_light, const Mat4& view, float ambient, float specular) {
  raster3d::Lighting l;
  l.material = raster3d::Material::plastic(Vec3f(1), 24, specular);
  l.color_material = true;
  l.model_ambient = Vec3f(ambient);
  l.lights[0].position = Vec4f(Vec3f(glm::normalize(Mat3(view) * to_light)), 0);
  return l;
}

std::vector<SceneObject> shadow_scene() {
  const auto arrays = [](const PolyMesh& mesh) { return raster3d::VertexArrays::from_mesh(to_tri_mesh(mesh)); };
  return {
      {arrays(make_grid(1, 1)), scale(3, 1, 3), {0.85f, 0.85f, 0.8f}},
      {arrays(make_uv_sphere(48, 24)), translate(-0.9, 0.6, 0.4) * scale(0.6, 0.6, 0.6), {0.8f, 0.3f, 0.25f}},
      {arrays(make_torus(0.55, 0.18, 64, 24)), translate(0.9, 0.75, -0.2) * rotate_x(radians(75)), {0.3f, 0.5f, 0.8f}},
      {arrays(with_face_normals(make_box())),
       translate(0.1, 0.5, -1.3) * rotate_y(radians(30)) * scale(0.4, 0.5, 0.4),
       {0.9f, 0.75f, 0.3f}}};
}

std::vector<raster3d::ShadowVolume> caster_volumes(const std::vector<SceneObject>& objects, const Vec4f& light) {
  std::vector<raster3d::ShadowVolume> out;
  for (size_t k = 1; k < objects.size(); ++k) {
    std::vector<Vec3f> world;
    for (const Vec3f& p : objects[k].arrays.positions)
      world.push_back(Vec3f(transform_point(objects[k].model, Vec3(p))));
    out.push_back(raster3d::shadow_volume(world, objects[k].arrays.indices, light));
  }
  return out;
}

}  // namespace tessera::examples
