#include "tessera/mesh/smoothing.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera {
namespace {

/// A unit sphere of triangles with every vertex moved radially by up to +-3%.
PolyMesh noisy_sphere() {
  PolyMesh sphere = triangulate(make_quad_sphere(12));
  Rng rng(7);
  for (Vec3& p : sphere.positions) p *= 1.0 + rng.uniform(-0.03, 0.03);
  return sphere;
}

/// The mean of 1 - cos(dihedral angle) over the edges: 0 for a plane, small for a fine smooth surface.
double roughness(const PolyMesh& mesh) {
  const EdgeTable edges = build_edge_table(mesh);
  const std::vector<Vec3> normals = face_normals(mesh);
  double sum = 0;
  for (size_t e = 0; e < edges.size(); ++e) {
    const uint32_t f0 = edges.face_of_corner[edges.half_edges[edges.offsets[e]]];
    const uint32_t f1 = edges.face_of_corner[edges.half_edges[edges.offsets[e] + 1]];
    sum += 1 - glm::dot(normals[f0], normals[f1]);
  }
  return sum / double(edges.size());
}

double volume_after(SmoothingMethod method, int iterations) {
  PolyMesh mesh = noisy_sphere();
  smooth(mesh, {method, iterations});
  return signed_volume(mesh);
}

TEST(Smoothing, LaplacianShrinksTaubinKeepsTheVolume) {
  const double v0 = signed_volume(noisy_sphere());
  const double laplacian_loss = 1 - volume_after(SmoothingMethod::laplacian, 30) / v0;
  const double cotangent_loss = 1 - volume_after(SmoothingMethod::cotangent, 30) / v0;
  const double taubin_loss = std::abs(1 - volume_after(SmoothingMethod::taubin, 30) / v0);
  RecordProperty("laplacian_volume_loss", std::to_string(laplacian_loss));
  RecordProperty("cotangent_volume_loss", std::to_string(cotangent_loss));
  RecordProperty("taubin_volume_loss", std::to_string(taubin_loss));
  EXPECT_GT(laplacian_loss, 0.05);
  EXPECT_GT(cotangent_loss, 0.05);
  EXPECT_LT(taubin_loss, 0.1 * laplacian_loss);
}

TEST(Smoothing, EveryMethodRemovesNoise) {
  const double before = roughness(noisy_sphere());
  for (SmoothingMethod m : {SmoothingMethod::laplacian, SmoothingMethod::cotangent, SmoothingMethod::taubin}) {
    PolyMesh mesh = noisy_sphere();
    int calls = 0;
    smooth(mesh, {m, 10}, [&](int step) { calls = step; });
    EXPECT_EQ(calls, 10);
    EXPECT_LT(roughness(mesh), 0.2 * before);
  }
}

TEST(Smoothing, TheNotesUniformStepWithLambdaOneIsTheNeighbourAverage) {
  PolyMesh grid = make_grid(2, 2);
  grid.positions[4].y = 1;  // the center vertex, neighbours at y = 0
  smooth(grid, {SmoothingMethod::laplacian, 1, 1.0});
  EXPECT_NEAR(grid.positions[4].y, 0, 1e-15);
  EXPECT_EQ(grid.positions[0], Vec3(-1, 0, -1));  // boundary vertices stay
}

// Coordinates near 1e308 (finite, as the readers accept them): the notes' step is the neighbour average, not inf or
// NaN (differences and sums of such coordinates overflow); every method keeps them finite, or refuses them.
TEST(Smoothing, HugeCoordinatesStayFinite) {
  PolyMesh grid = make_grid(2, 2);
  grid.positions[4].y = 1;
  for (Vec3& p : grid.positions) p *= 1e308;
  PolyMesh average = grid;
  smooth(average, {SmoothingMethod::laplacian, 1, 1.0});
  EXPECT_EQ(average.positions[4], Vec3(0, 0, 0));  // the mean of (+-1e308, 0, 0) and (0, 0, +-1e308)
  for (SmoothingMethod m : {SmoothingMethod::laplacian, SmoothingMethod::cotangent, SmoothingMethod::taubin}) {
    PolyMesh mesh = grid;
    smooth(mesh, {.method = m, .iterations = 5, .fix_boundary = false});
    for (const Vec3& p : mesh.positions)
      EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << int(m);
  }
  // A checkerboard of heights +-1.7e308 (every neighbour at -y): Taubin's pair of steps with lambda 0.1, mu -0.9
  // multiplies y by (1 - 2 lambda)(1 - 2 mu) = 2.24, past DBL_MAX: refused, and the mesh is left as it was.
  PolyMesh largest = make_grid(2, 2);
  for (size_t v = 0; v < largest.vertex_count(); ++v) largest.positions[v].y = v % 2 ? 1.7e308 : -1.7e308;
  const PolyMesh before = largest;
  EXPECT_THROW(smooth(largest, {SmoothingMethod::taubin, 1, 0.1, -0.9, false}), InvalidInput);
  EXPECT_EQ(largest.positions, before.positions);
}

TEST(Smoothing, RejectsBadParameters) {
  PolyMesh m = make_cube();
  EXPECT_THROW(smooth(m, {SmoothingMethod::laplacian, -1}), InvalidInput);
  EXPECT_THROW(smooth(m, {SmoothingMethod::laplacian, 1, 0.0}), InvalidInput);
  EXPECT_THROW(smooth(m, {SmoothingMethod::taubin, 1, 0.5, -0.4}), InvalidInput);
}

// A bumpy plane smoothed flat: its normals must follow the new shape (they pointed along the bumps before).
TEST(Smoothing, NormalsFollowTheSmoothedShape) {
  PolyMesh m;
  const int n = 6;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.positions.emplace_back(x, y, (x + y) % 2 == 0 ? 0.3 : -0.3);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const auto v = uint32_t(y * (n + 1) + x);
      m.add_face({v, v + 1, v + uint32_t(n) + 2, v + uint32_t(n) + 1});
    }
  m.normals.assign(m.vertex_count(), Vec3(1, 0, 0));
  smooth(m, {.method = SmoothingMethod::laplacian, .iterations = 50, .lambda = 0.5});
  ASSERT_EQ(m.normals.size(), m.vertex_count());
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    if (std::abs(m.positions[v].x - n / 2.0) > 1 || std::abs(m.positions[v].y - n / 2.0) > 1) continue;
    EXPECT_GT(std::abs(m.normals[v].z), 0.99) << v;  // the interior is flat after smoothing: normals along z
  }
}

}  // namespace
}  // namespace tessera
