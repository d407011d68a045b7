// Helpers for drawing one mesh: split facets, polygon edges, sphere framing.
#include "tessera/scene/mesh_view.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace tessera {

TriMesh split_faceted(const TriMesh& mesh) {
  TriMesh out;
  out.positions.reserve(mesh.indices.size());
  out.normals.reserve(mesh.indices.size());
  out.indices.reserve(mesh.indices.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* v = &mesh.indices[3 * t];
    const Vec3 a = mesh.positions[v[0]], b = mesh.positions[v[1]], c = mesh.positions[v[2]];
    const Vec3 cross = glm::cross(b - a, c - a);
    const double length = glm::length(cross);
    const Vec3 n = length > 0 ? cross / length : Vec3(0, 0, 1);
    for (int k = 0; k < 3; ++k) {
      out.indices.push_back(uint32_t(out.positions.size()));
      out.positions.push_back(mesh.positions[v[k]]);
      out.normals.push_back(n);
      if (!mesh.colors.empty()) out.colors.push_back(mesh.colors[v[k]]);
      if (!mesh.uvs.empty()) out.uvs.push_back(mesh.uvs[v[k]]);
    }
  }
  return out;
}

std::vector<std::pair<uint32_t, uint32_t>> polygon_edges(const PolyMesh& mesh) {
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (size_t i = 0; i < face.size(); ++i) {
      const uint32_t a = face[i], b = face[(i + 1) % face.size()];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return {edges.begin(), edges.end()};
}

double sphere_fit_distance(double radius, double half_angle, double margin) {
  return margin * radius / std::sin(half_angle);
}

Camera frame_sphere(Camera camera, const Vec3& center, double radius, const Vec3& direction, double margin) {
  const double distance = sphere_fit_distance(radius, camera.fovy / 2, margin);
  camera.center = center;
  camera.eye = center + distance * glm::normalize(direction);
  camera.near = std::max(distance - 1.5 * radius, 1e-3 * distance);
  camera.far = distance + 1.5 * radius;
  return camera;
}

}  // namespace tessera
