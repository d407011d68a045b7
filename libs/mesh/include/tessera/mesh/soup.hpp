#pragma once
// Polygon soup (the notes: "no connectivity between faces", every face carries its own coordinates) and its
// conversion to and from an indexed face set by vertex welding, exact or within a tolerance (a spatial hash).
#include <cstdint>
#include <span>
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// A polygon soup: face f has the corner points points[face_offsets[f] .. face_offsets[f+1]).
struct PolygonSoup {
  std::vector<Vec3> points;
  std::vector<uint32_t> face_offsets{0};  ///< F + 1 entries, starting with 0

  size_t face_count() const { return face_offsets.size() - 1; }
  /// Appends a face given by its corner points.
  void add_face(std::span<const Vec3> corners) {
    points.insert(points.end(), corners.begin(), corners.end());
    face_offsets.push_back(uint32_t(points.size()));
  }
};

/// The result of welding points: the distinct points and, for every input point, the index of its representative.
struct WeldedPoints {
  std::vector<Vec3> points;
  std::vector<uint32_t> remap;  ///< one per input point
};

/// Merges points: tolerance 0 merges bit-identical coordinates (-0 == +0) with a hash map; tolerance > 0 maps a
/// point to the first earlier representative within that distance, found in a spatial hash of cell size
/// `tolerance` (27 cells looked at). Deterministic (input order). Throws InvalidInput for a negative tolerance.
WeldedPoints weld_points(std::span<const Vec3> points, double tolerance = 0);

/// Polygon soup -> indexed face set (the notes' "shared vertex" representation) by welding the corner points.
/// Faces that collapse below 3 distinct consecutive vertices are dropped.
PolyMesh weld(const PolygonSoup& soup, double tolerance = 0);

/// Indexed face set -> polygon soup (every face gets its own copies of its corner points).
PolygonSoup to_soup(const PolyMesh& mesh);

/// Merges coincident vertices of a mesh in place (see weld_points). Per-vertex uvs and normals that differ inside a
/// merged group (a texture seam, a crease, patches that each carry their own (u, v)) become face-varying, every
/// corner keeping its old vertex's value, so nothing is lost; otherwise, and for colors, the group's first vertex
/// gives the value. Repeated consecutive corners are removed and faces left with < 3 corners dropped, with their
/// face-varying data and subdivision tags remapped. Returns the number of vertices merged away.
size_t weld_vertices(PolyMesh& mesh, double tolerance = 0);

/// Gives every pinched vertex — one whose faces form several fans that share no edge at it, as where welding joins
/// two surfaces that merely touch at a point — one vertex per fan (copies of its per-vertex properties), so the
/// mesh is manifold at its vertices. The fan of the vertex's first corner keeps the index (and the tags). Returns the
/// number of vertices added.
size_t split_pinched_vertices(PolyMesh& mesh);

}  // namespace tessera
