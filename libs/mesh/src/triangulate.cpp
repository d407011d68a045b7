#include "tessera/mesh/triangulate.hpp"

#include <algorithm>
#include <numeric>

namespace tessera {
namespace {

/// The polygon projected on the plane through its Newell normal n, as 2D points with (u, v, n) right-handed, so a
/// polygon counterclockwise about n is counterclockwise in 2D. Returns false when the polygon has no area.
bool project_to_plane(std::span<const Vec3> points, std::vector<Vec2>& out) {
  Vec3 n(0.0);
  for (size_t i = 0; i < points.size(); ++i) n += glm::cross(points[i], points[(i + 1) % points.size()]);
  const double len = glm::length(n);
  if (!(len > 0)) return false;
  n /= len;
  const Vec3 u = glm::normalize(glm::cross(std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0), n));
  const Vec3 v = glm::cross(n, u);
  out.clear();
  for (const Vec3& p : points) out.emplace_back(glm::dot(p, u), glm::dot(p, v));
  return true;
}

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool convex_2d(const std::vector<Vec2>& p) {
  double scale = 0;
  for (const Vec2& q : p) scale = std::max({scale, std::abs(q.x), std::abs(q.y)});
  const double eps = 1e-12 * scale * scale;
  for (size_t i = 0; i < p.size(); ++i)
    if (cross2(p[i], p[(i + 1) % p.size()], p[(i + 2) % p.size()]) < -eps) return false;
  return true;
}

/// Ear clipping of a counterclockwise 2D polygon.
std::vector<std::array<uint32_t, 3>> clip_ears(const std::vector<Vec2>& p) {
  std::vector<uint32_t> ring(p.size());
  std::iota(ring.begin(), ring.end(), 0u);
  std::vector<std::array<uint32_t, 3>> triangles;
  const auto inside = [&](const Vec2& q, const Vec2& a, const Vec2& b, const Vec2& c) {
    return cross2(a, b, q) >= 0 && cross2(b, c, q) >= 0 && cross2(c, a, q) >= 0;
  };
  while (ring.size() > 3) {
    const size_t n = ring.size();
    size_t ear = n;
    size_t best = 0;  // fallback when no ear exists (a self-intersecting polygon): the most convex corner
    double best_turn = -INFINITY;
    for (size_t i = 0; i < n && ear == n; ++i) {
      const uint32_t a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
      const double turn = cross2(p[a], p[b], p[c]);
      if (turn > best_turn) {
        best_turn = turn;
        best = i;
      }
      if (turn <= 0) continue;
      bool empty = true;
      for (size_t j = 0; j < n && empty; ++j) {
        const uint32_t q = ring[j];
        if (q == a || q == b || q == c || p[q] == p[a] || p[q] == p[b] || p[q] == p[c]) continue;
        empty = !inside(p[q], p[a], p[b], p[c]);
      }
      if (empty) ear = i;
    }
    if (ear == n) ear = best;
    triangles.push_back({ring[(ear + n - 1) % n], ring[ear], ring[(ear + 1) % n]});
    ring.erase(ring.begin() + std::ptrdiff_t(ear));
  }
  triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

std::vector<std::array<uint32_t, 3>> fan(size_t s) {
  std::vector<std::array<uint32_t, 3>> triangles;
  for (uint32_t i = 1; i + 1 < s; ++i) triangles.push_back({0, i, i + 1});
  return triangles;
}

}  // namespace

bool is_convex_polygon(std::span<const Vec3> points) {
  std::vector<Vec2> p;
  return !project_to_plane(points, p) || convex_2d(p);
}

std::vector<std::array<uint32_t, 3>> triangulate_polygon(std::span<const Vec3> points) {
  if (points.size() < 3) return {};
  std::vector<Vec2> p;
  if (points.size() == 3 || !project_to_plane(points, p) || convex_2d(p)) return fan(points.size());
  return clip_ears(p);
}

PolyMesh triangulate(const PolyMesh& mesh) {
  PolyMesh out;
  out.positions = mesh.positions;
  out.normals = mesh.normals;
  out.uvs = mesh.uvs;
  out.colors = mesh.colors;
  out.creases = mesh.creases;
  out.corners = mesh.corners;
  const bool corner_uv = !mesh.corner_uvs.empty(), corner_n = !mesh.corner_normals.empty();
  out.face_vertices.reserve(mesh.face_vertices.size() * 3 / 2);
  std::vector<Vec3> points;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    points.clear();
    for (uint32_t v : face) points.push_back(mesh.positions[v]);
    const uint32_t base = mesh.face_offsets[f];
    for (const auto& tri : triangulate_polygon(points)) {
      for (uint32_t i : tri) {
        out.face_vertices.push_back(face[i]);
        if (corner_uv) out.corner_uvs.push_back(mesh.corner_uvs[base + i]);
        if (corner_n) out.corner_normals.push_back(mesh.corner_normals[base + i]);
      }
      out.face_offsets.push_back(uint32_t(out.face_vertices.size()));
    }
  }
  return out;
}

}  // namespace tessera
