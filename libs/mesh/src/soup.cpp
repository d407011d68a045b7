#include "tessera/mesh/soup.hpp"

#include <fmt/format.h>

#include <array>
#include <bit>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

/// Hash of three 64-bit words (a multiply-xorshift mix).
struct Key3Hash {
  size_t operator()(const std::array<uint64_t, 3>& k) const {
    uint64_t h = k[0] * 0x9E3779B97F4A7C15ULL;
    h = (h ^ (h >> 29) ^ k[1]) * 0xBF58476D1CE4E5B9ULL;
    h = (h ^ (h >> 31) ^ k[2]) * 0x94D049BB133111EBULL;
    return size_t(h ^ (h >> 32));
  }
};

uint64_t bits(double v) { return std::bit_cast<uint64_t>(v == 0.0 ? 0.0 : v); }  // -0 and +0 weld

WeldedPoints weld_exact(std::span<const Vec3> points) {
  WeldedPoints out;
  out.remap.resize(points.size());
  std::unordered_map<std::array<uint64_t, 3>, uint32_t, Key3Hash> index;
  index.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const auto [it, inserted] = index.try_emplace({bits(p.x), bits(p.y), bits(p.z)}, uint32_t(out.points.size()));
    if (inserted) out.points.push_back(p);
    out.remap[i] = it->second;
  }
  return out;
}

WeldedPoints weld_tolerance(std::span<const Vec3> points, double tolerance) {
  WeldedPoints out;
  out.remap.resize(points.size());
  // Cells of size `tolerance`: a representative within the tolerance lies in one of the 27 cells around a point.
  std::unordered_map<std::array<uint64_t, 3>, std::vector<uint32_t>, Key3Hash> grid;
  const auto cell = [&](double v) { return int64_t(std::floor(v / tolerance)); };
  const double tol2 = tolerance * tolerance;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const int64_t cx = cell(p.x), cy = cell(p.y), cz = cell(p.z);
    uint32_t found = UINT32_MAX;
    for (int64_t dz = -1; dz <= 1 && found == UINT32_MAX; ++dz)
      for (int64_t dy = -1; dy <= 1 && found == UINT32_MAX; ++dy)
        for (int64_t dx = -1; dx <= 1 && found == UINT32_MAX; ++dx) {
          const auto it = grid.find({uint64_t(cx + dx), uint64_t(cy + dy), uint64_t(cz + dz)});
          if (it == grid.end()) continue;
          for (uint32_t r : it->second) {
            const Vec3 d = out.points[r] - p;
            if (glm::dot(d, d) <= tol2) {
              found = r;
              break;
            }
          }
        }
    if (found == UINT32_MAX) {
      found = uint32_t(out.points.size());
      out.points.push_back(p);
      grid[{uint64_t(cx), uint64_t(cy), uint64_t(cz)}].push_back(found);
    }
    out.remap[i] = found;
  }
  return out;
}

}  // namespace

WeldedPoints weld_points(std::span<const Vec3> points, double tolerance) {
  if (!(tolerance >= 0)) throw InvalidInput(fmt::format("weld tolerance must be >= 0, got {}", tolerance));
  return tolerance == 0 ? weld_exact(points) : weld_tolerance(points, tolerance);
}

PolyMesh weld(const PolygonSoup& soup, double tolerance) {
  PolyMesh mesh;
  mesh.positions = soup.points;
  mesh.face_offsets = soup.face_offsets;
  mesh.face_vertices.resize(soup.points.size());
  std::iota(mesh.face_vertices.begin(), mesh.face_vertices.end(), 0u);
  weld_vertices(mesh, tolerance);
  return mesh;
}

PolygonSoup to_soup(const PolyMesh& mesh) {
  PolygonSoup soup;
  soup.points.reserve(mesh.face_vertices.size());
  for (uint32_t v : mesh.face_vertices) soup.points.push_back(mesh.positions[v]);
  soup.face_offsets = mesh.face_offsets;
  return soup;
}

