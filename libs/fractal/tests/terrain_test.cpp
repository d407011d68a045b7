#include "tessera/fractal/terrain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

TEST(Terrain, OneDimensionalHalvingRange) {
  TerrainOptions options;
  options.depth = 10;
  const auto h = midpoint_displacement_1d(options);
  ASSERT_EQ(h.size(), 1025u);
  EXPECT_EQ(h.front(), 0.0);
  EXPECT_EQ(h.back(), 0.0);
  // The first midpoint moves by at most 1/4 (range 1/2); every point stays within the sum of the half-ranges.
  EXPECT_LE(std::abs(h[512]), 0.25);
  for (double v : h) EXPECT_LE(std::abs(v), 0.5);
  // A point of level k (odd multiple of 2^(10-1-k)) sits within r_k / 2 of the mean of its two parents.
  for (int k = 0; k < 10; ++k) {
    const size_t step = size_t(1024) >> k;
    const double r = 0.5 * std::pow(0.5, k);
    for (size_t i = step / 2; i < 1024; i += step)
      ASSERT_LE(std::abs(h[i] - 0.5 * (h[i - step / 2] + h[i + step / 2])), r / 2 + 1e-15);
  }
  EXPECT_EQ(midpoint_displacement_1d(options), h);  // seeded: reproducible
  options.seed = 2;
  EXPECT_NE(midpoint_displacement_1d(options), h);
}

TEST(Terrain, RoughnessControlsTheFineDetail) {
  // Mean squared second difference at the finest level grows with the roughness.
  const auto detail = [](double roughness) {
    TerrainOptions options;
    options.depth = 12;
    options.roughness = roughness;
    const auto h = midpoint_displacement_1d(options);
    double s = 0;
    for (size_t i = 1; i + 1 < h.size(); ++i) s += std::pow(h[i + 1] - 2 * h[i] + h[i - 1], 2);
    return s;
  };
  EXPECT_LT(detail(0.4), detail(0.5));
  EXPECT_LT(detail(0.5), detail(0.7));
}

TEST(Terrain, TriangleMountainHasNoCracks) {
  for (int depth = 0; depth <= 5; ++depth) {
    TerrainOptions options;
    options.depth = depth;
    const PolyMesh mesh = triangle_mountain(options);
    const size_t side = size_t(1) << depth;
    EXPECT_EQ(mesh.face_count(), side * side);
    EXPECT_EQ(mesh.vertex_count(), (side + 1) * (side + 2) / 2);  // shared midpoints: no duplicates
    EXPECT_EQ(mesh.colors.size(), mesh.vertex_count());
    // Every edge has one face (the boundary: 3 * 2^depth edges) or two opposite ones (interior): watertight.
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t f = 0; f < mesh.face_count(); ++f) {
      const auto face = mesh.face(f);
      for (size_t i = 0; i < 3; ++i) ++directed[{face[i], face[(i + 1) % 3]}];
    }
    size_t boundary = 0;
    for (const auto& [edge, count] : directed) {
      ASSERT_EQ(count, 1);
      if (!directed.count({edge.second, edge.first})) ++boundary;
    }
    EXPECT_EQ(boundary, 3 * side);
    // Faces point up (counterclockwise seen from above).
    for (size_t f = 0; f < mesh.face_count(); ++f) {
      const auto face = mesh.face(f);
      const Vec3 n = glm::cross(mesh.positions[face[1]] - mesh.positions[face[0]],
                                mesh.positions[face[2]] - mesh.positions[face[0]]);
      ASSERT_GT(n.y, 0);
    }
  }
}

TEST(Terrain, DiamondSquareIsSeededAndBounded) {
  TerrainOptions options;
  options.depth = 7;
  const Image<float> a = diamond_square(options);
  ASSERT_EQ(a.width(), 129);
  EXPECT_EQ(a(0, 0), 0.0f);
  EXPECT_EQ(a(128, 128), 0.0f);
  const Image<float> b = diamond_square(options);
  EXPECT_TRUE(std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin()));
  for (float v : a.pixels()) EXPECT_LE(std::abs(v), 1.0f);  // bounded by the sum of the half-ranges
  float lo = 0, hi = 0;
  for (float v : a.pixels()) lo = std::min(lo, v), hi = std::max(hi, v);
  EXPECT_GT(hi - lo, 0.05f);
}

TEST(Terrain, HeightMapMeshAndPicture) {
  Image<float> h(3, 2, 0.0f);
  h(1, 1) = 2.0f;
  const PolyMesh mesh = height_map_mesh(h, 0.5);
  EXPECT_EQ(mesh.vertex_count(), 6u);
  EXPECT_EQ(mesh.face_count(), 4u);
  EXPECT_EQ(mesh.positions[4], Vec3(0.5, 1.0, 1.0));
  const ImageRGB picture = height_map_picture(h);
  EXPECT_EQ(picture(1, 1), terrain_color(1.0));
  EXPECT_EQ(picture(0, 0), terrain_color(0.0));
  EXPECT_THROW(height_map_mesh(Image<float>(1, 5)), InvalidInput);
}

TEST(Terrain, RejectsBadOptions) {
  TerrainOptions options;
  options.roughness = 1.0;
  EXPECT_THROW(midpoint_displacement_1d(options), InvalidInput);
  options.roughness = 0.5;
  options.depth = kMaxTerrainDepthTriangles + 1;
  EXPECT_THROW(triangle_mountain(options), InvalidInput);
  options.depth = -1;
  EXPECT_THROW(diamond_square(options), InvalidInput);
}

}  // namespace
}  // namespace tessera
