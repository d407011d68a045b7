#pragma once
// Rossignac's corner table (the notes, "corners"): for a triangle mesh, G holds the vertex positions, V the vertex
// of every corner (corners 3t, 3t+1, 3t+2 are triangle t, counterclockwise seen from outside) and O the opposite
// corner of every corner: the corner of the neighbouring triangle across the edge facing c.
//
//   next(c)  = 3 * (c / 3) + (c + 1) % 3        left(c)  = prev(c).opposite   (the notes' left)
//   prev(c)  = next(next(c))                    right(c) = next(c).opposite   (the notes' right)
//   opposite(c) = O[c]                          swing(c) = next(c).opposite.next
//
// For triangle (v, a, b) with c at v: right(c) lies across edge v-b, left(c) across edge v-a (the notes'
// formulas, kept literally; docs/mesh.md has a figure). swing(c) is the corner at the same vertex in the next
// triangle counterclockwise around the vertex (seen from outside, for a consistently counterclockwise mesh);
// unswing(c) = prev(c).opposite.prev turns clockwise. A corner facing a boundary edge — or a non-manifold edge,
// shared by more than two triangles or by two triangles running the same way — has no opposite: O holds kNoCorner
// there, and every operator that would cross it returns kNoCorner.
#include <cstdint>
#include <span>
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

class CornerTable {
 public:
  /// The sentinel of a missing corner (the opposite of a boundary corner).
  static constexpr uint32_t kNoCorner = UINT32_MAX;

  /// Builds the table of a triangle mesh (G = positions, V = face_vertices) and its O table. Throws TopologyError
  /// when a face is not a triangle. Non-manifold input is accepted: O links manifold edges only.
  explicit CornerTable(const PolyMesh& mesh);
  /// Builds from G and V directly. Throws TopologyError when V's size is not a multiple of 3 or an index is out
  /// of range.
  CornerTable(std::vector<Vec3> geometry, std::vector<uint32_t> vertices);

  size_t corner_count() const { return v_.size(); }
  size_t triangle_count() const { return v_.size() / 3; }
  size_t vertex_count() const { return g_.size(); }

  /// The notes' c.next, c.prev and the triangle of a corner.
  static uint32_t next(uint32_t c) { return 3 * (c / 3) + (c + 1) % 3; }
  static uint32_t prev(uint32_t c) { return next(next(c)); }
  static uint32_t triangle(uint32_t c) { return c / 3; }

  /// V[c]: the vertex of corner c; G[V[c]]: its position.
  uint32_t vertex(uint32_t c) const { return v_[c]; }
  const Vec3& position(uint32_t c) const { return g_[v_[c]]; }
  /// O[c], or kNoCorner on a boundary (or non-manifold) edge.
  uint32_t opposite(uint32_t c) const { return o_[c]; }
  bool is_boundary(uint32_t c) const { return o_[c] == kNoCorner; }
  /// The notes' c.left = c.prev.opposite and c.right = c.next.opposite (kNoCorner across a boundary).
  uint32_t left(uint32_t c) const { return o_[prev(c)]; }
  uint32_t right(uint32_t c) const { return o_[next(c)]; }
  /// The notes' c.swing = c.next.opposite.next: the same vertex, next triangle counterclockwise; kNoCorner at a
  /// boundary.
  uint32_t swing(uint32_t c) const { return follow(o_[next(c)], &next); }
  /// The inverse of swing, c.prev.opposite.prev: clockwise.
  uint32_t unswing(uint32_t c) const { return follow(o_[prev(c)], &prev); }

  /// The tables themselves.
  const std::vector<Vec3>& geometry() const { return g_; }
  const std::vector<uint32_t>& vertices() const { return v_; }
  const std::vector<uint32_t>& opposites() const { return o_; }

  /// A corner of vertex v: the most clockwise one of its fan (unswing gives kNoCorner) when v is on a boundary, so
  /// swinging from it visits the whole fan; kNoCorner for an unreferenced vertex.
  uint32_t vertex_corner(uint32_t v) const { return vertex_corner_[v]; }
  /// The corners of v's fan, counterclockwise (from the boundary when v is on one). A non-manifold vertex has
  /// several fans: only the one holding vertex_corner(v) is listed.
  std::vector<uint32_t> corners_around(uint32_t v) const;
  /// The neighbour vertices of v (its one-ring), counterclockwise; for a boundary vertex the ring is open and has
  /// one more vertex than the fan has triangles.
  std::vector<uint32_t> one_ring(uint32_t v) const;
  /// The number of triangle edges left unpaired in O although two or more triangles share them (non-manifold or
  /// inconsistently oriented edges), each counted once.
  size_t unpaired_shared_edges() const { return unpaired_shared_; }

 private:
  uint32_t follow(uint32_t c, uint32_t (*step)(uint32_t)) const { return c == kNoCorner ? kNoCorner : step(c); }
  void build();

  std::vector<Vec3> g_;
  std::vector<uint32_t> v_, o_;
  std::vector<uint32_t> vertex_corner_;
  size_t unpaired_shared_ = 0;
};

/// Builds the O table of V (corners 3t..3t+2 per triangle) in O(n) expected time: corners are bucketed by the
/// lower vertex of their opposite edge (a counting sort), then matched within each bucket. Corners c and d are
/// opposite when V[c.next] == V[d.prev] and V[c.prev] == V[d.next] and no other corner faces the same edge;
/// everything else gets kNoCorner. `unpaired_shared` (optional) receives the count of edges left unpaired although
/// shared. Precondition: every entry of V < vertex_count.
std::vector<uint32_t> build_opposites(std::span<const uint32_t> vertices, size_t vertex_count,
                                      size_t* unpaired_shared = nullptr);

}  // namespace tessera
