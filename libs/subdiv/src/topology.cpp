#include "tessera/subdiv/topology.hpp"

#include <algorithm>
#include <atomic>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {
namespace {

constexpr int64_t kGrain = 4096;

// Lowers `slot` to `value` if smaller (the first offending element wins, whatever the thread schedule).
void atomic_min(std::atomic<uint64_t>& slot, uint64_t value) {
  uint64_t seen = slot.load(std::memory_order_relaxed);
  while (value < seen && !slot.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
  }
}

constexpr uint64_t kNoError = ~uint64_t(0);

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
    throw InvalidInput(fmt::format("subdivision: face {} has fewer than 3 vertices, an index out of range (>= {}) or "
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
    throw TopologyError(fmt::format("subdivision: non-manifold edge ({}, {}): more than two faces share it, or two "
                                    "faces of opposite orientation",
                                    face_vertices_[k], face_vertices_[next_corner(k)]));
  }

  build_edges();
  ring_corners_ = std::move(by_vertex);
  build_rings();
}

void TopologyTables::build_edges() {
  // An edge belongs to its first corner in face order; numbering follows that order.
  const size_t corners = face_vertices_.size();
  corner_edges_.resize(corners);
  auto owns = [&](uint32_t k) { return twins_[k] == kNone || k < twins_[k]; };
  // A parallel prefix sum over fixed chunks (the same numbering for any thread count).
  const int64_t chunks = (int64_t(corners) + kGrain - 1) / kGrain;
  std::vector<uint32_t> first_edge(size_t(chunks) + 1, 0);
  parallel_for(0, chunks, 1, [&](int64_t b, int64_t e) {
    for (int64_t c = b; c < e; ++c) {
      uint32_t n = 0;
      for (auto k = uint32_t(c * kGrain); k < std::min<uint64_t>(corners, uint64_t(c + 1) * kGrain); ++k) n += owns(k);
      first_edge[size_t(c) + 1] = n;
    }
  });
  for (size_t c = 0; c < size_t(chunks); ++c) first_edge[c + 1] += first_edge[c];
  edge_corners_.resize(first_edge.back());
  parallel_for(0, chunks, 1, [&](int64_t b, int64_t e) {
    for (int64_t c = b; c < e; ++c) {
      uint32_t edge = first_edge[size_t(c)];
      for (auto k = uint32_t(c * kGrain); k < std::min<uint64_t>(corners, uint64_t(c + 1) * kGrain); ++k)
        if (owns(k)) {
          corner_edges_[k] = edge;
          edge_corners_[edge++] = k;
        }
    }
  });
  parallel_for(0, int64_t(corners), kGrain, [&](int64_t b, int64_t e) {
    for (int64_t c = b; c < e; ++c)
      if (!owns(uint32_t(c))) corner_edges_[c] = corner_edges_[twins_[c]];
  });
}

void TopologyTables::build_rings() {
  // ring_corners_ holds each vertex's corners in corner order; walk them counterclockwise in place of that order.
  const int64_t vertices = int64_t(vertex_count());
  boundary_vertex_.assign(vertex_count(), uint8_t(0));
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
      boundary_vertex_[v] = starts == 1;
      local_max = std::max(local_max, n + starts);
    }
    uint32_t seen = max_valence.load();
    while (local_max > seen && !max_valence.compare_exchange_weak(seen, local_max)) {
    }
  });
  if (bad_vertex != kNoError)
    throw TopologyError(fmt::format("subdivision: non-manifold vertex {}: its faces do not form a single fan",
                                    uint64_t(bad_vertex)));
  max_valence_ = max_valence;
}

uint32_t TopologyTables::find_edge(uint32_t a, uint32_t b) const {
  if (a >= vertex_count() || b >= vertex_count()) return kNone;
  for (uint32_t i = 0, n = ring_edge_count(a); i < n; ++i)
    if (ring_neighbor(a, i) == b) return ring_edge(a, i);
  return kNone;
}

}  // namespace tessera
