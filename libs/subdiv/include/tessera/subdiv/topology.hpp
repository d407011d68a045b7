#pragma once
// Topology tables of a polygon mesh for subdivision, in flat arrays (OpenSubdiv's Vtr::Level): edges, the edge of
// every face corner, the faces of every edge, and the ring of faces and edges around every vertex in
// counterclockwise order (seen from outside), starting at the leading boundary edge of a boundary vertex.
//
// A face corner k is a half-edge: it goes from corner_vertex(k) to corner_vertex(next_corner(k)) inside
// corner_face(k). Each edge is numbered where it first appears in face order, as OpenSubdiv numbers them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "tessera/core/memory.hpp"

namespace tessera {

class TopologyTables {
 public:
  /// The "no such corner/edge" sentinel (the missing second face of a boundary edge).
  static constexpr uint32_t kNone = 0xffffffffu;

  /// Builds the tables of faces given by `face_offsets` (F + 1 entries, from 0) and `face_vertices`, in parallel.
  /// The tables keep views of both arrays, which must outlive them and stay unchanged.
  /// Throws InvalidInput for a face with fewer than 3 vertices, a repeated vertex or an index >= vertex_count, and
  /// TopologyError for a non-manifold edge or vertex or neighbours of opposite orientation.
  TopologyTables(std::span<const uint32_t> face_offsets, std::span<const uint32_t> face_vertices, size_t vertex_count);

  /// How one uniform refinement step splits the faces (subdivide.hpp): every n-gon into n quads, child face k made
  /// from parent corner k as (vertex, edge point, face point, previous edge point); or every triangle f into the
  /// four triangles 4f + j = (vertex j, edge point j, edge point j - 1) and 4f + 3 = (edge points 0, 1, 2).
  enum class Split { quads, triangles };

  /// The tables of the refined level, derived from the parent's in parallel without any search or sort (as
  /// OpenSubdiv's Vtr refines a level): identical to building them from the child faces, which `face_offsets` and
  /// `face_vertices` hold (viewed as above). Child vertices: the parent's, the face points (quads), then one edge
  /// point per parent edge. Throws InvalidInput when the arrays do not have the sizes of that refinement.
  TopologyTables(const TopologyTables& parent, Split split, std::span<const uint32_t> face_offsets,
                 std::span<const uint32_t> face_vertices);

  size_t vertex_count() const { return vertex_offsets_.size() - 1; }
  size_t face_count() const { return face_offsets_.size() - 1; }
  size_t edge_count() const { return edge_corners_.size(); }
  size_t corner_count() const { return face_vertices_.size(); }

  /// Face f's vertices in order, its size and the index of its first corner.
  std::span<const uint32_t> face(size_t f) const {
    return {face_vertices_.data() + face_offsets_[f], face_offsets_[f + 1] - face_offsets_[f]};
  }
  uint32_t face_size(size_t f) const { return face_offsets_[f + 1] - face_offsets_[f]; }
  uint32_t face_offset(size_t f) const { return face_offsets_[f]; }

  /// Corner k's vertex, face, following and preceding corner in its face, and the edge from it to the next corner.
  uint32_t corner_vertex(uint32_t k) const { return face_vertices_[k]; }
  uint32_t corner_face(uint32_t k) const {
    if (uniform_size_ == 4) return k >> 2;
    if (uniform_size_ == 3) return k / 3;  // a multiplication, where k / uniform_size_ is a division
    return uniform_size_ != 0 ? k / uniform_size_ : corner_faces_[k];
  }
  uint32_t next_corner(uint32_t k) const {
    if (uniform_size_ == 4) return (k & ~3u) | ((k + 1) & 3u);
    if (uniform_size_ == 3) return k % 3 == 2 ? k - 2 : k + 1;
    const uint32_t f = corner_face(k);
    return k + 1 == face_offsets_[f + 1] ? face_offsets_[f] : k + 1;
  }
  uint32_t prev_corner(uint32_t k) const {
    if (uniform_size_ == 4) return (k & ~3u) | ((k - 1) & 3u);
    if (uniform_size_ == 3) return k % 3 == 0 ? k + 2 : k - 1;
    const uint32_t f = corner_face(k);
    return k == face_offsets_[f] ? face_offsets_[f + 1] - 1 : k - 1;
  }
  uint32_t corner_edge(uint32_t k) const { return corner_edges_[k]; }
  /// The corner of the neighbouring face that runs the same edge the other way, or kNone on a boundary.
  uint32_t twin(uint32_t k) const { return twins_[k]; }

