#include "tessera/mesh/primitives.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/soup.hpp"

namespace tessera {
namespace {

constexpr double kPhi = 1.6180339887498948482;  // the golden ratio

void require(bool ok, const char* what, int value) {
  if (!ok) throw InvalidInput(fmt::format("{}: {} is out of range", what, value));
}

/// Scales every position to unit length (the solids' circumradius 1).
void normalize_positions(PolyMesh& mesh) {
  for (Vec3& p : mesh.positions) p = glm::normalize(p);
}

/// For a convex polytope around the origin: reverses every face whose normal points toward the origin.
void orient_convex(PolyMesh& mesh) {
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    if (glm::dot(face_area_vector(mesh, f), mesh.positions[face[0]]) < 0)
      std::reverse(mesh.face_vertices.begin() + mesh.face_offsets[f],
                   mesh.face_vertices.begin() + mesh.face_offsets[f + 1]);
  }
}

/// All triangles of points whose three sides have the polytope's edge length (the shortest distance): the faces of
/// the icosahedron and the octahedron, whose faces are exactly their triangles of shortest edges.
PolyMesh triangles_of_shortest_edges(std::vector<Vec3> points) {
  PolyMesh mesh;
  mesh.positions = std::move(points);
  const std::vector<Vec3>& p = mesh.positions;
  double shortest = INFINITY;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) shortest = std::min(shortest, glm::distance(p[i], p[j]));
  const auto is_edge = [&](size_t i, size_t j) { return glm::distance(p[i], p[j]) < shortest * (1 + 1e-9); };
  const auto n = uint32_t(mesh.positions.size());
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j)
      for (uint32_t k = j + 1; k < n; ++k)
        if (is_edge(i, j) && is_edge(j, k) && is_edge(i, k)) mesh.add_face({i, j, k});
  orient_convex(mesh);
  normalize_positions(mesh);
  return mesh;
}

/// The surface of the cube [-1, 1]^3 with each face split into n x n quads, welded into one closed mesh. Face
/// (N, U, V) has U x V = N, so its grid quads (s, t), (s+1, t), (s+1, t+1), (s, t+1) are counterclockwise from outside.
PolyMesh cube_grid(int n) {
  const std::array<std::array<Vec3, 3>, 6> frames{{
      {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
      {Vec3(-1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0)},
      {Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 0)},
      {Vec3(0, -1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)},
      {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0)},
      {Vec3(0, 0, -1), Vec3(0, 1, 0), Vec3(1, 0, 0)},
  }};
  PolygonSoup soup;
  const auto at = [n](int i) { return -1.0 + 2.0 * i / n; };  // identical on both faces of a shared cube edge
  for (const auto& [normal, u, v] : frames)
    for (int t = 0; t < n; ++t)
      for (int s = 0; s < n; ++s) {
        const std::array<Vec3, 4> quad{normal + at(s) * u + at(t) * v, normal + at(s + 1) * u + at(t) * v,
                                       normal + at(s + 1) * u + at(t + 1) * v, normal + at(s) * u + at(t + 1) * v};
        soup.add_face(quad);
      }
  return weld(soup);
}

/// Quads (i, j), (i+1, j), (i+1, j+1), (i, j+1) of an n x m grid of vertices index(i, j), wrapping as asked.
template <class Index>
void add_grid_quads(PolyMesh& mesh, int n, int m, Index index) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) mesh.add_face({index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)});
}

}  // namespace

PolyMesh make_tetrahedron() {
  PolyMesh mesh;
  mesh.positions = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  mesh.add_face({0, 1, 2});
  mesh.add_face({0, 3, 1});
  mesh.add_face({0, 2, 3});
  mesh.add_face({1, 3, 2});
  orient_convex(mesh);
  normalize_positions(mesh);
  return mesh;
}

PolyMesh make_box() { return cube_grid(1); }

PolyMesh make_cube() {
  PolyMesh mesh = make_box();
  normalize_positions(mesh);
  return mesh;
}

PolyMesh make_octahedron() {
  return triangles_of_shortest_edges(
      {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)});
}