size_t weld_vertices(PolyMesh& mesh, double tolerance) {
  WeldedPoints welded = weld_points(mesh.positions, tolerance);
  const size_t n = welded.points.size(), merged = mesh.positions.size() - n;
  // Per-vertex properties: the first vertex of each group gives the value, unless uvs or normals differ inside a
  // group: then they become face-varying (each corner keeps its old vertex's value).
  std::vector<uint32_t> first(n, UINT32_MAX);
  for (uint32_t v = 0; v < welded.remap.size(); ++v)
    if (first[welded.remap[v]] == UINT32_MAX) first[welded.remap[v]] = v;
  const auto to_corners = [&](auto& property, auto& per_corner) {
    if (property.size() != welded.remap.size() || property.empty() || !per_corner.empty()) return;
    bool differ = false;
    for (uint32_t v = 0; v < welded.remap.size() && !differ; ++v)
      differ = property[v] != property[first[welded.remap[v]]];
    if (!differ) return;
    per_corner.resize(mesh.face_vertices.size());
    for (size_t c = 0; c < mesh.face_vertices.size(); ++c) per_corner[c] = property[mesh.face_vertices[c]];
    property.clear();
  };
  to_corners(mesh.uvs, mesh.corner_uvs);
  to_corners(mesh.normals, mesh.corner_normals);
  const auto gather = [&](auto& property) {
    if (property.empty()) return;
    std::remove_reference_t<decltype(property)> kept(n);
    for (size_t i = 0; i < n; ++i) kept[i] = property[first[i]];
    property.swap(kept);
  };
  gather(mesh.normals);
  gather(mesh.uvs);
  gather(mesh.colors);
  mesh.positions = std::move(welded.points);

  // Faces: remap, drop repeated consecutive corners (cyclically), drop faces below 3 corners.
  const bool has_uv = !mesh.corner_uvs.empty(), has_n = !mesh.corner_normals.empty();
  std::vector<uint32_t> offsets{0}, corners;
  std::vector<Vec2> corner_uvs;
  std::vector<Vec3> corner_normals;
  corners.reserve(mesh.face_vertices.size());
  for (size_t f = 0; f + 1 < mesh.face_offsets.size(); ++f) {
    const uint32_t b = mesh.face_offsets[f], e = mesh.face_offsets[f + 1];
    const size_t start = corners.size();
    for (uint32_t c = b; c < e; ++c) {
      const uint32_t v = welded.remap[mesh.face_vertices[c]];
      if (corners.size() > start && corners.back() == v) continue;
      corners.push_back(v);
      if (has_uv) corner_uvs.push_back(mesh.corner_uvs[c]);
      if (has_n) corner_normals.push_back(mesh.corner_normals[c]);
    }
    while (corners.size() - start > 1 && corners.back() == corners[start]) {
      corners.pop_back();
      if (has_uv) corner_uvs.pop_back();
      if (has_n) corner_normals.pop_back();
    }
    if (corners.size() - start < 3) {
      corners.resize(start);
      if (has_uv) corner_uvs.resize(start);
      if (has_n) corner_normals.resize(start);
      continue;
    }
    offsets.push_back(uint32_t(corners.size()));
  }
  mesh.face_offsets = std::move(offsets);
  mesh.face_vertices = std::move(corners);
  mesh.corner_uvs = std::move(corner_uvs);
  mesh.corner_normals = std::move(corner_normals);
  for (EdgeCrease& c : mesh.creases) c = {welded.remap[c.v0], welded.remap[c.v1], c.sharpness};
  for (VertexCorner& c : mesh.corners) c.v = welded.remap[c.v];
  return merged;
}

size_t split_pinched_vertices(PolyMesh& mesh) {
  // Union-find over the face corners: two corners at the same vertex are in one fan when their faces share an edge
  // at that vertex (the edge {v, w} seen from both corners).
  const size_t corners = mesh.face_vertices.size();
  std::vector<uint32_t> parent(corners);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](uint32_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  std::unordered_map<uint64_t, uint32_t> edge_corner;
  edge_corner.reserve(2 * corners);
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const uint32_t b = mesh.face_offsets[f], n = mesh.face_size(f);
    for (uint32_t j = 0; j < n; ++j) {
      const uint32_t c = b + j, v = mesh.face_vertices[c];
      for (uint32_t w : {mesh.face_vertices[b + (j + 1) % n], mesh.face_vertices[b + (j + n - 1) % n]}) {
        const auto [it, inserted] = edge_corner.try_emplace(uint64_t(v) << 32 | w, c);
        if (!inserted) parent[find(c)] = find(it->second);
      }
    }
  }
  // The first fan seen at a vertex keeps it; every other fan gets a new vertex.
  const size_t original = mesh.vertex_count();
  const bool normals = mesh.normals.size() == original, uvs = mesh.uvs.size() == original,
             colors = mesh.colors.size() == original;
  std::vector<uint32_t> first_root(original, UINT32_MAX);
  std::unordered_map<uint32_t, uint32_t> fan_vertex;  // fan root -> its new vertex
  for (uint32_t c = 0; c < corners; ++c) {
    const uint32_t v = mesh.face_vertices[c], root = find(c);
    if (first_root[v] == UINT32_MAX) first_root[v] = root;
    if (first_root[v] == root) continue;
    const auto [it, inserted] = fan_vertex.try_emplace(root, uint32_t(mesh.positions.size()));
    if (inserted) {
      mesh.positions.push_back(mesh.positions[v]);
      if (normals && original > 0) mesh.normals.push_back(mesh.normals[v]);
      if (uvs && original > 0) mesh.uvs.push_back(mesh.uvs[v]);
      if (colors && original > 0) mesh.colors.push_back(mesh.colors[v]);
    }
    mesh.face_vertices[c] = it->second;
  }
  return mesh.vertex_count() - original;
}

}  // namespace tessera
