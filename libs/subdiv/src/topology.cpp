#include "tessera/subdiv/topology.hpp"

#include <algorithm>
#include <atomic>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {
namespace {

constexpr int64_t kGrain = 3072;  // a multiple of 12: a chunk of child corners holds whole split triangles

// Lowers `slot` to `value` if smaller (the first offending element wins, whatever the thread schedule).
void atomic_min(std::atomic<uint64_t>& slot, uint64_t value) {
  uint64_t seen = slot.load(std::memory_order_relaxed);
  while (value < seen && !slot.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
  }
}

constexpr uint64_t kNoError = ~uint64_t(0);

int64_t chunk_count(int64_t n) { return (n + kGrain - 1) / kGrain; }

// Turns chunk totals (chunk c's at entry c + 1, entry 0 zero) into each chunk's first value, the total at the back.
void prefix_sum(std::vector<uint32_t>& first) {
  for (size_t c = 1; c < first.size(); ++c) first[c] += first[c - 1];
}

// count(begin, end) of every fixed chunk of kGrain indices of [0, n), chunk c's at entry c + 1.
template <class Count>
std::vector<uint32_t> chunk_totals(int64_t n, const Count& count) {
  std::vector<uint32_t> totals(size_t(chunk_count(n)) + 1, 0);
  parallel_for(0, int64_t(totals.size()) - 1, 1, [&](int64_t b, int64_t e) {
    for (int64_t c = b; c < e; ++c) totals[size_t(c) + 1] = count(c * kGrain, std::min(n, (c + 1) * kGrain));
  });
  return totals;
}

// The first value of every chunk in the exclusive prefix sum of those totals, the grand total at the back: the
// same result for any thread count.
template <class Count>
std::vector<uint32_t> chunk_starts(int64_t n, const Count& count) {
  std::vector<uint32_t> first = chunk_totals(n, count);
  prefix_sum(first);
  return first;
}

// Calls body(begin, end, first) for every chunk of chunk_starts() in parallel.
template <class Body>
void for_chunks(int64_t n, const std::vector<uint32_t>& first, const Body& body) {
  parallel_for(0, int64_t(first.size()) - 1, 1, [&](int64_t b, int64_t e) {
    for (int64_t c = b; c < e; ++c) body(c * kGrain, std::min(n, (c + 1) * kGrain), first[size_t(c)]);
  });
}

// Rotates the ring of an interior child vertex (its corners and their neighbours) to start at its smallest corner
// (the corner a build from the child faces starts at) and writes it to `corners_out` and `neighbors_out`.
template <size_t N>
void write_from_smallest(const std::array<uint32_t, N>& corners, const std::array<uint32_t, N>& neighbors,
                         uint32_t* corners_out, uint32_t* neighbors_out) {
  const size_t start = size_t(std::min_element(corners.begin(), corners.end()) - corners.begin());
  for (size_t i = 0; i < N; ++i) {
    corners_out[i] = corners[(start + i) % N];
    neighbors_out[i] = neighbors[(start + i) % N];
  }
}

}  // namespace

