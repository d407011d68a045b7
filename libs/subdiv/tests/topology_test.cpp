#include "tessera/subdiv/topology.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

#include "fixtures.hpp"
#include "tessera/core/error.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera {
namespace {

// A mesh with its tables (which view the mesh's face arrays).
struct Built {
  explicit Built(PolyMesh m) : mesh(std::move(m)), tables(mesh.face_offsets, mesh.face_vertices, mesh.vertex_count()) {}
  PolyMesh mesh;
  TopologyTables tables;
};

void build(const std::vector<uint32_t>& offsets, const std::vector<uint32_t>& vertices, size_t vertex_count) {
  const TopologyTables t(offsets, vertices, vertex_count);
}

TEST(TopologyTables, CubeCounts) {
  const Built b(test::cube());
  const TopologyTables& t = b.tables;
  EXPECT_EQ(t.vertex_count(), 8u);
  EXPECT_EQ(t.face_count(), 6u);
  EXPECT_EQ(t.edge_count(), 12u);
  EXPECT_EQ(t.max_valence(), 3u);
  for (uint32_t v = 0; v < 8; ++v) {
    EXPECT_FALSE(t.is_boundary_vertex(v));
    EXPECT_EQ(t.ring_face_count(v), 3u);
    EXPECT_EQ(t.ring_edge_count(v), 3u);
  }
  for (uint32_t e = 0; e < 12; ++e) EXPECT_FALSE(t.is_boundary_edge(e));
  // Edges are numbered in order of first appearance: face 0 = (0, 3, 2, 1).
  EXPECT_EQ(t.edge_vertices(0), (std::array<uint32_t, 2>{0, 3}));
  EXPECT_EQ(t.edge_vertices(3), (std::array<uint32_t, 2>{1, 0}));
  EXPECT_EQ(t.find_edge(3, 0), 0u);
  EXPECT_EQ(t.find_edge(0, 6), TopologyTables::kNone);
}

TEST(TopologyTables, RingsAreCounterclockwiseAndConsistent) {
  for (const PolyMesh& m : {test::cube(), test::grid(4, 3), test::house(), test::icosahedron()}) {
    const TopologyTables t(m.face_offsets, m.face_vertices, m.vertex_count());
    for (uint32_t v = 0; v < t.vertex_count(); ++v) {
      const auto ring = t.ring_corners(v);
      for (uint32_t i = 0; i < ring.size(); ++i) {
        const uint32_t k = ring[i];
        EXPECT_EQ(t.corner_vertex(k), v);
        // Face i lies between edge i (its outgoing edge at v) and edge i+1 (its incoming edge at v).
        EXPECT_EQ(t.ring_edge(v, i), t.corner_edge(k));
        EXPECT_EQ(t.ring_neighbors(v)[i], t.corner_vertex(t.next_corner(k)));
        EXPECT_EQ(t.ring_edge(v, (i + 1) % t.ring_edge_count(v)), t.corner_edge(t.prev_corner(k)));
      }
      // Counterclockwise seen from outside: edge 0 x edge 1 points along face 0's (Newell) normal.
      if (t.ring_edge_count(v) >= 2) {
        const Vec3 a = m.positions[t.ring_neighbor(v, 0)] - m.positions[v];
        const Vec3 b = m.positions[t.ring_neighbor(v, 1)] - m.positions[v];
        Vec3 normal(0.0);
        const auto face = m.face(t.corner_face(ring[0]));
        for (size_t i = 0; i < face.size(); ++i)
          normal += glm::cross(m.positions[face[i]], m.positions[face[(i + 1) % face.size()]]);
        EXPECT_GT(glm::dot(glm::cross(a, b), normal), 0.0) << "vertex " << v;
      }
    }
  }
}

TEST(TopologyTables, GridBoundary) {
  const Built b(test::grid(4, 3));
  const TopologyTables& t = b.tables;
  EXPECT_EQ(t.edge_count(), 4u * 4u + 5u * 3u);
  int boundary_edges = 0;
  for (uint32_t e = 0; e < t.edge_count(); ++e) boundary_edges += t.is_boundary_edge(e);
  EXPECT_EQ(boundary_edges, 2 * (4 + 3));
  // Corner vertex 0: one face, two boundary edges; edge 0 is the leading boundary edge (0 -> 1).
  EXPECT_TRUE(t.is_boundary_vertex(0));
  EXPECT_EQ(t.ring_face_count(0), 1u);
  EXPECT_EQ(t.ring_edge_count(0), 2u);
  EXPECT_EQ(t.ring_neighbor(0, 0), 1u);
  EXPECT_EQ(t.ring_neighbor(0, 1), 5u);
  // Bottom edge vertex 2: faces 1 and 2, edges to 3, 7, 1 in counterclockwise order.
  EXPECT_EQ(t.ring_face_count(2), 2u);
  EXPECT_EQ(t.ring_neighbor(2, 0), 3u);
  EXPECT_EQ(t.ring_neighbor(2, 1), 7u);
  EXPECT_EQ(t.ring_neighbor(2, 2), 1u);
  EXPECT_FALSE(t.is_boundary_vertex(6));
  EXPECT_EQ(t.ring_edge_count(6), 4u);
}

TEST(TopologyTables, RejectsBadFacesAndNonManifolds) {
  EXPECT_THROW(build({0, 2}, {0, 1}, 2), InvalidInput);                  // a 2-gon
  EXPECT_THROW(build({0, 3}, {0, 1, 5}, 3), InvalidInput);               // index out of range
  EXPECT_THROW(build({0, 4}, {0, 1, 2, 1}, 3), InvalidInput);            // repeated vertex
  EXPECT_THROW(build({0, 3, 6}, {0, 1, 2, 0, 1, 3}, 4), TopologyError);  // same edge, same direction
  // Three triangles on edge 0-1.
  EXPECT_THROW(build({0, 3, 6, 9}, {0, 1, 2, 1, 0, 3, 1, 0, 4}, 5), TopologyError);
  // Two triangles touching at vertex 0 only (a bowtie).
  EXPECT_THROW(build({0, 3, 6}, {0, 1, 2, 0, 3, 4}, 5), TopologyError);
}

TEST(TopologyTables, IsolatedVerticesHaveEmptyRings) {
  const std::vector<uint32_t> offsets{0, 3}, vertices{0, 1, 2};
  const TopologyTables t(offsets, vertices, 4);
  EXPECT_EQ(t.ring_face_count(3), 0u);
  EXPECT_EQ(t.ring_edge_count(3), 0u);
  EXPECT_EQ(t.edge_count(), 3u);
}

// The child faces of one uniform step as subdivide() lays them out (child vertices: parent vertices, face points
// for quads, then edge points), built here from the parent tables alone.
PolyMesh split_faces(const TopologyTables& t, TopologyTables::Split split) {
  PolyMesh child;
  const auto edge_point = [&](uint32_t k) {
    return uint32_t(t.vertex_count() + (split == TopologyTables::Split::quads ? t.face_count() : 0) + t.corner_edge(k));
  };
  for (uint32_t f = 0; f < t.face_count(); ++f) {
    const uint32_t o = t.face_offset(f), n = t.face_size(f);
    if (split == TopologyTables::Split::quads) {
      for (uint32_t j = 0; j < n; ++j)
        child.add_face({t.corner_vertex(o + j), edge_point(o + j), uint32_t(t.vertex_count() + f),
                        edge_point(o + (j + n - 1) % n)});
    } else {
      for (uint32_t j = 0; j < 3; ++j)
        child.add_face({t.corner_vertex(o + j), edge_point(o + j), edge_point(o + (j + 2) % 3)});
      child.add_face({edge_point(o), edge_point(o + 1), edge_point(o + 2)});
    }
  }
  return child;
}

void expect_same_tables(const TopologyTables& a, const TopologyTables& b) {
  ASSERT_EQ(a.vertex_count(), b.vertex_count());
  ASSERT_EQ(a.edge_count(), b.edge_count());
  ASSERT_EQ(a.corner_count(), b.corner_count());
  EXPECT_EQ(a.max_valence(), b.max_valence());
  for (uint32_t k = 0; k < a.corner_count(); ++k) {
    ASSERT_EQ(a.twin(k), b.twin(k)) << "corner " << k;
    ASSERT_EQ(a.corner_edge(k), b.corner_edge(k)) << "corner " << k;
  }
  for (uint32_t e = 0; e < a.edge_count(); ++e) ASSERT_EQ(a.edge_corners(e), b.edge_corners(e)) << "edge " << e;
  for (uint32_t v = 0; v < a.vertex_count(); ++v) {
    ASSERT_EQ(a.is_boundary_vertex(v), b.is_boundary_vertex(v)) << "vertex " << v;
    const auto ra = a.ring_corners(v), rb = b.ring_corners(v);
    ASSERT_EQ(std::vector<uint32_t>(ra.begin(), ra.end()), std::vector<uint32_t>(rb.begin(), rb.end()))
        << "vertex " << v;
    const auto na = a.ring_neighbors(v), nb = b.ring_neighbors(v);
    ASSERT_EQ(std::vector<uint32_t>(na.begin(), na.end()), std::vector<uint32_t>(nb.begin(), nb.end()))
        << "vertex " << v;
  }
}

// The tables derived from the parent's equal the tables built from the child faces, level after level, for closed
// meshes, boundaries, mixed polygons and isolated vertices.
TEST(TopologyTables, DerivedLevelsEqualLevelsBuiltFromFaces) {
  PolyMesh with_isolated = test::grid(3, 2);
  with_isolated.positions.push_back({5, 5, 5});
  const std::pair<PolyMesh, TopologyTables::Split> cases[] = {
      {test::cube(), TopologyTables::Split::quads},
      {test::grid(4, 3), TopologyTables::Split::quads},
      {test::house(), TopologyTables::Split::quads},
      {with_isolated, TopologyTables::Split::quads},
      {test::icosahedron(), TopologyTables::Split::triangles},
      {test::torus(6, 5, true), TopologyTables::Split::triangles},
      {triangulate(test::grid(4, 3)), TopologyTables::Split::triangles}};
  for (const auto& [cage, split] : cases) {
    std::vector<PolyMesh> levels{cage};
    auto derived = std::make_unique<TopologyTables>(cage.face_offsets, cage.face_vertices, cage.vertex_count());
    for (int level = 1; level <= 3; ++level) {
      const size_t vertices = derived->vertex_count() +
                              (split == TopologyTables::Split::quads ? derived->face_count() : 0) +
                              derived->edge_count();
      levels.push_back(split_faces(*derived, split));
      const PolyMesh& child = levels.back();
      derived = std::make_unique<TopologyTables>(*derived, split, child.face_offsets, child.face_vertices);
      const TopologyTables built(child.face_offsets, child.face_vertices, vertices);
      SCOPED_TRACE("level " + std::to_string(level) + ", " + std::to_string(cage.face_count()) + " faces");
      expect_same_tables(*derived, built);
    }
  }
}

}  // namespace
}  // namespace tessera
