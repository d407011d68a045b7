#include "tessera/curves/bezier_patch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "tessera/core/error.hpp"
#include "tessera/curves/bpt.hpp"

namespace tessera {
namespace {

BezierPatch random_patch(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  BezierPatch p;
  for (Vec3& q : p.points) q = Vec3(u(rng), u(rng), u(rng));
  return p;
}

// A smooth bump over the unit square: a height field, normals up (+z) with du = +x, dv = +y.
BezierPatch bump() {
  BezierPatch p;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      p.at(i, j) = Vec3(i / 3.0, j / 3.0, (i == 1 || i == 2) && (j == 1 || j == 2) ? 0.5 : 0.0);
  return p;
}

// A dome like the teapot's lid: row 0 collapsed to the apex, rows 1..3 on circles of growing radius (a quarter turn
// in v), so ∂S/∂v = 0 along u = 0. With row 1 collapsed too, ∂S/∂u vanishes there as well and the apex is the tip of
// a cone whose generators run along P_2j - P_00 = (arc_j, -0.4).
BezierPatch dome(bool also_row1) {
  const double k = 0.5523;  // quarter-circle handle length
  const std::array<Vec2, 4> arc{Vec2(1, 0), Vec2(1, k), Vec2(k, 1), Vec2(0, 1)};
  const std::array<double, 4> radius{0, also_row1 ? 0 : 0.6, 1.0, 1.0};
  const std::array<double, 4> height{1, 1, 0.6, 0};
  BezierPatch p;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      p.at(i, j) = Vec3(radius[size_t(i)] * arc[size_t(j)].x, radius[size_t(i)] * arc[size_t(j)].y, height[size_t(i)]);
  return p;
}

TEST(BezierPatch, FourStepsAgreeWithTensorProduct) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const BezierPatch p = random_patch(rng);
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j <= 10; ++j) {
        const double u = i / 10.0, v = j / 10.0;
        const Vec3 a = evaluate_four_curves(p, u, v), b = evaluate_bernstein(p, u, v);
        EXPECT_LT(glm::length(a - b), 1e-12);
        // A third, independent way: de Casteljau on the columns, then on the resulting row.
        Bezier3 column_points;
        for (int c = 0; c < 4; ++c) {
          const Bezier3 column = cubic(p.at(0, c), p.at(1, c), p.at(2, c), p.at(3, c));
          column_points.points.push_back(evaluate_de_casteljau(column, u));
        }
        EXPECT_LT(glm::length(evaluate_de_casteljau(column_points, v) - b), 1e-12);
        EXPECT_LT(glm::length(evaluate_with_partials(p, u, v).position - b), 1e-12);
      }
  }
}

TEST(BezierPatch, CornersInterpolateAndEdgesAreRowCurves) {
  std::mt19937 rng(2);
  const BezierPatch p = random_patch(rng);
  EXPECT_EQ(evaluate_bernstein(p, 0, 0), p.at(0, 0));
  EXPECT_EQ(evaluate_bernstein(p, 1, 1), p.at(3, 3));
  for (double v = 0; v <= 1; v += 0.125)
    EXPECT_LT(glm::length(evaluate_bernstein(p, 0, v) - evaluate_de_casteljau(p.row(0), v)), 1e-15);
}

TEST(BezierPatch, PartialsMatchFiniteDifferences) {
  std::mt19937 rng(4);
  const double h = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const BezierPatch p = random_patch(rng);
    for (const double u : {0.1, 0.5, 0.8})
      for (const double v : {0.2, 0.6, 0.95}) {
        const PatchSample s = evaluate_with_partials(p, u, v);
        const Vec3 du = (evaluate_bernstein(p, u + h, v) - evaluate_bernstein(p, u - h, v)) / (2 * h);
        const Vec3 dv = (evaluate_bernstein(p, u, v + h) - evaluate_bernstein(p, u, v - h)) / (2 * h);
        EXPECT_LT(glm::length(s.du - du), 1e-7);
        EXPECT_LT(glm::length(s.dv - dv), 1e-7);
      }
  }
  // At the corners the partials are 3 (P_10 - P_00) and 3 (P_01 - P_00), as for curves.
  const BezierPatch b = bump();
  const PatchSample corner = evaluate_with_partials(b, 0, 0);
  EXPECT_LT(glm::length(corner.du - 3.0 * (b.at(1, 0) - b.at(0, 0))), 1e-15);
  EXPECT_LT(glm::length(corner.dv - 3.0 * (b.at(0, 1) - b.at(0, 0))), 1e-15);
  EXPECT_GT(patch_normal(b, 0.5, 0.5).z, 0.999);
}

