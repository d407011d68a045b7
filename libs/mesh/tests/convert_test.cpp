#include "tessera/mesh/convert.hpp"

#include <gtest/gtest.h>

#include "tessera/mesh/primitives.hpp"

namespace tessera {
namespace {

TEST(Convert, SeamsSplitVerticesByTheirFaceVaryingUvs) {
  const int slices = 8, stacks = 4;
  const PolyMesh sphere = make_uv_sphere(slices, stacks);
  const TriMesh tri = to_tri_mesh(sphere);
  EXPECT_EQ(tri.triangle_count(), size_t(slices * 2 + slices * (stacks - 2) * 2));
  // Interior rings: one extra vertex per ring on the seam (u = 0 and u = 1); poles: one vertex per fan triangle.
  EXPECT_EQ(tri.vertex_count(), size_t((stacks - 1) * (slices + 1) + 2 * slices));
  EXPECT_EQ(tri.uvs.size(), tri.vertex_count());
  EXPECT_EQ(tri.normals.size(), tri.vertex_count());
  for (size_t i = 0; i < tri.indices.size(); ++i) EXPECT_LT(tri.indices[i], tri.vertex_count());
}

TEST(Convert, WithoutFaceVaryingDataTheNumberingIsKept) {
  const PolyMesh cube = make_cube();
  const TriMesh tri = to_tri_mesh(cube);
  EXPECT_EQ(tri.positions, cube.positions);
  EXPECT_EQ(tri.triangle_count(), 12u);
  const PolyMesh back = to_poly_mesh(tri);
  EXPECT_TRUE(back.is_triangle_mesh());
  EXPECT_EQ(back.face_vertices, tri.indices);
  EXPECT_EQ(back.face_count(), 12u);
}

}  // namespace
}  // namespace tessera
