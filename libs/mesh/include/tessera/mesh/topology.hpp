#pragma once
// Topology of polygon meshes (the notes: manifold, boundary and non-manifold edges and vertices): the undirected
// edge table, classification, connected components, boundary loops, Euler characteristic, genus and orientation.
// Works on faces of any valence and on broken input (non-manifold, duplicated faces, unreferenced vertices).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// An edge is a boundary edge (1 face), a manifold edge (2 faces) or a non-manifold edge (3 or more faces).
enum class EdgeKind : uint8_t { boundary, manifold, non_manifold };

/// A vertex is isolated (no face), interior (its faces form one closed fan), on the boundary (one open fan), on a
/// non-manifold edge, or a non-manifold "pinch" vertex whose faces form several fans (a bowtie).
enum class VertexKind : uint8_t { isolated, interior, boundary, on_non_manifold_edge, non_manifold_fan };

/// The undirected edges of a polygon mesh and the face corners along each ("half-edges": corner c stands for the
/// directed edge from its vertex to the next corner's vertex in its face).
struct EdgeTable {
  std::vector<std::array<uint32_t, 2>> vertices;  ///< per edge, lower vertex first
  std::vector<uint32_t> offsets;                  ///< edge e has half-edges half_edges[offsets[e] .. offsets[e+1])
  std::vector<uint32_t> half_edges;               ///< corner indices (into face_vertices)
  std::vector<uint32_t> edge_of_corner;           ///< per corner, the edge from it to the next corner
  std::vector<uint32_t> face_of_corner;           ///< per corner, its face
  std::vector<uint32_t> next_corner;              ///< per corner, the next corner of its face

  size_t size() const { return vertices.size(); }
  /// The number of faces along edge e (with multiplicity).
  uint32_t valence(size_t e) const { return offsets[e + 1] - offsets[e]; }
  EdgeKind kind(size_t e) const {
    return valence(e) == 1 ? EdgeKind::boundary : valence(e) == 2 ? EdgeKind::manifold : EdgeKind::non_manifold;
  }
};

/// Builds the edge table by sorting the half-edges by their undirected key, O(n log n). Faces must have >= 3
/// corners and valid indices (as the readers guarantee).
EdgeTable build_edge_table(const PolyMesh& mesh);

/// The kind of every vertex: union-find of the corners around each vertex joined across manifold edges.
std::vector<VertexKind> classify_vertices(const PolyMesh& mesh, const EdgeTable& edges);

/// Connected components of the faces (faces sharing a vertex are connected): the label of every face, and the
/// number of components through `count`.
std::vector<uint32_t> face_components(const PolyMesh& mesh, size_t* count);

/// The boundary loops: the connected pieces of the graph of boundary edges, each as its vertices in walking order
/// (boundary half-edges chained head to tail, against the direction where orientation flips). On a manifold mesh
/// each piece is one simple cycle; on a non-manifold one, chains that touch are one loop (as MeshLab counts).
std::vector<std::vector<uint32_t>> boundary_loops(const PolyMesh& mesh, const EdgeTable& edges);

/// True when every manifold edge is used in opposite directions by its two faces (a consistent orientation).
bool is_consistently_oriented(const PolyMesh& mesh, const EdgeTable& edges);

/// The figures of `tessera mesh info`.
struct TopologyReport {
  size_t vertices = 0;               ///< all vertices
  size_t unreferenced_vertices = 0;  ///< vertices no face uses (left out of the Euler characteristic)
  size_t faces = 0, edges = 0;
  size_t boundary_edges = 0, nonmanifold_edges = 0;
  size_t boundary_loops = 0, components = 0;
  size_t nonmanifold_vertices = 0;  ///< pinch vertices (several fans) not on a non-manifold edge, as MeshLab counts
  size_t inconsistent_edges = 0;    ///< manifold edges whose two faces run the same way
  long euler = 0;                   ///< chi = V - E + F over the referenced vertices
  std::optional<long> genus;        ///< (2 components - boundary loops - chi) / 2, for orientable manifolds only

  bool manifold() const { return nonmanifold_edges == 0 && nonmanifold_vertices == 0; }
  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0; }
  bool oriented() const { return inconsistent_edges == 0; }
};

/// Everything above in one pass. chi = 2c - 2g - b for an orientable surface with c components, genus g and b
/// boundary loops.
TopologyReport analyze_topology(const PolyMesh& mesh);

}  // namespace tessera