PolyMesh make_icosahedron() {
  std::vector<Vec3> points;
  for (double a : {-1.0, 1.0})
    for (double b : {-kPhi, kPhi}) {
      points.emplace_back(0, a, b);
      points.emplace_back(a, b, 0);
      points.emplace_back(b, 0, a);
    }
  return triangles_of_shortest_edges(std::move(points));
}

PolyMesh make_dodecahedron() {
  // The dual of the icosahedron: a vertex per icosahedron face (its centroid), a pentagon per icosahedron vertex
  // joining the centroids of the five faces around it, sorted by angle about the vertex.
  const PolyMesh ico = make_icosahedron();
  PolyMesh mesh;
  std::vector<std::vector<uint32_t>> faces_at(ico.vertex_count());
  for (size_t f = 0; f < ico.face_count(); ++f) {
    Vec3 c(0.0);
    for (uint32_t v : ico.face(f)) {
      c += ico.positions[v];
      faces_at[v].push_back(uint32_t(f));
    }
    mesh.positions.push_back(c / 3.0);
  }
  for (size_t v = 0; v < ico.vertex_count(); ++v) {
    const Vec3 axis = ico.positions[v];
    const Vec3 e1 = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    const Vec3 e2 = glm::cross(axis, e1);
    auto& ring = faces_at[v];
    const auto angle = [&](uint32_t f) {
      return std::atan2(glm::dot(mesh.positions[f], e2), glm::dot(mesh.positions[f], e1));
    };
    std::sort(ring.begin(), ring.end(), [&](uint32_t a, uint32_t b) { return angle(a) < angle(b); });
    mesh.add_face(ring);
  }
  orient_convex(mesh);
  normalize_positions(mesh);
  return mesh;
}

