#include "sharpness.hpp"

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera::detail {
namespace {

// A tag may be given twice: keep each id once, in increasing order (the order the child's tags are made in).
void sort_unique(std::vector<uint32_t>& ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
}

}  // namespace

LevelSharpness::LevelSharpness(const TopologyTables& topology, const PolyMesh& mesh, BoundaryInterpolation boundary)
    : topology_(topology) {
  auto touch = [&](uint32_t v) {
    if (touched_.empty()) touched_.assign(topology.vertex_count(), uint8_t(0));
    touched_[v] = 1;
  };
  for (const EdgeCrease& c : mesh.creases) {
    if (std::isnan(c.sharpness))
      throw InvalidInput(fmt::format("crease ({}, {}): sharpness is NaN", c.v0, c.v1));
    const uint32_t e = topology.find_edge(c.v0, c.v1);
    if (e == TopologyTables::kNone)
      throw InvalidInput(fmt::format("crease ({}, {}) names no edge of the mesh", c.v0, c.v1));
    if (c.sharpness > 0.0f && !topology.is_boundary_edge(e)) {
      if (edges_.empty()) edges_.assign(topology.edge_count(), 0.0f);
      edges_[e] = std::min(c.sharpness, kInfiniteSharpness);
      tagged_edge_ids_.push_back(e);
      touch(c.v0);
      touch(c.v1);
    }
  }
  sort_unique(tagged_edge_ids_);
  for (const VertexCorner& c : mesh.corners) {
    if (std::isnan(c.sharpness)) throw InvalidInput(fmt::format("corner {}: sharpness is NaN", c.v));
    if (c.v >= topology.vertex_count())
      throw InvalidInput(fmt::format("corner {} names no vertex (the mesh has {})", c.v, topology.vertex_count()));
    if (c.sharpness > 0.0f) {
      if (tagged_vertices_.empty()) tagged_vertices_.assign(topology.vertex_count(), 0.0f);
      tagged_vertices_[c.v] = std::min(c.sharpness, kInfiniteSharpness);
      tagged_vertex_ids_.push_back(c.v);
      touch(c.v);
    }
  }
  sort_unique(tagged_vertex_ids_);
  vertices_ = tagged_vertices_;
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