TopologyTables::TopologyTables(std::span<const uint32_t> face_offsets, std::span<const uint32_t> face_vertices,
                               size_t vertex_count)
    : face_offsets_(face_offsets), face_vertices_(face_vertices) {
  if (face_offsets_.empty() || face_offsets_.front() != 0 || face_offsets_.back() != face_vertices_.size())
    throw InvalidInput("subdivision: face offsets do not match the face-vertex list");
  if (vertex_count >= kNone || face_vertices_.size() >= kNone)
    throw InvalidInput("subdivision: mesh too large for 32-bit indices");
  const int64_t faces = int64_t(face_count());

  // Faces: at least 3 distinct vertices, all in range.
  std::atomic<uint64_t> bad_face{kNoError};
  uniform_size_ = faces > 0 ? face_offsets_[1] - face_offsets_[0] : 0;
  for (int64_t f = 1; f < faces && uniform_size_ != 0; ++f)
    if (face_offsets_[f + 1] - face_offsets_[f] != uniform_size_) uniform_size_ = 0;
  if (uniform_size_ == 0) corner_faces_.resize(face_vertices_.size());
  parallel_for(0, faces, kGrain, [&](int64_t b, int64_t e) {
    for (int64_t f = b; f < e; ++f) {
      const uint32_t o = face_offsets_[f], end = face_offsets_[f + 1];
      const uint32_t n = end >= o && end <= face_vertices_.size() ? end - o : 0;
      bool ok = n >= 3;
      for (uint32_t i = 0; ok && i < n; ++i) {
        ok = face_vertices_[o + i] < vertex_count;
        for (uint32_t j = 0; ok && j < i; ++j) ok = face_vertices_[o + i] != face_vertices_[o + j];
        if (uniform_size_ == 0) corner_faces_[o + i] = uint32_t(f);
      }
      if (!ok) {
        atomic_min(bad_face, uint64_t(f));
        return;
      }
    }
  });
  if (bad_face != kNoError) {
    const uint64_t f = bad_face;
    throw InvalidInput(
        fmt::format("subdivision: face {} has fewer than 3 vertices, an index out of range (>= {}) or "
                    "a repeated vertex; faces need at least 3 distinct vertices",
                    f, vertex_count));
  }

  // Corners grouped by vertex (a parallel counting sort; the order inside a group does not matter, see build_rings).
  const int64_t corners = int64_t(face_vertices_.size());
  vertex_offsets_.assign(vertex_count + 1, 0u);
  parallel_for(0, corners, 4 * kGrain, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k)
      std::atomic_ref<uint32_t>(vertex_offsets_[face_vertices_[k] + 1]).fetch_add(1, std::memory_order_relaxed);
  });
  for (size_t v = 0; v < vertex_count; ++v) vertex_offsets_[v + 1] += vertex_offsets_[v];
  RawVector<uint32_t> by_vertex(face_vertices_.size());
  {
    RawVector<uint32_t> fill(vertex_offsets_.begin(), vertex_offsets_.end() - 1);
    parallel_for(0, corners, 4 * kGrain, [&](int64_t b, int64_t e) {
      for (int64_t k = b; k < e; ++k)
        by_vertex[std::atomic_ref<uint32_t>(fill[face_vertices_[k]]).fetch_add(1, std::memory_order_relaxed)] =
            uint32_t(k);
    });
  }

  // Twins: corner a->b finds the corner b->a among b's corners.
  twins_.resize(face_vertices_.size());
  std::atomic<uint64_t> bad_corner{kNoError};
  parallel_for(0, corners, kGrain, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k) {
      const uint32_t a = face_vertices_[k], to = face_vertices_[next_corner(uint32_t(k))];
      uint32_t twin = kNone;
      for (uint32_t i = vertex_offsets_[to]; i < vertex_offsets_[to + 1]; ++i) {
        const uint32_t j = by_vertex[i];
        if (face_vertices_[next_corner(j)] == a) {
          if (twin != kNone) atomic_min(bad_corner, uint64_t(k));
          twin = j;
        }
      }
      twins_[k] = twin;
    }
  });
  parallel_for(0, corners, kGrain, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k) {
      if (twins_[k] != kNone) {
        if (twins_[twins_[k]] != uint32_t(k)) atomic_min(bad_corner, uint64_t(k));
        continue;
      }
      const uint32_t a = face_vertices_[k], to = face_vertices_[next_corner(uint32_t(k))];
      for (uint32_t i = vertex_offsets_[a]; i < vertex_offsets_[a + 1]; ++i) {
        const uint32_t j = by_vertex[i];
        if (j != uint32_t(k) && face_vertices_[next_corner(j)] == to) atomic_min(bad_corner, uint64_t(k));
      }
    }
  });
  if (bad_corner != kNoError) {
    const auto k = uint32_t(uint64_t(bad_corner));
    throw TopologyError(
        fmt::format("subdivision: non-manifold edge ({}, {}): more than two faces share it, or two "
                    "faces of opposite orientation",
                    face_vertices_[k], face_vertices_[next_corner(k)]));
  }

  build_edges(chunk_totals(corners, [&](int64_t b, int64_t e) { return count_edge_owners(b, e); }));
  ring_corners_ = std::move(by_vertex);
  build_rings();
}