  /// Edge e's two vertices (in the direction of its first corner).
  std::array<uint32_t, 2> edge_vertices(size_t e) const {
    return {face_vertices_[edge_corners_[e]], face_vertices_[next_corner(edge_corners_[e])]};
  }
  /// Edge e's corners: [0] in its first face, [1] in the second face or kNone on a boundary.
  std::array<uint32_t, 2> edge_corners(size_t e) const { return {edge_corners_[e], twins_[edge_corners_[e]]}; }
  bool is_boundary_edge(size_t e) const { return twins_[edge_corners_[e]] == kNone; }
  /// The edge joining a and b, or kNone. O(valence).
  uint32_t find_edge(uint32_t a, uint32_t b) const;

  /// Vertex v's incident corners (one per incident face), counterclockwise.
  std::span<const uint32_t> ring_corners(size_t v) const {
    return {ring_corners_.data() + vertex_offsets_[v], vertex_offsets_[v + 1] - vertex_offsets_[v]};
  }
  /// Number of faces around v; the number of edges is one more on a boundary.
  uint32_t ring_face_count(size_t v) const { return vertex_offsets_[v + 1] - vertex_offsets_[v]; }
  uint32_t ring_edge_count(size_t v) const { return ring_face_count(v) + (boundary_vertex_[v] ? 1u : 0u); }
  bool is_boundary_vertex(size_t v) const { return boundary_vertex_[v] != 0; }
  /// Edge i around v (edge i lies between face i-1 and face i) and the vertex at its far end.
  uint32_t ring_edge(size_t v, uint32_t i) const {
    const uint32_t n = ring_face_count(v);
    return i < n ? corner_edges_[ring_corners_[vertex_offsets_[v] + i]]
                 : corner_edges_[prev_corner(ring_corners_[vertex_offsets_[v] + n - 1])];
  }
  uint32_t ring_neighbor(size_t v, uint32_t i) const {
    const uint32_t n = ring_face_count(v);
    return i < n ? ring_neighbors_[vertex_offsets_[v] + i]
                 : face_vertices_[prev_corner(ring_corners_[vertex_offsets_[v] + n - 1])];
  }
  /// The far ends of v's first ring_face_count(v) edges (one per ring corner), in a flat array for gathers.
  std::span<const uint32_t> ring_neighbors(size_t v) const {
    return {ring_neighbors_.data() + vertex_offsets_[v], vertex_offsets_[v + 1] - vertex_offsets_[v]};
  }
  /// Hints for gathers, in two steps: the entries that edge_corners(e) and edge_vertices(e) read, then (with those
  /// in cache) the vertices of e's second face.
  void prefetch_edge(size_t e) const {
    const uint32_t k = edge_corners_[e];
    prefetch_line(&twins_[k]);
    prefetch_line(&face_vertices_[k]);
  }
  void prefetch_edge_second_face(size_t e) const {
    if (const uint32_t k = twins_[edge_corners_[e]]; k != kNone) prefetch_line(&face_vertices_[k]);
  }

  /// The largest number of edges around a vertex.
  uint32_t max_valence() const { return max_valence_; }

 private:
  // An edge belongs to its first corner in face order; edges are numbered in that order, from the number of owning
  // corners in every chunk of corners (chunk c's at entry c + 1, see topology.cpp).
  bool owns_edge(uint32_t k) const { return twins_[k] == kNone || k < twins_[k]; }
  uint32_t count_edge_owners(int64_t begin, int64_t end) const;
  void build_edges(std::vector<uint32_t> owners);
  void build_rings();

  std::span<const uint32_t> face_offsets_, face_vertices_;
  uint32_t uniform_size_ = 0;         // the size of every face, 0 when sizes differ
  RawVector<uint32_t> corner_faces_;  // empty when every face has uniform_size_ corners
  RawVector<uint32_t> corner_edges_, twins_;
  RawVector<uint32_t> edge_corners_;  // the first corner of every edge
  RawVector<uint32_t> vertex_offsets_, ring_corners_;
  RawVector<uint32_t> ring_neighbors_;  // corner_vertex(next_corner(k)) of every ring corner k
  RawVector<uint8_t> boundary_vertex_;
  uint32_t max_valence_ = 0;
};

}  // namespace tessera
