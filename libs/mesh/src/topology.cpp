#include "tessera/mesh/topology.hpp"

#include <algorithm>
#include <numeric>

namespace tessera {
namespace {

/// Union-find with path halving.
class DisjointSets {
 public:
  explicit DisjointSets(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace

EdgeTable build_edge_table(const PolyMesh& mesh) {
  EdgeTable t;
  const size_t n = mesh.face_vertices.size();
  t.face_of_corner.resize(n);
  t.next_corner.resize(n);
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const uint32_t b = mesh.face_offsets[f], e = mesh.face_offsets[f + 1];
    for (uint32_t c = b; c < e; ++c) {
      t.face_of_corner[c] = uint32_t(f);
      t.next_corner[c] = c + 1 == e ? b : c + 1;
    }
  }
  // Sort (undirected key, corner) pairs; equal keys are one edge.
  std::vector<std::pair<uint64_t, uint32_t>> keyed(n);
  for (uint32_t c = 0; c < n; ++c) {
    const uint32_t a = mesh.face_vertices[c], b = mesh.face_vertices[t.next_corner[c]];
    keyed[c] = {(uint64_t(std::min(a, b)) << 32) | std::max(a, b), c};
  }
  std::sort(keyed.begin(), keyed.end());
  t.half_edges.resize(n);
  t.edge_of_corner.resize(n);
  t.offsets.push_back(0);
  for (size_t i = 0; i < n; ++i) {
    if (i > 0 && keyed[i].first != keyed[i - 1].first) t.offsets.push_back(uint32_t(i));
    if (i == 0 || keyed[i].first != keyed[i - 1].first)
      t.vertices.push_back({uint32_t(keyed[i].first >> 32), uint32_t(keyed[i].first)});
    t.half_edges[i] = keyed[i].second;
    t.edge_of_corner[keyed[i].second] = uint32_t(t.vertices.size() - 1);
  }
  t.offsets.push_back(uint32_t(n));
  if (n == 0) t.offsets = {0};
  return t;
}

std::vector<VertexKind> classify_vertices(const PolyMesh& mesh, const EdgeTable& edges) {
  const size_t nv = mesh.vertex_count(), n = mesh.face_vertices.size();
  std::vector<VertexKind> kind(nv, VertexKind::isolated);
  std::vector<uint8_t> on_boundary(nv, 0), on_nonmanifold(nv, 0);
  // Corners around each vertex are joined across manifold edges; a vertex with one group has one fan.
  DisjointSets fans(n);
  const auto corner_at = [&](uint32_t c, uint32_t v) { return mesh.face_vertices[c] == v ? c : edges.next_corner[c]; };
  for (size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges.vertices[e];
    if (edges.kind(e) == EdgeKind::manifold) {
      const uint32_t c0 = edges.half_edges[edges.offsets[e]], c1 = edges.half_edges[edges.offsets[e] + 1];
      fans.unite(corner_at(c0, a), corner_at(c1, a));
      fans.unite(corner_at(c0, b), corner_at(c1, b));
    } else {
      auto& mark = edges.kind(e) == EdgeKind::boundary ? on_boundary : on_nonmanifold;
      mark[a] = mark[b] = 1;
    }
  }
  std::vector<uint32_t> first_root(nv, UINT32_MAX);
  std::vector<uint8_t> several(nv, 0);
  for (uint32_t c = 0; c < n; ++c) {
    const uint32_t v = mesh.face_vertices[c], r = fans.find(c);
    if (first_root[v] == UINT32_MAX)
      first_root[v] = r;
    else if (first_root[v] != r)
      several[v] = 1;
  }
  for (size_t v = 0; v < nv; ++v) {
    if (first_root[v] == UINT32_MAX) continue;
    kind[v] = on_nonmanifold[v] ? VertexKind::on_non_manifold_edge
              : several[v]      ? VertexKind::non_manifold_fan
              : on_boundary[v]  ? VertexKind::boundary
                                : VertexKind::interior;
  }
  return kind;
}

std::vector<uint32_t> face_components(const PolyMesh& mesh, size_t* count) {
  DisjointSets sets(mesh.vertex_count());
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (size_t i = 1; i < face.size(); ++i) sets.unite(face[0], face[i]);
  }
  std::vector<uint32_t> label_of_root(mesh.vertex_count(), UINT32_MAX), labels(mesh.face_count());
  uint32_t next = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    uint32_t& label = label_of_root[sets.find(mesh.face(f)[0])];
    if (label == UINT32_MAX) label = next++;
    labels[f] = label;
  }
  if (count != nullptr) *count = next;
  return labels;
}

std::vector<std::vector<uint32_t>> boundary_loops(const PolyMesh& mesh, const EdgeTable& edges) {
  // Boundary half-edges by start vertex (directed) and by end vertex (for chains that must run against it).
  const size_t nv = mesh.vertex_count();
  std::vector<uint32_t> boundary;
  for (size_t e = 0; e < edges.size(); ++e)
    if (edges.kind(e) == EdgeKind::boundary) boundary.push_back(edges.half_edges[edges.offsets[e]]);
  const auto from = [&](uint32_t c) { return mesh.face_vertices[c]; };
  const auto to = [&](uint32_t c) { return mesh.face_vertices[edges.next_corner[c]]; };
  std::vector<std::vector<uint32_t>> out_of(nv), into(nv);
  for (uint32_t i = 0; i < boundary.size(); ++i) {
    out_of[from(boundary[i])].push_back(i);
    into[to(boundary[i])].push_back(i);
  }
  std::vector<uint8_t> used(boundary.size(), 0);
  const auto take = [&](const std::vector<uint32_t>& list) -> int64_t {
    for (uint32_t i : list)
      if (!used[i]) return i;
    return -1;
  };
  // Trace chains, then merge the chains of one connected piece of the boundary graph into one loop.
  std::vector<std::vector<uint32_t>> chains;
  DisjointSets pieces(nv);
  for (uint32_t s = 0; s < boundary.size(); ++s) {
    pieces.unite(from(boundary[s]), to(boundary[s]));
    if (used[s]) continue;
    std::vector<uint32_t> chain{from(boundary[s])};
    used[s] = 1;
    uint32_t at = to(boundary[s]);
    while (at != chain.front()) {
      chain.push_back(at);
      int64_t i = take(out_of[at]);
      if (i >= 0) {
        used[size_t(i)] = 1;
        at = to(boundary[size_t(i)]);
        continue;
      }
      i = take(into[at]);
      if (i < 0) break;  // an open chain (possible only around non-manifold vertices)
      used[size_t(i)] = 1;
      at = from(boundary[size_t(i)]);
    }
    chains.push_back(std::move(chain));
  }
  std::vector<std::vector<uint32_t>> loops;
  std::vector<uint32_t> loop_of_root(nv, UINT32_MAX);
  for (auto& chain : chains) {
    uint32_t& loop = loop_of_root[pieces.find(chain.front())];
    if (loop == UINT32_MAX) {
      loop = uint32_t(loops.size());
      loops.push_back(std::move(chain));
    } else {
      loops[loop].insert(loops[loop].end(), chain.begin(), chain.end());
    }
  }
  return loops;
}

bool is_consistently_oriented(const PolyMesh& mesh, const EdgeTable& edges) {
  for (size_t e = 0; e < edges.size(); ++e) {
    if (edges.kind(e) != EdgeKind::manifold) continue;
    if (mesh.face_vertices[edges.half_edges[edges.offsets[e]]] ==
        mesh.face_vertices[edges.half_edges[edges.offsets[e] + 1]])
      return false;
  }
  return true;
}

TopologyReport analyze_topology(const PolyMesh& mesh) {
  const EdgeTable edges = build_edge_table(mesh);
  TopologyReport r;
  r.vertices = mesh.vertex_count();
  r.faces = mesh.face_count();
  r.edges = edges.size();
  for (size_t e = 0; e < edges.size(); ++e) {
    const EdgeKind k = edges.kind(e);
    r.boundary_edges += k == EdgeKind::boundary;
    r.nonmanifold_edges += k == EdgeKind::non_manifold;
    r.inconsistent_edges += k == EdgeKind::manifold && mesh.face_vertices[edges.half_edges[edges.offsets[e]]] ==
                                                           mesh.face_vertices[edges.half_edges[edges.offsets[e] + 1]];
  }
  for (VertexKind k : classify_vertices(mesh, edges)) {
    r.unreferenced_vertices += k == VertexKind::isolated;
    r.nonmanifold_vertices += k == VertexKind::non_manifold_fan;
  }
  face_components(mesh, &r.components);
  r.boundary_loops = boundary_loops(mesh, edges).size();
  r.euler = long(r.vertices - r.unreferenced_vertices) - long(r.edges) + long(r.faces);
  if (r.manifold() && r.oriented()) r.genus = (2 * long(r.components) - long(r.boundary_loops) - r.euler) / 2;
  return r;
}

}  // namespace tessera
