// The mesh-view helpers against independent expectations: a cube's 12 edges, analytic face normals, and a framed
// sphere's projection computed from its angular radius.
#include "tessera/scene/mesh_view.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"

namespace tessera {
namespace {

TEST(MeshView, PolygonEdgesOfACubeAreItsTwelveEdges) {
  const PolyMesh cube = make_cube();  // circumradius 1: edge 2 / sqrt(3)
  const auto edges = polygon_edges(cube);
  ASSERT_EQ(edges.size(), 12u);
  std::map<uint32_t, int> valence;
  for (const auto& [a, b] : edges) {
    EXPECT_LT(a, b);
    EXPECT_NEAR(glm::distance(cube.positions[a], cube.positions[b]), 2 / std::sqrt(3.0), 1e-12);  // no diagonals
    ++valence[a];
    ++valence[b];
  }
  ASSERT_EQ(valence.size(), 8u);
  for (const auto& [v, n] : valence) EXPECT_EQ(n, 3) << v;
  // The triangulation's diagonals are not polygon edges: 6 more edges in the triangle mesh's own faces.
  const TriMesh tris = to_tri_mesh(cube);
  PolyMesh as_triangles;
  as_triangles.positions = tris.positions;
  for (size_t t = 0; t < tris.triangle_count(); ++t)
    as_triangles.add_face({tris.indices[3 * t], tris.indices[3 * t + 1], tris.indices[3 * t + 2]});
  EXPECT_EQ(polygon_edges(as_triangles).size(), 18u);
}

TEST(MeshView, SplitFacetedHasThreeCornersPerTriangleWithTheFaceNormal) {
  // A cube centered at the origin: each face's outward normal is the axis toward its center.
  const TriMesh cube = to_tri_mesh(make_cube());
  const TriMesh f = split_faceted(cube);
  ASSERT_EQ(f.positions.size(), 3 * cube.triangle_count());
  ASSERT_EQ(f.normals.size(), f.positions.size());
  ASSERT_EQ(f.indices.size(), f.positions.size());
  for (size_t t = 0; t < f.triangle_count(); ++t) {
    const Vec3 mid = (f.positions[3 * t] + f.positions[3 * t + 1] + f.positions[3 * t + 2]) / 3.0;
    // The face's axis: the coordinate of largest magnitude of any point on that face... of the face center, which is
    // the triangle's centroid projected; the centroid's largest coordinate picks the same axis.
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(mid[k]) > std::abs(mid[axis])) axis = k;
    Vec3 expected(0);
    expected[axis] = mid[axis] > 0 ? 1 : -1;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(f.indices[3 * t + k], 3 * t + k);
      EXPECT_NEAR(glm::distance(f.normals[3 * t + k], expected), 0, 1e-12) << t;
      EXPECT_EQ(f.positions[3 * t + k], cube.positions[cube.indices[3 * t + k]]);
    }
  }
  // A single counterclockwise triangle in the xy plane faces +z; its colors and uvs follow its corners.
  TriMesh one;
  one.positions = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  one.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  one.uvs = {{0, 0}, {1, 0}, {0, 1}};
  one.indices = {2, 0, 1};
  const TriMesh g = split_faceted(one);
  EXPECT_EQ(g.normals[0], Vec3(0, 0, 1));
  EXPECT_EQ(g.colors[0], Vec3(0, 0, 1));
  EXPECT_EQ(g.uvs[1], Vec2(0, 0));
}

TEST(MeshView, FrameSpherePutsTheSphereInsideTheViewWithTheMargin) {
  const double fovy = radians(40), margin = 1.1;
  const Vec3 center(1, -2, 0.5);
  const double radius = 2;
  Camera base;
  base.fovy = fovy;
  const Camera c = frame_sphere(base, center, radius, Vec3(1, 0.8, 1.6), margin);
  EXPECT_NEAR(glm::distance(c.eye, center), margin * radius / std::sin(fovy / 2), 1e-12);
  EXPECT_EQ(c.center, center);
  EXPECT_LT(c.near, glm::distance(c.eye, center) - radius);
  EXPECT_GT(c.far, glm::distance(c.eye, center) + radius);
  // The sphere's angular radius: sin(theta) = sin(fovy / 2) / margin; its silhouette reaches tan(theta) / tan(fovy / 2)
  // of the way to the edge of the view, in normalized device coordinates.
  const double theta = std::asin(std::sin(fovy / 2) / margin);
  const double reach = std::tan(theta) / std::tan(fovy / 2);
  const Mat4 m = c.projection() * c.view();
  double most = 0;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j < 400; ++j) {
      const double polar = kPi * i / 200, az = 2 * kPi * j / 400;
      const Vec3 p =
          center + radius * Vec3(std::sin(polar) * std::cos(az), std::cos(polar), std::sin(polar) * std::sin(az));
      const glm::dvec4 clip = m * glm::dvec4(p, 1);
      most = std::max({most, std::abs(clip.x / clip.w), std::abs(clip.y / clip.w)});
    }
  EXPECT_LT(most, 1.0);
  EXPECT_NEAR(most, reach, 2e-3);
  EXPECT_NEAR(sphere_fit_distance(1, radians(30), 1), 2, 1e-12);  // sin 30 = 1/2
}

}  // namespace
}  // namespace tessera