uint32_t TopologyTables::count_edge_owners(int64_t begin, int64_t end) const {
  uint32_t n = 0;
  for (auto k = uint32_t(begin); k < uint32_t(end); ++k) n += owns_edge(k);
  return n;
}

void TopologyTables::build_edges(std::vector<uint32_t> owners) {
  const auto corners = int64_t(face_vertices_.size());
  corner_edges_.resize(size_t(corners));
  prefix_sum(owners);
  edge_corners_.resize(owners.back());
  for_chunks(corners, owners, [&](int64_t b, int64_t e, uint32_t edge) {
    for (int64_t k = b; k < e; ++k)
      if (owns_edge(uint32_t(k))) {
        corner_edges_[k] = edge;
        if (twins_[k] != kNone) corner_edges_[twins_[k]] = edge;  // the twin's only writer
        edge_corners_[edge++] = uint32_t(k);
      }
  });
}

void TopologyTables::build_rings() {
  // ring_corners_ holds each vertex's corners in corner order; walk them counterclockwise in place of that order.
  const int64_t vertices = int64_t(vertex_count());
  boundary_vertex_.assign(vertex_count(), uint8_t(0));
  ring_neighbors_.resize(ring_corners_.size());
  std::atomic<uint64_t> bad_vertex{kNoError};
  std::atomic<uint32_t> max_valence{0};
  parallel_for(0, vertices, 1024, [&](int64_t b, int64_t e) {
    std::vector<uint32_t> ring;
    uint32_t local_max = 0;
    for (int64_t v = b; v < e; ++v) {
      const uint32_t first = vertex_offsets_[v], n = vertex_offsets_[v + 1] - first;
      if (n == 0) continue;
      // The first face counterclockwise is the one whose outgoing edge is a boundary edge; an interior ring starts
      // at the vertex's first corner in face order (deterministic whatever the order of the group).
      uint32_t start = ring_corners_[first], starts = 0;
      for (uint32_t i = 0; i < n; ++i) {
        const uint32_t k = ring_corners_[first + i];
        if (twins_[k] == kNone) {
          if (starts++ == 0) start = k;
        } else if (starts == 0) {
          start = std::min(start, k);
        }
      }
      ring.clear();
      uint32_t k = start;
      do {
        ring.push_back(k);
        k = twins_[prev_corner(k)];
      } while (k != kNone && k != start && ring.size() <= n);
      if (starts > 1 || ring.size() != n || (starts == 1) != (k == kNone)) {
        atomic_min(bad_vertex, uint64_t(v));
        continue;
      }
      std::copy(ring.begin(), ring.end(), ring_corners_.begin() + first);
      for (uint32_t i = 0; i < n; ++i) ring_neighbors_[first + i] = face_vertices_[next_corner(ring[i])];
      boundary_vertex_[v] = starts == 1;
      local_max = std::max(local_max, n + starts);
    }
    uint32_t seen = max_valence.load();
    while (local_max > seen && !max_valence.compare_exchange_weak(seen, local_max)) {
    }
  });
  if (bad_vertex != kNoError)
    throw TopologyError(
        fmt::format("subdivision: non-manifold vertex {}: its faces do not form a single fan", uint64_t(bad_vertex)));
  max_valence_ = max_valence;
}