TEST(BezierPatch, CollapsedRowHasFiniteUnitNormals) {
  for (const bool also_row1 : {false, true}) {
    const BezierPatch p = dome(also_row1);
    EXPECT_EQ(glm::length(evaluate_with_partials(p, 0, 0.3).dv), 0.0);  // exactly degenerate
    for (int j = 0; j <= 8; ++j) {
      const double v = j / 8.0;
      const Vec3 n = patch_normal(p, 0, v);
      ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
      EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
      // The limit at a smooth apex is the axis (+z, as du x dv points out of the dome); at the cone's tip the limit
      // along each generator is tilted by atan(0.4) from the axis.
      EXPECT_NEAR(n.z, also_row1 ? 1 / std::sqrt(1.16) : 1.0, 0.01) << "v " << v;
      EXPECT_GT(glm::dot(n, patch_normal(p, 0.05, v)), 0.9) << "v " << v;
    }
  }
}

TEST(BezierPatch, UniformTessellationCountsAndNormals) {
  const std::vector<BezierPatch> patches{bump(), dome(false), dome(true)};
  for (const int n : {1, 4, 10}) {
    const TriMesh m = tessellate(patches, PatchTessellation{.steps = n});
    EXPECT_EQ(m.vertex_count(), 3u * size_t(n + 1) * size_t(n + 1));
    EXPECT_EQ(m.triangle_count(), 3u * 2u * size_t(n) * size_t(n));
    ASSERT_EQ(m.normals.size(), m.vertex_count());
    ASSERT_EQ(m.uvs.size(), m.vertex_count());
    for (const Vec3& normal : m.normals) EXPECT_NEAR(glm::length(normal), 1.0, 1e-9);
    for (const uint32_t index : m.indices) EXPECT_LT(index, m.vertex_count());
    // Winding agrees with the normals on non-degenerate triangles.
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const Vec3& a = m.positions[m.indices[3 * t]];
      const Vec3 g = glm::cross(m.positions[m.indices[3 * t + 1]] - a, m.positions[m.indices[3 * t + 2]] - a);
      if (glm::length(g) > 1e-9) {
        EXPECT_GT(glm::dot(g, m.normals[m.indices[3 * t]]), 0);
      }
    }
  }
  const TriMesh flipped = tessellate(patches, PatchTessellation{.steps = 2, .orientation = PatchOrientation::flipped});
  const TriMesh plain = tessellate(patches, PatchTessellation{.steps = 2});
  EXPECT_EQ(flipped.normals[5], -plain.normals[5]);
  EXPECT_EQ(flipped.indices[1], plain.indices[2]);
  EXPECT_THROW(tessellate(patches, PatchTessellation{.steps = 0}), InvalidInput);
}

TEST(BezierPatch, AdaptiveTessellationMeetsTolerance) {
  // A flat bilinear patch needs one step; a curved one needs more, and the triangles stay within the tolerance.
  BezierPatch flat;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) flat.at(i, j) = Vec3(i, j, 0);
  EXPECT_EQ(flatness_steps(flat, 1e-3), 1);
  const BezierPatch b = bump();
  for (const double tolerance : {0.05, 0.01, 0.001}) {
    const int n = flatness_steps(b, tolerance);
    const TriMesh m = tessellate(std::vector<BezierPatch>{b}, PatchTessellation{.steps = 256, .tolerance = tolerance});
    ASSERT_EQ(m.vertex_count(), size_t(n + 1) * size_t(n + 1));
    // The centroid of each triangle against the surface at the centroid's (u, v).
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      Vec3 centroid(0.0);
      Vec2 uv(0.0);
      for (int k = 0; k < 3; ++k) {
        centroid += m.positions[m.indices[3 * t + size_t(k)]] / 3.0;
        uv += m.uvs[m.indices[3 * t + size_t(k)]] / 3.0;
      }
      EXPECT_LE(glm::length(evaluate_bernstein(b, uv.x, uv.y) - centroid), tolerance);
    }
  }
  EXPECT_GT(flatness_steps(b, 0.001), flatness_steps(b, 0.01));
}

