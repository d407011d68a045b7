#include "tessera/mesh/triangulate.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/topology.hpp"

namespace tessera {
namespace {

double triangle_area_z(const std::vector<Vec3>& p, const std::array<uint32_t, 3>& t) {
  return 0.5 * glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]).z;
}

TEST(Triangulate, ConvexFacesGetTheNotesFan) {
  std::vector<Vec3> hexagon;
  for (int i = 0; i < 6; ++i) hexagon.emplace_back(std::cos(i * kPi / 3), std::sin(i * kPi / 3), 0);
  EXPECT_TRUE(is_convex_polygon(hexagon));
  const auto tris = triangulate_polygon(hexagon);
  ASSERT_EQ(tris.size(), 4u);  // s - 2 triangles, s - 3 diagonals from corner 0
  for (size_t i = 0; i < tris.size(); ++i)
    EXPECT_EQ(tris[i], (std::array<uint32_t, 3>{0, uint32_t(i + 1), uint32_t(i + 2)}));
}

TEST(Triangulate, ConcaveFacesAreEarClippedInTheirPlane) {
  // An L shape, tilted out of the xy plane: a fan from corner 0 would cover the notch.
  const Mat3 tilt = Mat3(glm::rotate(glm::dmat4(1.0), 0.7, Vec3(1, 1, 0)));
  std::vector<Vec3> l{Vec3(2, 2, 0), Vec3(0, 2, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(2, 1, 0)};
  EXPECT_FALSE(is_convex_polygon(l));
  const auto flat = triangulate_polygon(l);
  ASSERT_EQ(flat.size(), 4u);
  double area = 0;
  for (const auto& t : flat) {
    EXPECT_GT(triangle_area_z(l, t), 0);  // orientation kept, no flipped triangle
    area += triangle_area_z(l, t);
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
  for (Vec3& p : l) p = tilt * p;
  EXPECT_EQ(triangulate_polygon(l), flat);
}

TEST(Triangulate, MeshesKeepAreaTopologyAndCornerData) {
  const PolyMesh sphere = make_uv_sphere(8, 5);
  const PolyMesh tris = triangulate(sphere);
  EXPECT_TRUE(tris.is_triangle_mesh());
  EXPECT_EQ(tris.face_count(), 8u * 2 + 8u * 3 * 2);
  EXPECT_EQ(tris.corner_uvs.size(), tris.face_vertices.size());
  EXPECT_NEAR(surface_area(tris), surface_area(sphere), 1e-9 * surface_area(sphere));
  EXPECT_EQ(analyze_topology(tris).euler, 2);
  const PolyMesh dodeca = triangulate(make_dodecahedron());
  EXPECT_EQ(dodeca.face_count(), 36u);
  for (size_t f = 0; f < dodeca.face_count(); ++f)
    EXPECT_GT(glm::dot(face_normal(dodeca, f), dodeca.positions[dodeca.face(f)[0]]), 0);
}

}  // namespace
}  // namespace tessera