PolyMesh make_uv_sphere(int slices, int stacks) {
  require(slices >= 3 && slices <= 1 << 14, "uv sphere slices", slices);
  require(stacks >= 2 && stacks <= 1 << 14, "uv sphere stacks", stacks);
  // Vertex (i, j): polar angle theta = pi i / stacks from +y, longitude phi = 2 pi j / slices from +z toward +x.
  // Seen from outside, i grows downward and j to the right, so (i,j), (i+1,j), (i+1,j+1), (i,j+1) is
  // counterclockwise; the pole rows collapse to one vertex each.
  PolyMesh mesh;
  mesh.positions.emplace_back(0, 1, 0);
  for (int i = 1; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const double theta = kPi * i / stacks, phi = 2 * kPi * j / slices;
      mesh.positions.emplace_back(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
    }
  mesh.positions.emplace_back(0, -1, 0);
  const auto south = uint32_t(mesh.positions.size() - 1);
  const auto index = [&](int i, int j) -> uint32_t {
    if (i == 0) return 0;
    if (i == stacks) return south;
    return uint32_t(1 + (i - 1) * slices + j % slices);
  };
  const auto uv = [&](int i, int j) { return Vec2(double(j) / slices, 1.0 - double(i) / stacks); };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const std::array<std::pair<int, int>, 4> quad{{{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
      std::vector<uint32_t> face;
      for (const auto& [a, b] : quad) {
        const uint32_t v = index(a, b);
        if (!face.empty() && face.back() == v) continue;  // the pole's collapsed corners
        face.push_back(v);
        mesh.corner_uvs.push_back(uv(a, b));
      }
      if (face.front() == face.back()) {
        face.pop_back();
        mesh.corner_uvs.pop_back();
      }
      mesh.add_face(face);
    }
  mesh.normals = mesh.positions;
  return mesh;
}

PolyMesh make_quad_sphere(int n) {
  require(n >= 1 && n <= 4096, "quad sphere subdivisions", n);
  PolyMesh mesh = cube_grid(n);
  normalize_positions(mesh);
  mesh.normals = mesh.positions;
  return mesh;
}

PolyMesh make_cylinder(int segments, bool caps) {
  require(segments >= 3 && segments <= 1 << 20, "cylinder segments", segments);
  // Ring vertex k at angle 2 pi k / n from +z toward +x: bottom ring k, top ring n + k. Seen from outside the side
  // quad (bottom k, bottom k+1, top k+1, top k) is counterclockwise; seen from +y the top ring runs counterclockwise.
  PolyMesh mesh;
  const auto n = uint32_t(segments);
  for (double y : {-1.0, 1.0})
    for (uint32_t k = 0; k < n; ++k) {
      const double a = 2 * kPi * k / n;
      mesh.positions.emplace_back(std::sin(a), y, std::cos(a));
    }
  for (uint32_t k = 0; k < n; ++k) mesh.add_face({k, (k + 1) % n, n + (k + 1) % n, n + k});
  if (caps) {
    std::vector<uint32_t> top, bottom;
    for (uint32_t k = 0; k < n; ++k) {
      top.push_back(n + k);
      bottom.push_back(n - 1 - k);
    }
    mesh.add_face(top);
    mesh.add_face(bottom);
  }
  return mesh;
}

PolyMesh make_cone(int segments, bool cap) {
  require(segments >= 3 && segments <= 1 << 20, "cone segments", segments);
  PolyMesh mesh;
  const auto n = uint32_t(segments);
  for (uint32_t k = 0; k < n; ++k) {
    const double a = 2 * kPi * k / n;
    mesh.positions.emplace_back(std::sin(a), -1, std::cos(a));
  }
  mesh.positions.emplace_back(0, 1, 0);
  for (uint32_t k = 0; k < n; ++k) mesh.add_face({k, (k + 1) % n, n});
  if (cap) {
    std::vector<uint32_t> base;
    for (uint32_t k = 0; k < n; ++k) base.push_back(n - 1 - k);
    mesh.add_face(base);
  }
  return mesh;
}

PolyMesh make_torus(double major_radius, double minor_radius, int n, int m) {
  require(n >= 3 && n <= 1 << 14, "torus ring segments", n);
  require(m >= 3 && m <= 1 << 14, "torus tube segments", m);
  if (!(minor_radius > 0 && minor_radius < major_radius && std::isfinite(major_radius)))
    throw InvalidInput(
        fmt::format("torus radii must satisfy 0 < r < R, got R = {}, r = {}", major_radius, minor_radius));
  // Vertex (i, j): u = 2 pi i / n around the ring (from +z toward +x), v = 2 pi j / m around the tube (0 outside,
  // growing upward there). Seen from outside i grows to the right and j upward: the grid quads are counterclockwise.
  PolyMesh mesh;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * kPi * i / n, v = 2 * kPi * j / m;
      const Vec3 normal(std::cos(v) * std::sin(u), std::sin(v), std::cos(v) * std::cos(u));
      mesh.positions.push_back(Vec3(major_radius * std::sin(u), 0, major_radius * std::cos(u)) + minor_radius * normal);
      mesh.normals.push_back(normal);
    }
  add_grid_quads(mesh, n, m, [&](int i, int j) { return uint32_t((i % n) * m + j % m); });
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      for (const auto& [a, b] : std::array<std::pair<int, int>, 4>{{{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}})
        mesh.corner_uvs.emplace_back(double(a) / n, double(b) / m);
  return mesh;
}

PolyMesh make_grid(int nx, int ny) {
  require(nx >= 1 && nx <= 1 << 14, "grid columns", nx);
  require(ny >= 1 && ny <= 1 << 14, "grid rows", ny);
  // Vertex (i, j) at x = -1 + 2i/nx, z = -1 + 2j/ny. Seen from +y (x right, -z up) the quad (i,j), (i,j+1),
  // (i+1,j+1), (i+1,j) is counterclockwise.
  PolyMesh mesh;
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) {
      mesh.positions.emplace_back(-1.0 + 2.0 * i / nx, 0, -1.0 + 2.0 * j / ny);
      mesh.normals.emplace_back(0, 1, 0);
      mesh.uvs.emplace_back(double(i) / nx, double(j) / ny);
    }
  const auto index = [&](int i, int j) { return uint32_t(i * (ny + 1) + j); };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) mesh.add_face({index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j)});
  return mesh;
}

}  // namespace tessera
