#pragma once
// Triangulation of polygons (the notes: "on each face, divide it into triangles by drawing s - 3 edges from one
// vertex" — right for convex faces; concave faces need ear clipping).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// True when the polygon, projected on its best-fit plane (Newell's normal), turns the same way at every corner
/// (collinear corners allowed). Degenerate polygons (zero area) count as convex.
bool is_convex_polygon(std::span<const Vec3> points);

/// Triangulates one simple polygon of s >= 3 points into s - 2 triangles of local indices, keeping its orientation:
/// the notes' fan from corner 0 (s - 3 diagonals) when convex, ear clipping in the best-fit plane when concave
/// (Meisters 1975; O(s^2)). A self-intersecting polygon still yields s - 2 triangles (best effort).
std::vector<std::array<uint32_t, 3>> triangulate_polygon(std::span<const Vec3> points);

/// Triangulates every face of a mesh (triangles are kept as they are). Per-vertex properties and subdivision tags
/// are kept; face-varying uvs and normals follow their corners.
PolyMesh triangulate(const PolyMesh& mesh);

}  // namespace tessera
