#include "sharpness.hpp"

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera::detail {

LevelSharpness::LevelSharpness(const TopologyTables& topology, const PolyMesh& mesh, BoundaryInterpolation boundary)
    : topology_(topology) {
  auto touch = [&](uint32_t v) {
    if (touched_.empty()) touched_.assign(topology.vertex_count(), uint8_t(0));
    touched_[v] = 1;
  };
  for (const EdgeCrease& c : mesh.creases) {
    if (std::isnan(c.sharpness)) throw InvalidInput(fmt::format("crease ({}, {}): sharpness is NaN", c.v0, c.v1));
    const uint32_t e = topology.find_edge(c.v0, c.v1);
    if (e == TopologyTables::kNone)
      throw InvalidInput(fmt::format("crease ({}, {}) names no edge of the mesh", c.v0, c.v1));
    if (c.sharpness > 0.0f && !topology.is_boundary_edge(e)) {
      if (edges_.empty()) {
        // One entry per edge at every level: zeroed in parallel.
        edges_.resize(topology.edge_count());
        parallel_for(0, int64_t(edges_.size()), 1 << 16,
                     [&](int64_t b, int64_t end) { std::fill(edges_.begin() + b, edges_.begin() + end, 0.0f); });
      }
      edges_[e] = std::min(c.sharpness, kInfiniteSharpness);
      tagged_edge_ids_.push_back(e);
      touch(c.v0);
      touch(c.v1);
    }
  }
  // A tag may be given twice: each edge and vertex once, in increasing order (the order of the child's tags).
  std::sort(tagged_edge_ids_.begin(), tagged_edge_ids_.end());
  tagged_edge_ids_.erase(std::unique(tagged_edge_ids_.begin(), tagged_edge_ids_.end()), tagged_edge_ids_.end());
  for (const VertexCorner& c : mesh.corners) {
    if (std::isnan(c.sharpness)) throw InvalidInput(fmt::format("corner {}: sharpness is NaN", c.v));
    if (c.v >= topology.vertex_count())
      throw InvalidInput(fmt::format("corner {} names no vertex (the mesh has {})", c.v, topology.vertex_count()));
    if (c.sharpness > 0.0f) {
      if (vertices_.empty()) vertices_.assign(topology.vertex_count(), 0.0f);
      vertices_[c.v] = std::min(c.sharpness, kInfiniteSharpness);
      corner_tags_.push_back({c.v, 0.0f});
      touch(c.v);
    }
  }
  std::sort(corner_tags_.begin(), corner_tags_.end(),
            [](const VertexCorner& a, const VertexCorner& b) { return a.v < b.v; });
  corner_tags_.erase(std::unique(corner_tags_.begin(), corner_tags_.end(),
                                 [](const VertexCorner& a, const VertexCorner& b) { return a.v == b.v; }),
                     corner_tags_.end());
  for (VertexCorner& c : corner_tags_) c.sharpness = vertices_[c.v];  // the last tag of each vertex
  if (boundary == BoundaryInterpolation::edge_and_corner) {
    for (uint32_t v = 0; v < topology.vertex_count(); ++v) {
      if (topology.is_boundary_vertex(v) && topology.ring_face_count(v) == 1) {
        if (vertices_.empty()) vertices_.assign(topology.vertex_count(), 0.0f);
        vertices_[v] = kInfiniteSharpness;
      }
    }
  }
}

VertexRule LevelSharpness::rule(uint32_t v, std::span<float> ring) const {
  const uint32_t n = topology_.ring_edge_count(v);
  if (n == 0) return VertexRule::corner;
  int sharp = 0;
  for (uint32_t i = 0; i < n; ++i) {
    ring[i] = edge(topology_.ring_edge(v, i));
    sharp += ring[i] > 0.0f;
  }
  return vertex_rule(vertex(v), sharp);
}

}  // namespace tessera::detail
