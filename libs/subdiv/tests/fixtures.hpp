#pragma once
// Meshes built in code for the subdivision tests: cube, quad grid with boundary, octahedron, icosahedron, a mixed
// triangle/quad/pentagon solid, and 10k-face tori (quads and triangles). All closed meshes are oriented outward.
#include <cmath>
#include <vector>

#include "tessera/core/rng.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera::test {

/// The box [-1, 1]^3 as 6 quads.
inline PolyMesh cube() {
  PolyMesh m;
  m.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  m.add_face({0, 3, 2, 1});
  m.add_face({4, 5, 6, 7});
  m.add_face({0, 1, 5, 4});
  m.add_face({2, 3, 7, 6});
  m.add_face({0, 4, 7, 3});
  m.add_face({1, 2, 6, 5});
  return m;
}

/// The cube with its top face's four edges and one vertical edge (6-2) tagged with sharpness s, and corner 0 too:
/// vertex 6 then has three sharp edges (corner rule), vertices 4, 5, 7 two (crease rule), vertex 2 one (dart).
inline PolyMesh creased_cube(float s) {
  PolyMesh m = cube();
  m.creases = {{4, 5, s}, {5, 6, s}, {6, 7, s}, {7, 4, s}, {6, 2, s}};
  m.corners = {{0, s}};
  return m;
}

/// An nx x ny grid of quads over [-1, 1]^2 with a gentle bump (a surface with boundary and four corners).
inline PolyMesh grid(int nx, int ny) {
  PolyMesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = -1.0 + 2.0 * i / nx, y = -1.0 + 2.0 * j / ny;
      m.positions.push_back({x, y, 0.3 * std::sin(2.0 * x) * std::cos(1.5 * y)});
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const auto v = uint32_t(j * (nx + 1) + i);
      m.add_face({v, v + 1, v + uint32_t(nx) + 2, v + uint32_t(nx) + 1});
    }
  return m;
}

/// Faces of a convex polyhedron around the origin from its vertices: every triple at edge length `edge` apart,
/// oriented outward.
inline PolyMesh triangulated_hull(std::vector<Vec3> positions, double edge) {
  PolyMesh m;
  m.positions = std::move(positions);
  const auto n = uint32_t(m.positions.size());
  auto adjacent = [&](uint32_t a, uint32_t b) {
    return std::abs(glm::distance(m.positions[a], m.positions[b]) - edge) < 1e-9;
  };
  for (uint32_t a = 0; a < n; ++a)
    for (uint32_t b = a + 1; b < n; ++b)
      for (uint32_t c = b + 1; c < n; ++c) {
        if (!adjacent(a, b) || !adjacent(b, c) || !adjacent(a, c)) continue;
        const Vec3 normal = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
        if (glm::dot(normal, m.positions[a]) > 0)
          m.add_face({a, b, c});
        else
          m.add_face({a, c, b});
      }
  return m;
}

inline PolyMesh octahedron() {
  return triangulated_hull({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}, std::sqrt(2.0));
}

inline PolyMesh icosahedron() {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v;
  for (double s : {-1.0, 1.0})
    for (double t : {-p, p}) {
      v.push_back({0, s, t});
      v.push_back({s, t, 0});
      v.push_back({t, 0, s});
    }
  return triangulated_hull(v, 2.0);
}

/// A pentagonal prism with a pyramid roof: a pentagon, five quads and five triangles.
inline PolyMesh house() {
  PolyMesh m;
  for (int i = 0; i < 5; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / 5.0;
    m.positions.push_back({std::cos(a), std::sin(a), 0.0});
  }
  for (int i = 0; i < 5; ++i) m.positions.push_back({m.positions[i].x, m.positions[i].y, 1.0});
  m.positions.push_back({0.1, -0.05, 1.7});
  m.add_face({4, 3, 2, 1, 0});
  for (uint32_t i = 0; i < 5; ++i) {
    const uint32_t j = (i + 1) % 5;
    m.add_face({i, j, j + 5, i + 5});
    m.add_face({i + 5, j + 5, 10});
  }
  return m;
}

/// An n x m torus of quads (R = 2, r = 0.7), vertices jittered deterministically; triangles splits every quad.
inline PolyMesh torus(int n, int m, bool triangles = false) {
  PolyMesh mesh;
  Rng rng(7);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2.0 * 3.14159265358979323846 * i / n, v = 2.0 * 3.14159265358979323846 * j / m;
      const double r = 0.7 * (1.0 + 0.05 * rng.uniform(-1.0, 1.0));
      mesh.positions.push_back(
          {(2.0 + r * std::cos(v)) * std::cos(u), r * std::sin(v), (2.0 + r * std::cos(v)) * std::sin(u)});
    }
  auto id = [&](int i, int j) { return uint32_t((i % n) * m + (j % m)); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (triangles) {
        mesh.add_face({a, d, c});
        mesh.add_face({a, c, b});
      } else {
        mesh.add_face({a, d, c, b});
      }
    }
  return mesh;
}

}  // namespace tessera::test
