#include "tessera/mesh/measure.hpp"

#include "normal_scale.hpp"

namespace tessera {

Bounds3 bounding_box(const PolyMesh& mesh) {
  Bounds3 box;
  for (const Vec3& p : mesh.positions) {
    box.lo = glm::min(box.lo, p);
    box.hi = glm::max(box.hi, p);
  }
  return box;
}

double surface_area(const PolyMesh& mesh) {
  double area = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) area += detail::face_area(mesh, f);
  return area;
}

double signed_volume(const PolyMesh& mesh) {
  double volume = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    const Vec3& p0 = mesh.positions[face[0]];
    for (size_t i = 1; i + 1 < face.size(); ++i)
      volume += glm::dot(p0, glm::cross(mesh.positions[face[i]], mesh.positions[face[i + 1]]));
  }
  return volume / 6.0;
}

}  // namespace tessera