TopologyTables::TopologyTables(const TopologyTables& parent, Split split, std::span<const uint32_t> face_offsets,
                               std::span<const uint32_t> face_vertices)
    : face_offsets_(face_offsets), face_vertices_(face_vertices) {
  const bool quads = split == Split::quads;
  const auto corners = uint32_t(parent.corner_count()), faces = uint32_t(parent.face_count()),
             vertices = uint32_t(parent.vertex_count()), edges = uint32_t(parent.edge_count());
  uniform_size_ = quads ? 4 : 3;
  const size_t child_faces = quads ? corners : 4 * size_t(faces);
  if (face_offsets_.size() != child_faces + 1 || face_vertices_.size() != 4 * size_t(corners) ||
      4 * size_t(corners) >= kNone)
    throw InvalidInput("subdivision: the child faces do not have the sizes of the parent's refinement");

  // Child corners: quads, corner i of the quad of parent corner k is 4k + i; triangles, corner i of the corner
  // triangle of parent corner k (face f, position j) is 12f + 3j + i and the middle triangle's corner at edge
  // point j is 12f + 9 + j.
  auto at = [&](uint32_t k, uint32_t i) { return quads ? 4 * k + i : 4 * k - k % 3 + i; };
  auto middle = [](uint32_t k) { return 12 * (k / 3) + 9 + k % 3; };
  const uint32_t* parent_twins = parent.twins_.data();

  // Twins: the halves of a parent edge pair up with the halves in the neighbouring face; the edges inside a parent
  // face pair up inside it. Chunk c of the child corners comes from parent corners [c, c + 1) * kGrain / 4 (whole
  // faces for triangles), so its edge owners are counted while its twins are in cache.
  twins_.resize(4 * size_t(corners));
  std::vector<uint32_t> owners(size_t(chunk_count(4 * int64_t(corners))) + 1, 0);
  parallel_for(0, int64_t(owners.size()) - 1, 1, [&](int64_t first_chunk, int64_t last_chunk) {
    for (int64_t c = first_chunk; c < last_chunk; ++c) {
      const auto b = uint32_t(c * kGrain / 4), e = uint32_t(std::min<int64_t>(corners, (c + 1) * kGrain / 4));
      for (uint32_t k = b; k < e; ++k) {
        const uint32_t t = parent_twins[k], p = parent.prev_corner(k), n = parent.next_corner(k), tp = parent_twins[p];
        twins_[at(k, 0)] = t == kNone ? kNone : at(parent.next_corner(t), quads ? 3 : 2);
        if (quads) {
          twins_[4 * k + 1] = 4 * n + 2;
          twins_[4 * k + 2] = 4 * p + 1;
          twins_[4 * k + 3] = tp == kNone ? kNone : 4 * tp;
        } else {
          twins_[at(k, 1)] = middle(p);
          twins_[at(k, 2)] = tp == kNone ? kNone : at(tp, 0);
          twins_[middle(k)] = at(n, 1);
        }
      }
      owners[size_t(c) + 1] = count_edge_owners(4 * int64_t(b), 4 * int64_t(e));
    }
  });
  build_edges(std::move(owners));

  // Rings: a vertex keeps its parent ring (one child corner per parent corner); a face point's ring is its quads
  // in order; an edge point's ring joins the child faces on both sides of its parent edge. The neighbour across
  // each ring corner (the vertex of the next corner) follows from the parent's corners too.
  const size_t child_vertices = size_t(vertices) + (quads ? faces : 0) + edges;
  const uint32_t first_edge_point = vertices + (quads ? faces : 0);
  auto edge_point = [&](uint32_t k) { return first_edge_point + parent.corner_edges_[k]; };
  auto face_point = [&](uint32_t k) { return vertices + parent.corner_face(k); };
  vertex_offsets_.resize(child_vertices + 1);
  ring_corners_.resize(4 * size_t(corners));
  ring_neighbors_.resize(4 * size_t(corners));
  boundary_vertex_.resize(child_vertices);
  parallel_for(0, vertices, kGrain, [&](int64_t b, int64_t e) {
    for (int64_t v = b; v < e; ++v) {
      vertex_offsets_[v] = parent.vertex_offsets_[v];
      for (uint32_t i = parent.vertex_offsets_[v]; i < parent.vertex_offsets_[v + 1]; ++i) {
        ring_corners_[i] = at(parent.ring_corners_[i], 0);
        ring_neighbors_[i] = edge_point(parent.ring_corners_[i]);
      }
      boundary_vertex_[v] = parent.boundary_vertex_[v];
    }
  });
  uint32_t max_face = 0;
  if (quads) {
    max_face = parent.uniform_size_;
    for (uint32_t f = 0; f < faces && parent.uniform_size_ == 0; ++f)
      max_face = std::max(max_face, parent.face_size(f));
    parallel_for(0, faces, kGrain, [&](int64_t b, int64_t e) {
      for (int64_t f = b; f < e; ++f) {
        const uint32_t o = parent.face_offset(f), n = parent.face_size(f);
        vertex_offsets_[vertices + f] = corners + o;
        for (uint32_t i = 0; i < n; ++i) {
          ring_corners_[corners + o + i] = 4 * (o + i) + 2;
          ring_neighbors_[corners + o + i] = edge_point(parent.prev_corner(o + i));
        }
        boundary_vertex_[vertices + f] = 0;
      }
    });
  }
  // Edge point e: 2 (quads) or 3 (triangles) child faces per face of e, after the rings of the older vertices.
  const uint32_t first_ring = quads ? 2 * corners : corners, per_face = quads ? 2 : 3;
  const std::vector<uint32_t> boundary_before = chunk_starts(edges, [&](int64_t b, int64_t e) {
    uint32_t n = 0;
    for (int64_t edge = b; edge < e; ++edge) n += parent.is_boundary_edge(size_t(edge));
    return n;
  });
  constexpr uint32_t kAhead = 8;  // edges between a prefetch and its use
  for_chunks(edges, boundary_before, [&](int64_t b, int64_t e, uint32_t boundary) {
    for (auto edge = uint32_t(b); edge < uint32_t(e); ++edge) {
      // The second face of an edge lies anywhere: ask for its corners two steps ahead.
      if (edge + 2 * kAhead < e) parent.prefetch_edge(edge + 2 * kAhead);
      if (edge + kAhead < e) {
        if (const uint32_t t = parent_twins[parent.edge_corners_[edge + kAhead]]; t != kNone) {
          prefetch_line(&parent.corner_edges_[t]);
          prefetch_line(&parent.face_vertices_[t]);
        }
      }
      const uint32_t offset = first_ring + per_face * (2 * edge - boundary);
      uint32_t *ring = ring_corners_.data() + offset, *around = ring_neighbors_.data() + offset;
      const uint32_t k = parent.edge_corners_[edge], t = parent_twins[k], n = parent.next_corner(k);
      vertex_offsets_[first_edge_point + edge] = offset;
      boundary_vertex_[first_edge_point + edge] = t == kNone;
      // Around the edge point: the parent's end vertices, and the face points (quads) or the edge points of the
      // other edges of the two triangles.
      if (t == kNone) {
        // Starts at the face whose outgoing edge is the boundary half.
        ring[0] = at(n, quads ? 3 : 2);
        around[0] = parent.corner_vertex(n);
        if (quads) {
          ring[1] = 4 * k + 1;
          around[1] = face_point(k);
        } else {
          ring[1] = middle(k);
          around[1] = edge_point(n);
          ring[2] = at(k, 1);
          around[2] = edge_point(parent.prev_corner(k));
        }
        ++boundary;
      } else if (quads) {
        const uint32_t nt = parent.next_corner(t);
        write_from_smallest(std::array{4 * k + 1, 4 * nt + 3, 4 * t + 1, 4 * n + 3},
                            std::array{face_point(k), parent.corner_vertex(nt), face_point(t), parent.corner_vertex(n)},
                            ring, around);
      } else {
        const uint32_t nt = parent.next_corner(t);
        write_from_smallest(std::array{at(k, 1), at(nt, 2), middle(t), at(t, 1), at(n, 2), middle(k)},
                            std::array{edge_point(parent.prev_corner(k)), parent.corner_vertex(nt), edge_point(nt),
                                       edge_point(parent.prev_corner(t)), parent.corner_vertex(n), edge_point(n)},
                            ring, around);
      }
    }
  });
  vertex_offsets_[child_vertices] = 4 * corners;
  const bool interior_edges = boundary_before.back() < edges;
  const uint32_t edge_point_valence = edges == 0 ? 0 : (quads ? 3 : 4) + (interior_edges ? per_face - 1 : 0);
  max_valence_ = std::max({parent.max_valence_, max_face, edge_point_valence});
}

uint32_t TopologyTables::find_edge(uint32_t a, uint32_t b) const {
  if (a >= vertex_count() || b >= vertex_count()) return kNone;
  for (uint32_t i = 0, n = ring_edge_count(a); i < n; ++i)
    if (ring_neighbor(a, i) == b) return ring_edge(a, i);
  return kNone;
}

}  // namespace tessera
