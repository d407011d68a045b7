#pragma once
// Indexed face sets: PolyMesh (faces of any valence) and TriMesh (triangles, what the renderers draw).
//
// Topology is flat integer arrays (cache-friendly, as the corner table's V and O); properties are parallel arrays.
// Per-vertex properties are either empty or exactly one per vertex. Face-varying properties (an OBJ's vt/vn whose
// indices differ from the vertex's, e.g. at texture seams) are one per face corner, parallel to face_vertices.
#include <cstdint>
#include <span>
#include <vector>

#include "tessera/math/types.hpp"

namespace tessera {

/// A sharp or semi-sharp edge tag (OpenSubdiv's `t crease`): the edge v0-v1 with sharpness s (>= 10 = infinite).
struct EdgeCrease {
  uint32_t v0, v1;
  float sharpness;
};

/// A sharp vertex tag (OpenSubdiv's `t corner`).
struct VertexCorner {
  uint32_t v;
  float sharpness;
};

/// A polygon mesh: face f uses vertices face_vertices[face_offsets[f] .. face_offsets[f+1]).
struct PolyMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> face_offsets{0};  ///< F + 1 entries, starting with 0
  std::vector<uint32_t> face_vertices;    ///< vertex index of every face corner, face by face

  std::vector<Vec3> normals;  ///< per vertex, or empty
  std::vector<Vec2> uvs;      ///< per vertex, or empty
  std::vector<Vec3> colors;   ///< per vertex (linear RGB in [0,1]), or empty

  std::vector<Vec2> corner_uvs;      ///< per face corner (parallel to face_vertices), or empty
  std::vector<Vec3> corner_normals;  ///< per face corner, or empty

  std::vector<EdgeCrease> creases;    ///< subdivision edge tags
  std::vector<VertexCorner> corners;  ///< subdivision vertex tags

  size_t vertex_count() const { return positions.size(); }
  size_t face_count() const { return face_offsets.size() - 1; }
  /// Number of vertices of face f.
  uint32_t face_size(size_t f) const { return face_offsets[f + 1] - face_offsets[f]; }
  /// The vertex indices of face f, in order (counterclockwise seen from outside).
  std::span<const uint32_t> face(size_t f) const { return {face_vertices.data() + face_offsets[f], face_size(f)}; }
  /// Appends a face.
  void add_face(std::span<const uint32_t> vertices) {
    face_vertices.insert(face_vertices.end(), vertices.begin(), vertices.end());
    face_offsets.push_back(uint32_t(face_vertices.size()));
  }
  void add_face(std::initializer_list<uint32_t> vertices) {
    add_face(std::span<const uint32_t>(vertices.begin(), vertices.size()));
  }
  /// True when every face is a triangle.
  bool is_triangle_mesh() const { return face_vertices.size() == 3 * face_count(); }
};

/// A triangle mesh with per-vertex properties only (seams already split): what renderers and ray tracers consume.
struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  ///< 3 per triangle, counterclockwise seen from outside
  std::vector<Vec3> normals;      ///< per vertex, or empty
  std::vector<Vec2> uvs;          ///< per vertex, or empty
  std::vector<Vec3> colors;       ///< per vertex, or empty

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace tessera
