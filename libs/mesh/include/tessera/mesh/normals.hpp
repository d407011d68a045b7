#pragma once
// Face and vertex normals (the notes: the face normal is E1 x E2 normalized, E1 = P1 - P0, E2 = P2 - P0).
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// How vertex normals average the normals of the faces around a vertex.
enum class NormalWeighting {
  area,   ///< weight by face area (sum of the unnormalized cross products)
  angle,  ///< weight by the face's interior angle at the vertex (Thürmer and Wüthrich 1998)
};

/// Half the sum of the cross products of a fan from corner 0: the vector area of face f (length = area for planar
/// faces, direction = normal; equals Newell's vector for any polygon). For a triangle it is (E1 x E2) / 2.
Vec3 face_area_vector(const PolyMesh& mesh, size_t f);

/// The unit normal of face f (E1 x E2 normalized for triangles, the normalized vector area for polygons);
/// (0, 0, 0) for a degenerate face.
Vec3 face_normal(const PolyMesh& mesh, size_t f);

/// Unit normals of all faces.
std::vector<Vec3> face_normals(const PolyMesh& mesh);

/// Unit vertex normals averaged from the faces around each vertex; (0, 0, 0) for unreferenced vertices.
std::vector<Vec3> vertex_normals(const PolyMesh& mesh, NormalWeighting weighting = NormalWeighting::area);

/// Sets mesh.normals to vertex_normals(mesh, weighting) and clears face-varying normals.
void compute_vertex_normals(PolyMesh& mesh, NormalWeighting weighting = NormalWeighting::area);

}  // namespace tessera
