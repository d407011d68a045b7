#include "tessera/mesh/corner_table.hpp"

#include <gtest/gtest.h>

#include "shared_data.hpp"
#include "tessera/core/error.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera {
namespace {

constexpr uint32_t kNone = CornerTable::kNoCorner;

/// The notes' O(n^2) construction, verbatim: for each corner a, for each corner b, if a.next.vert == b.prev.vert
/// and a.prev.vert == b.next.vert then O(a) = b, O(b) = a.
std::vector<uint32_t> notes_opposites(const std::vector<uint32_t>& v) {
  std::vector<uint32_t> o(v.size(), kNone);
  for (uint32_t a = 0; a < v.size(); ++a)
    for (uint32_t b = 0; b < v.size(); ++b)
      if (v[CornerTable::next(a)] == v[CornerTable::prev(b)] && v[CornerTable::prev(a)] == v[CornerTable::next(b)]) {
        o[a] = b;
        o[b] = a;
      }
  return o;
}

std::vector<PolyMesh> manifold_fixtures() {
  return {triangulate(make_icosahedron()),       triangulate(make_cube()),     triangulate(make_uv_sphere(10, 6)),
          triangulate(make_torus(1, 0.3, 9, 7)), triangulate(make_grid(4, 3)), triangulate(make_cylinder(7, false)),
          triangulate(make_dodecahedron())};
}

TEST(CornerTable, NextPrevFollowTheNotes) {
  EXPECT_EQ(CornerTable::next(0), 1u);
  EXPECT_EQ(CornerTable::next(2), 0u);
  EXPECT_EQ(CornerTable::next(5), 3u);
  EXPECT_EQ(CornerTable::prev(3), 5u);
  EXPECT_EQ(CornerTable::prev(7), 6u);
  EXPECT_EQ(CornerTable::triangle(8), 2u);
}

TEST(CornerTable, FastOppositesEqualTheNotesQuadraticLoop) {
  for (const PolyMesh& mesh : manifold_fixtures()) {
    const CornerTable table(mesh);
    EXPECT_EQ(table.opposites(), notes_opposites(mesh.face_vertices));
    EXPECT_EQ(table.unpaired_shared_edges(), 0u);
  }
}

TEST(CornerTable, FastOppositesEqualTheOracleOnSharedData) {
  TESSERA_SHARED_FILE(path, "meshes/spot/spot_control_mesh.obj");
  const PolyMesh spot = triangulate(read_mesh(path));
  EXPECT_EQ(CornerTable(spot).opposites(), notes_opposites(spot.face_vertices));
}

TEST(CornerTable, OperatorsAreTheNotesCompositions) {
  const CornerTable t(triangulate(make_icosahedron()));
  for (uint32_t c = 0; c < t.corner_count(); ++c) {
    EXPECT_EQ(t.opposite(t.opposite(c)), c);
    EXPECT_EQ(t.left(c), t.opposite(CornerTable::prev(c)));
    EXPECT_EQ(t.right(c), t.opposite(CornerTable::next(c)));
    EXPECT_EQ(t.swing(c), CornerTable::next(t.opposite(CornerTable::next(c))));
    EXPECT_EQ(t.vertex(t.swing(c)), t.vertex(c));
    EXPECT_EQ(t.unswing(t.swing(c)), c);
    // Opposite corners face the same edge from both sides.
    const uint32_t o = t.opposite(c);
    EXPECT_EQ(t.vertex(CornerTable::next(c)), t.vertex(CornerTable::prev(o)));
  }
}

TEST(CornerTable, SwingTurnsCounterclockwiseAroundTheVertex) {
  const PolyMesh ico = make_icosahedron();
  const CornerTable t(ico);
  for (uint32_t v = 0; v < t.vertex_count(); ++v) {
    const auto fan = t.corners_around(v);
    ASSERT_EQ(fan.size(), 5u);
    const auto ring = t.one_ring(v);
    ASSERT_EQ(ring.size(), 5u);
    const Vec3& p = ico.positions[v];
    for (size_t i = 0; i < 5; ++i) {
      EXPECT_EQ(t.vertex(fan[i]), v);
      const Vec3 a = ico.positions[ring[i]] - p, b = ico.positions[ring[(i + 1) % 5]] - p;
      EXPECT_GT(glm::dot(glm::cross(a, b), p), 0) << "vertex " << v;  // counterclockwise seen from outside
    }
  }
}

TEST(CornerTable, OneRingWorksAtBoundaries) {
  // A 2 x 2 grid split into triangles: the center vertex is interior, the edge midpoints are on the boundary.
  const PolyMesh grid = triangulate(make_grid(2, 2));
  const CornerTable t(grid);
  const uint32_t center = 4, edge_mid = 1, corner = 0;
  EXPECT_EQ(t.one_ring(center).size(), t.corners_around(center).size());
  const auto fan = t.corners_around(edge_mid);
  const auto ring = t.one_ring(edge_mid);
  EXPECT_EQ(ring.size(), fan.size() + 1);
  EXPECT_EQ(t.unswing(fan.front()), kNone);
  EXPECT_EQ(t.swing(fan.back()), kNone);
  EXPECT_GE(t.one_ring(corner).size(), 2u);
  size_t boundary_corners = 0;
  for (uint32_t c = 0; c < t.corner_count(); ++c) boundary_corners += t.is_boundary(c);
  EXPECT_EQ(boundary_corners, 8u);  // one per boundary edge
}

TEST(CornerTable, RejectsPolygonsAndBadIndices) {
  EXPECT_THROW(CornerTable{make_cube()}, TopologyError);
  EXPECT_THROW(CornerTable({Vec3(0.0)}, {0, 0}), TopologyError);
  EXPECT_THROW(CornerTable({Vec3(0.0)}, {0, 0, 1}), TopologyError);
}

TEST(CornerTable, NonManifoldBunnyIsClassifiedNotCrashed) {
  TESSERA_SHARED_FILE(path, "meshes/bunny/bun_zipper_res4.ply");
  const CornerTable t(read_mesh(path));
  EXPECT_EQ(t.unpaired_shared_edges(), 70u);
  size_t visited = 0;
  for (uint32_t v = 0; v < t.vertex_count(); ++v) visited += t.corners_around(v).size();
  EXPECT_LE(visited, t.corner_count());
  for (uint32_t c = 0; c < t.corner_count(); ++c) {
    if (t.opposite(c) != kNone) {
      EXPECT_EQ(t.opposite(t.opposite(c)), c);
    }
  }
}

}  // namespace
}  // namespace tessera
