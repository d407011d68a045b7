#include "tessera/mesh/corner_table.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "tessera/core/error.hpp"

namespace tessera {

std::vector<uint32_t> build_opposites(std::span<const uint32_t> v, size_t vertex_count, size_t* unpaired_shared) {
  const auto n = uint32_t(v.size());
  std::vector<uint32_t> o(n, CornerTable::kNoCorner);
  // The edge facing corner c runs from V[next(c)] to V[prev(c)]; bucket corners by that edge's lower vertex.
  const auto lo = [&](uint32_t c) { return std::min(v[CornerTable::next(c)], v[CornerTable::prev(c)]); };
  const auto hi = [&](uint32_t c) { return std::max(v[CornerTable::next(c)], v[CornerTable::prev(c)]); };
  std::vector<uint32_t> start(vertex_count + 1, 0);
  for (uint32_t c = 0; c < n; ++c) ++start[lo(c) + 1];
  for (size_t i = 0; i < vertex_count; ++i) start[i + 1] += start[i];
  std::vector<uint32_t> bucket(n), fill(start.begin(), start.end() - 1);
  for (uint32_t c = 0; c < n; ++c) bucket[fill[lo(c)]++] = c;

  size_t unpaired = 0;
  for (size_t b = 0; b < vertex_count; ++b) {
    const auto first = bucket.begin() + start[b], last = bucket.begin() + start[b + 1];
    std::sort(first, last, [&](uint32_t x, uint32_t y) { return hi(x) < hi(y) || (hi(x) == hi(y) && x < y); });
    for (auto run = first; run != last;) {
      auto end = run;
      while (end != last && hi(*end) == hi(*run)) ++end;
      const uint32_t a = *run;
      if (end - run == 2) {
        const uint32_t d = *(run + 1);
        if (v[CornerTable::next(a)] == v[CornerTable::prev(d)] && v[CornerTable::prev(a)] == v[CornerTable::next(d)] &&
            v[CornerTable::next(a)] != v[CornerTable::prev(a)]) {
          o[a] = d;
          o[d] = a;
        } else {
          ++unpaired;
        }
      } else if (end - run > 2) {
        ++unpaired;
      }
      run = end;
    }
  }
  if (unpaired_shared != nullptr) *unpaired_shared = unpaired;
  return o;
}

CornerTable::CornerTable(const PolyMesh& mesh) : g_(mesh.positions), v_(mesh.face_vertices) {
  if (!mesh.is_triangle_mesh())
    throw TopologyError("a corner table needs a triangle mesh (triangulate the polygons first)");
  build();
}

CornerTable::CornerTable(std::vector<Vec3> geometry, std::vector<uint32_t> vertices)
    : g_(std::move(geometry)), v_(std::move(vertices)) {
  if (v_.size() % 3 != 0)
    throw TopologyError(fmt::format("a corner table needs 3 corners per triangle, got {}", v_.size()));
  build();
}

void CornerTable::build() {
  if (v_.size() >= kNoCorner) throw TopologyError("too many corners for 32-bit corner indices");
  for (uint32_t x : v_)
    if (x >= g_.size())
      throw TopologyError(fmt::format("corner vertex {} is out of range ({} vertices)", x, g_.size()));
  o_ = build_opposites(v_, g_.size(), &unpaired_shared_);
  // A corner per vertex, turned clockwise as far as the fan allows (at most the vertex's corner count of steps).
  std::vector<uint32_t> valence(g_.size(), 0);
  vertex_corner_.assign(g_.size(), kNoCorner);
  for (uint32_t c = 0; c < v_.size(); ++c) {
    ++valence[v_[c]];
    if (vertex_corner_[v_[c]] == kNoCorner) vertex_corner_[v_[c]] = c;
  }
  for (uint32_t x = 0; x < g_.size(); ++x) {
    const uint32_t start = vertex_corner_[x];
    if (start == kNoCorner) continue;
    uint32_t c = start;
    for (uint32_t step = 0; step < valence[x]; ++step) {
      const uint32_t u = unswing(c);
      if (u == kNoCorner || u == start) break;
      c = u;
    }
    vertex_corner_[x] = unswing(c) == kNoCorner ? c : start;
  }
}

std::vector<uint32_t> CornerTable::corners_around(uint32_t v) const {
  std::vector<uint32_t> fan;
  const uint32_t start = vertex_corner_[v];
  if (start == kNoCorner) return fan;
  uint32_t c = start;
  do {
    fan.push_back(c);
    c = swing(c);
  } while (c != kNoCorner && c != start && fan.size() <= v_.size());
  return fan;
}

std::vector<uint32_t> CornerTable::one_ring(uint32_t v) const {
  const std::vector<uint32_t> fan = corners_around(v);
  std::vector<uint32_t> ring;
  for (uint32_t c : fan) ring.push_back(v_[next(c)]);
  if (!fan.empty() && swing(fan.back()) == kNoCorner) ring.push_back(v_[prev(fan.back())]);
  return ring;
}

}  // namespace tessera
