#include "tessera/mesh/normals.hpp"

#include <gtest/gtest.h>

#include "tessera/mesh/primitives.hpp"

namespace tessera {
namespace {

TEST(Normals, FaceNormalIsTheNormalizedCrossOfTheFirstTwoEdges) {
  PolyMesh tri;
  tri.positions = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0)};
  tri.add_face({0, 1, 2});
  EXPECT_EQ(face_normal(tri, 0), Vec3(0, 0, 1));
  EXPECT_EQ(face_area_vector(tri, 0), Vec3(0, 0, 3));
  tri.positions[2] = Vec3(4, 0, 0);  // degenerate
  EXPECT_EQ(face_normal(tri, 0), Vec3(0.0));
}

TEST(Normals, SphereVertexNormalsPointOutward) {
  const PolyMesh sphere = make_quad_sphere(8);
  for (NormalWeighting w : {NormalWeighting::Area, NormalWeighting::Angle}) {
    const auto n = vertex_normals(sphere, w);
    for (size_t v = 0; v < n.size(); ++v) EXPECT_GT(glm::dot(n[v], sphere.positions[v]), 0.99);
  }
}

TEST(Normals, AngleWeightingIgnoresHowAFaceIsSplit) {
  // A box corner where the top face is split into two triangles: area weights are unchanged by the split but angle
  // weights see the top face once (90 degrees in total), so the angle-weighted corner normal stays on the diagonal.
  PolyMesh corner;
  corner.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                      Vec3(1, 0, 1), Vec3(1, 1, 0), Vec3(0, 1, 1)};
  corner.add_face({0, 2, 5, 1});  // z = 0 plane, normal -z
  corner.add_face({0, 1, 4, 3});  // y = 0 plane, normal -y
  corner.add_face({0, 3, 6});     // x = 0 plane, normal -x, as two triangles
  corner.add_face({0, 6, 2});
  const Vec3 angle = vertex_normals(corner, NormalWeighting::Angle)[0];
  EXPECT_NEAR(angle.x, -1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(angle.y, -1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(angle.z, -1 / std::sqrt(3.0), 1e-12);
  const Vec3 area = vertex_normals(corner, NormalWeighting::Area)[0];
  EXPECT_NEAR(area.x, area.y, 1e-12);  // both x = 0 triangles have area 1/2: same total as the quads
  PolyMesh copy = corner;
  compute_vertex_normals(copy, NormalWeighting::Angle);
  EXPECT_EQ(copy.normals.size(), copy.vertex_count());
}

}  // namespace
}  // namespace tessera
