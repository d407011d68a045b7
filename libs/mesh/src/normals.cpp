#include "tessera/mesh/normals.hpp"

#include <cmath>

namespace tessera {
namespace {
Vec3 normalized_or_zero(const Vec3& v) {
  const double len = glm::length(v);
  return len > 0 && std::isfinite(len) ? v / len : Vec3(0.0);
}
}  // namespace

Vec3 face_area_vector(const PolyMesh& mesh, size_t f) {
  const auto face = mesh.face(f);
  const Vec3& p0 = mesh.positions[face[0]];
  Vec3 sum(0.0);
  for (size_t i = 1; i + 1 < face.size(); ++i)
    sum += glm::cross(mesh.positions[face[i]] - p0, mesh.positions[face[i + 1]] - p0);
  return 0.5 * sum;
}

Vec3 face_normal(const PolyMesh& mesh, size_t f) { return normalized_or_zero(face_area_vector(mesh, f)); }

std::vector<Vec3> face_normals(const PolyMesh& mesh) {
  std::vector<Vec3> normals(mesh.face_count());
  for (size_t f = 0; f < normals.size(); ++f) normals[f] = face_normal(mesh, f);
  return normals;
}

std::vector<Vec3> vertex_normals(const PolyMesh& mesh, NormalWeighting weighting) {
  std::vector<Vec3> sums(mesh.vertex_count(), Vec3(0.0));
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    const Vec3 area = face_area_vector(mesh, f);
    if (weighting == NormalWeighting::Area) {
      for (uint32_t v : face) sums[v] += area;
      continue;
    }
    const Vec3 n = normalized_or_zero(area);
    const size_t k = face.size();
    for (size_t i = 0; i < k; ++i) {
      const Vec3& p = mesh.positions[face[i]];
      const Vec3 a = normalized_or_zero(mesh.positions[face[(i + 1) % k]] - p);
      const Vec3 b = normalized_or_zero(mesh.positions[face[(i + k - 1) % k]] - p);
      sums[face[i]] += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * n;
    }
  }
  for (Vec3& s : sums) s = normalized_or_zero(s);
  return sums;
}

void compute_vertex_normals(PolyMesh& mesh, NormalWeighting weighting) {
  mesh.normals = vertex_normals(mesh, weighting);
  mesh.corner_normals.clear();
}

}  // namespace tessera
