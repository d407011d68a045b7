#include "tessera/mesh/convert.hpp"

#include <array>
#include <bit>
#include <unordered_map>

#include "bit_key.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera {
namespace {

/// A split vertex: the original vertex and the bit patterns of its corner's uv and normal.
using CornerKey = std::array<uint64_t, 6>;

}  // namespace

PolyMesh split_seams(const PolyMesh& mesh) {
  const bool corner_uv = !mesh.corner_uvs.empty(), corner_n = !mesh.corner_normals.empty();
  if (!corner_uv && !corner_n) return mesh;
  const size_t nv = mesh.vertex_count();
  const bool vertex_uv = !corner_uv && mesh.uvs.size() == nv && nv > 0;
  const bool vertex_n = !corner_n && mesh.normals.size() == nv && nv > 0;
  const bool colors = mesh.colors.size() == nv && nv > 0;
  PolyMesh out;
  out.face_offsets = mesh.face_offsets;
  out.face_vertices.reserve(mesh.face_vertices.size());
  std::vector<uint32_t> first_copy(nv, UINT32_MAX);
  std::unordered_map<CornerKey, uint32_t, detail::BitKeyHash> split;
  split.reserve(mesh.face_vertices.size());
  for (size_t c = 0; c < mesh.face_vertices.size(); ++c) {
    const uint32_t v = mesh.face_vertices[c];
    CornerKey key{v, 0, 0, 0, 0, 0};
    if (corner_uv) {
      key[1] = std::bit_cast<uint64_t>(mesh.corner_uvs[c].x);
      key[2] = std::bit_cast<uint64_t>(mesh.corner_uvs[c].y);
    }
    if (corner_n)
      for (int i = 0; i < 3; ++i) key[size_t(3 + i)] = std::bit_cast<uint64_t>(mesh.corner_normals[c][i]);
    const auto [it, inserted] = split.try_emplace(key, uint32_t(out.positions.size()));
    if (inserted) {
      if (first_copy[v] == UINT32_MAX) first_copy[v] = it->second;
      out.positions.push_back(mesh.positions[v]);
      if (corner_uv) out.uvs.push_back(mesh.corner_uvs[c]);
      if (vertex_uv) out.uvs.push_back(mesh.uvs[v]);
      if (corner_n) out.normals.push_back(mesh.corner_normals[c]);
      if (vertex_n) out.normals.push_back(mesh.normals[v]);
      if (colors) out.colors.push_back(mesh.colors[v]);
    }
    out.face_vertices.push_back(it->second);
  }
  for (const EdgeCrease& e : mesh.creases)
    if (first_copy[e.v0] != UINT32_MAX && first_copy[e.v1] != UINT32_MAX)
      out.creases.push_back({first_copy[e.v0], first_copy[e.v1], e.sharpness});
  for (const VertexCorner& k : mesh.corners)
    if (first_copy[k.v] != UINT32_MAX) out.corners.push_back({first_copy[k.v], k.sharpness});
  return out;
}

TriMesh to_tri_mesh(const PolyMesh& poly) {
  PolyMesh mesh = split_seams(poly.is_triangle_mesh() ? poly : triangulate(poly));
  TriMesh out;
  out.positions = std::move(mesh.positions);
  out.indices = std::move(mesh.face_vertices);
  out.normals = std::move(mesh.normals);
  out.uvs = std::move(mesh.uvs);
  out.colors = std::move(mesh.colors);
  return out;
}

PolyMesh to_poly_mesh(const TriMesh& mesh) {
  PolyMesh out;
  out.positions = mesh.positions;
  out.normals = mesh.normals;
  out.uvs = mesh.uvs;
  out.colors = mesh.colors;
  out.face_vertices = mesh.indices;
  out.face_offsets.resize(mesh.triangle_count() + 1);
  for (size_t t = 0; t <= mesh.triangle_count(); ++t) out.face_offsets[t] = uint32_t(3 * t);
  return out;
}

}  // namespace tessera
