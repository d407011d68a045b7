#pragma once
// The sharpness of every edge and vertex of one level, from a mesh's crease and corner tags, the boundary and the
// boundary interpolation option; shared by the refinement driver and the limit masks.
#include <cstdint>
#include <span>
#include <vector>

#include "tessera/core/memory.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/subdiv/rules.hpp"
#include "tessera/subdiv/subdivide.hpp"
#include "tessera/subdiv/topology.hpp"

namespace tessera::detail {

/// Per-edge and per-vertex sharpness of a level; empty arrays mean "all smooth" (boundary edges excepted).
class LevelSharpness {
 public:
  /// Reads the tags of `mesh` over `topology`. Throws InvalidInput for a crease that names no edge, a corner that
  /// names no vertex, or NaN sharpness.
  LevelSharpness(const TopologyTables& topology, const PolyMesh& mesh, BoundaryInterpolation boundary);

  /// Sharpness of edge e: infinite on a boundary, else its tag (0 when untagged).
  float edge(uint32_t e) const {
    if (topology_.is_boundary_edge(e)) return kInfiniteSharpness;
    return edges_.empty() ? 0.0f : edges_[e];
  }
  /// True when interior edge e carries a crease tag (a sharpness > 0).
  bool tagged_edge(uint32_t e) const { return !edges_.empty() && edges_[e] > 0.0f; }
  /// Sharpness of vertex v: its corner tag, infinite for a boundary corner under edge_and_corner.
  float vertex(uint32_t v) const { return vertices_.empty() ? 0.0f : vertices_[v]; }
  /// False when vertex v certainly follows the smooth rule: interior, no tag on it or on its edges.
  bool may_be_sharp(uint32_t v) const {
    return topology_.is_boundary_vertex(v) || (!touched_.empty() && touched_[v] != 0);
  }
  /// The interior edges with a tag > 0, in increasing order.
  std::span<const uint32_t> tagged_edge_ids() const { return tagged_edge_ids_; }
  /// The corner tags > 0 as given (without boundary corners), in increasing vertex order.
  std::span<const VertexCorner> corner_tags() const { return corner_tags_; }

  /// The rule of vertex v, with the sharpness of its ring edges written to `ring` (ring_edge_count(v) entries).
  VertexRule rule(uint32_t v, std::span<float> ring) const;

 private:
  const TopologyTables& topology_;
  RawVector<float> edges_;       // per edge (empty when no edge is tagged)
  std::vector<float> vertices_;  // per vertex (empty when no vertex is sharp)
  std::vector<uint32_t> tagged_edge_ids_;
  std::vector<VertexCorner> corner_tags_;
  std::vector<uint8_t> touched_;  // per vertex: tagged, or an end of a tagged edge (empty when nothing is tagged)
};

/// The ring indices of the first and last sharp entry of `sharpness` (the two edges of a crease).
inline void crease_ends(std::span<const float> sharpness, uint32_t ends[2]) {
  uint32_t a = 0, b = uint32_t(sharpness.size()) - 1;
  while (sharpness[a] <= 0.0f) ++a;
  while (sharpness[b] <= 0.0f) --b;
  ends[0] = a;
  ends[1] = b;
}

}  // namespace tessera::detail
