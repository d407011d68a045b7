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
  for (NormalWeighting w : {NormalWeighting::area, NormalWeighting::angle}) {
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
  const Vec3 angle = vertex_normals(corner, NormalWeighting::angle)[0];
  EXPECT_NEAR(angle.x, -1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(angle.y, -1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(angle.z, -1 / std::sqrt(3.0), 1e-12);
  const Vec3 area = vertex_normals(corner, NormalWeighting::area)[0];
  EXPECT_NEAR(area.x, area.y, 1e-12);  // both x = 0 triangles have area 1/2: same total as the quads
  PolyMesh copy = corner;
  compute_vertex_normals(copy, NormalWeighting::angle);
  EXPECT_EQ(copy.normals.size(), copy.vertex_count());
}

// Issue 24, class 2: the cross products of coordinates beyond about 1e154 overflowed (and below 1e-154 underflowed),
// so a mesh at 1e300 or 1e-300 got zero normals. Faces outside 2^+-128 are computed on points scaled by a power of two:
// the cube's normals at any scale are the analytic ones, (+-1, +-1, +-1) / sqrt(3) at its corners (three equal faces
// at right angles, for either weighting) and the axes for its faces; so are a tetrahedron's face normals, minus its
// vertex directions (the opposite face's normal points away from the vertex).
TEST(Normals, HugeAndTinyCoordinatesGiveTheUnitMeshsNormals) {
  for (const double scale : {1.0, 1e300, 1e-300, 1e200, 1e-200, 1e154, 1e-154, 0x1p1000, 0x1p-1000}) {
    SCOPED_TRACE(scale);
    PolyMesh cube = make_cube(), tetra = make_tetrahedron();
    for (Vec3& p : cube.positions) p *= scale;
    for (Vec3& p : tetra.positions) p *= scale;
    for (NormalWeighting w : {NormalWeighting::area, NormalWeighting::angle}) {
      const auto n = vertex_normals(cube, w);
      for (size_t v = 0; v < n.size(); ++v) {
        const Vec3 analytic = glm::sign(cube.positions[v]) / std::sqrt(3.0);
        EXPECT_NEAR(glm::length(n[v] - analytic), 0, 1e-15) << v;
      }
    }
    for (size_t f = 0; f < cube.face_count(); ++f) {
      Vec3 centroid(0.0);
      for (uint32_t v : cube.face(f)) centroid += glm::sign(cube.positions[v]);  // on the face's axis, +-4
      EXPECT_EQ(face_normal(cube, f), centroid / 4.0) << f;
    }
    for (size_t f = 0; f < tetra.face_count(); ++f) {
      const auto face = tetra.face(f);
      const uint32_t opposite = uint32_t(0 + 1 + 2 + 3 - face[0] - face[1] - face[2]);
      EXPECT_NEAR(glm::length(face_normal(tetra, f) + glm::normalize(tetra.positions[opposite] / scale)), 0, 1e-15);
    }
  }
  // Power-of-two scales are exact: the normals are those of the unit cube, bit for bit.
  PolyMesh huge = make_cube();
  for (Vec3& p : huge.positions) p *= 0x1p1000;
  EXPECT_EQ(vertex_normals(huge), vertex_normals(make_cube()));
  PolyMesh large = make_cube();
  for (Vec3& p : large.positions) p *= 0x1p500;  // areas near 2^1000: still doubles, though the cross products were not
  for (size_t f = 0; f < large.face_count(); ++f)
    EXPECT_EQ(face_area_vector(large, f), 0x1p1000 * face_area_vector(make_cube(), f)) << f;
}

}  // namespace
}  // namespace tessera
