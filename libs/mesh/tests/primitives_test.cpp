#include "tessera/mesh/primitives.hpp"

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "tessera/core/error.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/normals.hpp"

namespace tessera {
namespace {

/// Counts directed edges; a closed, consistently oriented mesh has every directed edge once and its reverse once.
struct EdgeCheck {
  bool closed_and_oriented = true;
  size_t edges = 0;
};

EdgeCheck check_edges(const PolyMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (size_t i = 0; i < face.size(); ++i) ++directed[{face[i], face[(i + 1) % face.size()]}];
  }
  EdgeCheck check;
  for (const auto& [e, n] : directed) {
    const auto reverse = directed.find({e.second, e.first});
    if (n != 1 || reverse == directed.end() || reverse->second != 1) check.closed_and_oriented = false;
  }
  check.edges = directed.size() / 2;
  return check;
}

struct Expected {
  const char* name;
  PolyMesh mesh;
  size_t vertices, faces, edges;
  int euler;
  double volume;  // 0 = not checked beyond > 0
};

TEST(Primitives, ClosedSolidsHaveCountsEulerCharacteristicAndPositiveVolume) {
  const double s3 = std::sqrt(3.0);
  const Expected cases[] = {
      {"tetrahedron", make_tetrahedron(), 4, 4, 6, 2, 8.0 / (9.0 * s3)},
      {"cube", make_cube(), 8, 6, 12, 2, 8.0 / (3.0 * s3)},
      {"octahedron", make_octahedron(), 6, 8, 12, 2, 4.0 / 3.0},
      {"dodecahedron", make_dodecahedron(), 20, 12, 30, 2, 2.785163863},
      {"icosahedron", make_icosahedron(), 12, 20, 30, 2, 2.536150710},
      {"box", make_box(), 8, 6, 12, 2, 8.0},
      {"uv sphere", make_uv_sphere(16, 8), 2 + 16 * 7, 16 * 8, 16 * 7 + 16 * 8, 2, 0},
      {"quad sphere", make_quad_sphere(4), 6 * 16 + 2, 6 * 16, 12 * 16, 2, 0},
      {"cylinder", make_cylinder(12), 24, 14, 36, 2, 0},
      {"cone", make_cone(12), 13, 13, 24, 2, 0},
      {"torus", make_torus(1.0, 0.25, 24, 12), 24 * 12, 24 * 12, 2 * 24 * 12, 0, 0},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    EXPECT_EQ(c.mesh.vertex_count(), c.vertices);
    EXPECT_EQ(c.mesh.face_count(), c.faces);
    const EdgeCheck edges = check_edges(c.mesh);
    EXPECT_TRUE(edges.closed_and_oriented);
    EXPECT_EQ(edges.edges, c.edges);
    EXPECT_EQ(int(c.vertices) - int(edges.edges) + int(c.faces), c.euler);
    const double volume = signed_volume(c.mesh);
    EXPECT_GT(volume, 0);
    if (c.volume > 0) {
      EXPECT_NEAR(volume, c.volume, 1e-8);
    }
    // Every face normal points away from the origin for these star-shaped solids (the torus excepted).
    if (c.euler == 2) {
      for (size_t f = 0; f < c.mesh.face_count(); ++f)
        EXPECT_GT(glm::dot(face_normal(c.mesh, f), c.mesh.positions[c.mesh.face(f)[0]]), 0) << "face " << f;
    }
  }
}

TEST(Primitives, PlatonicSolidsHaveUnitCircumradiusAndRegularFaces) {
  for (const PolyMesh& mesh :
       {make_tetrahedron(), make_cube(), make_octahedron(), make_dodecahedron(), make_icosahedron()}) {
    for (const Vec3& p : mesh.positions) EXPECT_NEAR(glm::length(p), 1.0, 1e-12);
    const auto face0 = mesh.face(0);
    const double edge = glm::distance(mesh.positions[face0[0]], mesh.positions[face0[1]]);
    for (size_t f = 0; f < mesh.face_count(); ++f) {
      const auto face = mesh.face(f);
      EXPECT_EQ(face.size(), face0.size());
      for (size_t i = 0; i < face.size(); ++i)
        EXPECT_NEAR(glm::distance(mesh.positions[face[i]], mesh.positions[face[(i + 1) % face.size()]]), edge, 1e-12);
    }
  }
}

TEST(Primitives, SphereVolumesApproachFourThirdsPi) {
  const double ball = 4.0 / 3.0 * kPi;
  EXPECT_NEAR(signed_volume(make_uv_sphere(128, 64)), ball, 0.01 * ball);
  EXPECT_NEAR(signed_volume(make_quad_sphere(32)), ball, 0.01 * ball);
  EXPECT_NEAR(signed_volume(make_torus(1.0, 0.25, 128, 64)), 2 * kPi * kPi * 1.0 * 0.25 * 0.25, 0.01);
  EXPECT_NEAR(signed_volume(make_cylinder(256)), 2 * kPi, 0.01);
  EXPECT_NEAR(signed_volume(make_cone(256)), 2 * kPi / 3, 0.01);
}

TEST(Primitives, AttributesAreParallelArrays) {
  const PolyMesh uv = make_uv_sphere(8, 4);
  EXPECT_EQ(uv.normals.size(), uv.vertex_count());
  EXPECT_EQ(uv.corner_uvs.size(), uv.face_vertices.size());
  EXPECT_EQ(uv.face_size(0), 3u);  // a pole fan triangle
  const PolyMesh torus = make_torus(2, 0.5, 6, 5);
  EXPECT_EQ(torus.corner_uvs.size(), torus.face_vertices.size());
  for (size_t v = 0; v < torus.vertex_count(); ++v) EXPECT_NEAR(glm::length(torus.normals[v]), 1.0, 1e-12);
  const PolyMesh grid = make_grid(3, 2);
  EXPECT_EQ(grid.vertex_count(), 12u);
  EXPECT_EQ(grid.face_count(), 6u);
  EXPECT_EQ(grid.uvs.size(), 12u);
  for (size_t f = 0; f < grid.face_count(); ++f) EXPECT_NEAR(face_normal(grid, f).y, 1.0, 1e-12);
  const EdgeCheck open = check_edges(make_cylinder(8, false));
  EXPECT_FALSE(open.closed_and_oriented);
}

TEST(Primitives, RejectBadCounts) {
  EXPECT_THROW(make_uv_sphere(2, 4), InvalidInput);
  EXPECT_THROW(make_uv_sphere(8, 1), InvalidInput);
  EXPECT_THROW(make_quad_sphere(0), InvalidInput);
  EXPECT_THROW(make_cylinder(2), InvalidInput);
  EXPECT_THROW(make_cone(-1), InvalidInput);
  EXPECT_THROW(make_torus(1, 2, 8, 8), InvalidInput);
  EXPECT_THROW(make_grid(0, 3), InvalidInput);
}

}  // namespace
}  // namespace tessera
