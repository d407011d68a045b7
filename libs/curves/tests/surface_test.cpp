#include "tessera/curves/surface.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

double triangle_area(const TriMesh& m, size_t t) {
  const Vec3& a = m.positions[m.indices[3 * t]];
  const Vec3& b = m.positions[m.indices[3 * t + 1]];
  const Vec3& c = m.positions[m.indices[3 * t + 2]];
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

// Every vertex normal is unit, and every non-degenerate triangle's winding agrees with its vertices' normals.
void expect_consistent_normals(const TriMesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (const Vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-9);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3& a = m.positions[m.indices[3 * t]];
    const Vec3 g = glm::cross(m.positions[m.indices[3 * t + 1]] - a, m.positions[m.indices[3 * t + 2]] - a);
    if (glm::length(g) < 1e-12) continue;
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(g, m.normals[m.indices[3 * t + size_t(k)]]), 0) << "triangle " << t;
  }
}

// The same surface without its analytic normal, so that finite differences are used.
ParametricSurface without_normal(ParametricSurface s) {
  s.normal = nullptr;
  return s;
}

TEST(Surface, ParallelogramOfTheNotes) {
  const Vec3 p1(1, 1, 0), p2(4, 1, 0), p3(2, 3, 1);
  const auto s = parallelogram(p1, p2, p3);
  EXPECT_EQ(s.position(0, 0), p1);
  EXPECT_EQ(s.position(1, 0), p2);
  EXPECT_EQ(s.position(0, 1), p3);
  EXPECT_EQ(s.position(1, 1), p2 + p3 - p1);
  const TriMesh m = tessellate(s, 4, 3);
  EXPECT_EQ(m.vertex_count(), 20u);
  EXPECT_EQ(m.triangle_count(), 24u);
  double area = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) area += triangle_area(m, t);
  EXPECT_NEAR(area, glm::length(glm::cross(p2 - p1, p3 - p1)), 1e-12);
  expect_consistent_normals(m);
  EXPECT_THROW(parallelogram(p1, p2, p1 + 2.0 * (p2 - p1)), InvalidInput);
}

TEST(Surface, CylinderAndSphereOfTheNotes) {
  const auto c = cylinder(2, 3);
  for (double s = 0; s < 6.3; s += 0.5)
    for (double t = 0; t <= 1; t += 0.25) {
      const Vec3 p = c.position(s, t);
      EXPECT_NEAR(std::hypot(p.x, p.y), 2.0, 1e-12);
      EXPECT_NEAR(p.z, 3 * t, 1e-12);
    }
  const auto sp = sphere(2);
  EXPECT_LT(glm::length(sp.position(1.0, kPi / 2) - Vec3(0, 0, 2)), 1e-12);  // t = π/2 is the north pole
  EXPECT_LT(glm::length(sp.position(0.0, 0.0) - Vec3(2, 0, 0)), 1e-12);      // t = 0 the equator
  const TriMesh m = tessellate(sp, 64, 32);
  for (const Vec3& p : m.positions) EXPECT_NEAR(glm::length(p), 2.0, 1e-12);
  double area = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) area += triangle_area(m, t);
  EXPECT_NEAR(area, 16 * kPi, 0.01 * 16 * kPi);
  expect_consistent_normals(m);
  expect_consistent_normals(tessellate(c, 16, 4));
  for (const Vec2& uv : m.uvs) {
    EXPECT_GE(std::min(uv.x, uv.y), 0.0);
    EXPECT_LE(std::max(uv.x, uv.y), 1.0);
  }
}

TEST(Surface, FiniteDifferenceNormalsMatchAnalytic) {
  for (const auto& s : {cylinder(1.5, 2), sphere(1.0), parallelogram(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 1))}) {
    const auto fd = without_normal(s);
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        const double a = s.s.lo + (s.s.hi - s.s.lo) * i / 8, b = s.t.lo + (s.t.hi - s.t.lo) * j / 8;
        const Vec3 n = surface_normal(fd, a, b);
        EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
        EXPECT_GT(glm::dot(n, s.normal(a, b)), 1 - 1e-6) << i << " " << j;
      }
  }
}

TEST(Surface, SpherePolesGetTheLimitNormal) {
  // At the poles ∂P/∂s vanishes; the finite-difference normal falls back to a nearby regular point.
  const auto fd = without_normal(sphere(1.0));
  for (const double s : {0.0, 1.0, 2 * kPi}) {
    EXPECT_GT(surface_normal(fd, s, kPi / 2).z, 0.9999);
    EXPECT_LT(surface_normal(fd, s, -kPi / 2).z, -0.9999);
  }
  expect_consistent_normals(tessellate(fd, 24, 12));
}

TEST(Surface, RejectsBadInput) {
  EXPECT_THROW(tessellate(sphere(1), 0, 4), InvalidInput);
  EXPECT_THROW(tessellate(ParametricSurface{}, 4, 4), InvalidInput);
  EXPECT_THROW(cylinder(-1, 1), InvalidInput);
  EXPECT_THROW(sphere(0), InvalidInput);
}

}  // namespace
}  // namespace tessera