TEST(BezierPatch, ControlNet) {
  const std::vector<BezierPatch> patches{bump(), dome(false)};
  const PolyMesh net = control_net(patches);
  EXPECT_EQ(net.vertex_count(), 32u);
  EXPECT_EQ(net.face_count(), 18u);
  EXPECT_EQ(net.positions[17], patches[1].points[1]);
}

TEST(BezierPatch, TeapotFromSharedDataWhenPresent) {
  // Optional: the real data set. The other tests use patches built in code.
  const char* env = std::getenv("TESSERA_SHARED_DATA");
  const std::filesystem::path path = std::filesystem::path(env ? env : TESSERA_SHARED_DATA) / "bezier/teapot.bpt";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const auto patches = read_bpt(path);
  ASSERT_EQ(patches.size(), 32u);
  const TriMesh m = tessellate(patches, PatchTessellation{.steps = 6});
  EXPECT_EQ(m.triangle_count(), 32u * 72u);
  for (const Vec3& n : m.normals) {
    ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    EXPECT_NEAR(glm::length(n), 1.0, 1e-9);
  }
  // The lid's tip (patches 21-24, u = 0) and the bottom's center (29-32) have vertical normals.
  for (const size_t p : {20u, 28u}) EXPECT_GT(std::abs(patch_normal(patches[p], 0, 0.5).z), 0.99);
  // Newell's data is wound so that du x dv points inside; Outward flips it.
  const TriMesh outward = tessellate(patches, PatchTessellation{.steps = 6, .orientation = PatchOrientation::outward});
  EXPECT_EQ(outward.normals[0], -m.normals[0]);
  EXPECT_LT(patch_normal(patches[20], 0, 0.5).z, -0.99) << "as given, the lid tip's normal points into the pot";
}

// A closed model: four dome quarters turned about z, and the same turned upside down (a rotation about x, so the
// winding stays outward). Transposing every net (P_ij <-> P_ji) swaps u and v and so turns it inside out.
std::vector<BezierPatch> closed_domes(bool transposed) {
  std::vector<BezierPatch> patches;
  BezierPatch quarter = dome(false);
  for (int q = 0; q < 4; ++q) {
    patches.push_back(quarter);
    BezierPatch lower = quarter;
    for (Vec3& p : lower.points) p = Vec3(p.x, -p.y, -p.z);
    patches.push_back(lower);
    for (Vec3& p : quarter.points) p = Vec3(-p.y, p.x, p.z);
  }
  if (transposed)
    for (BezierPatch& patch : patches) {
      const BezierPatch copy = patch;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) patch.at(j, i) = copy.at(i, j);
    }
  return patches;
}

double signed_volume(const TriMesh& m) {
  double volume = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    volume += glm::dot(m.positions[m.indices[3 * t]],
                       glm::cross(m.positions[m.indices[3 * t + 1]], m.positions[m.indices[3 * t + 2]])) /
              6;
  return volume;
}

TEST(BezierPatch, OutwardOrientationOfAClosedModel) {
  const auto outward = closed_domes(false), inward = closed_domes(true);
  const auto volume = [](const std::vector<BezierPatch>& patches, PatchOrientation orientation) {
    return signed_volume(tessellate(patches, PatchTessellation{.steps = 8, .orientation = orientation}));
  };
  // Each dome (radius 1, height 1) holds more than its inscribed cone (π/3) and less than its cylinder (π).
  EXPECT_GT(volume(outward, PatchOrientation::as_given), 2 * kPi / 3);
  EXPECT_LT(volume(outward, PatchOrientation::as_given), 2 * kPi);
  EXPECT_LT(volume(outward, PatchOrientation::flipped), 0);
  EXPECT_LT(volume(inward, PatchOrientation::as_given), 0);
  EXPECT_NEAR(volume(inward, PatchOrientation::outward), volume(outward, PatchOrientation::outward), 1e-9);
  EXPECT_GT(volume(outward, PatchOrientation::outward), 0);
}

}  // namespace
}  // namespace tessera
