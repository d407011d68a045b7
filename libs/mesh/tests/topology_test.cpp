#include "tessera/mesh/topology.hpp"

#include <gtest/gtest.h>

#include "shared_data.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"

namespace tessera {
namespace {

PolyMesh two_cubes() {
  PolyMesh a = make_cube();
  const PolyMesh b = make_cube();
  const auto offset = uint32_t(a.vertex_count());
  for (const Vec3& p : b.positions) a.positions.push_back(p + Vec3(3, 0, 0));
  for (size_t f = 0; f < b.face_count(); ++f) {
    std::vector<uint32_t> face;
    for (uint32_t v : b.face(f)) face.push_back(v + offset);
    a.add_face(face);
  }
  return a;
}

TEST(Topology, ClosedSurfacesHaveTheirEulerCharacteristicAndGenus) {
  const TopologyReport cube = analyze_topology(make_cube());
  EXPECT_EQ(cube.edges, 12u);
  EXPECT_EQ(cube.euler, 2);
  EXPECT_EQ(cube.genus, 0);
  EXPECT_TRUE(cube.closed());
  EXPECT_TRUE(cube.manifold());
  EXPECT_TRUE(cube.oriented());
  const TopologyReport torus = analyze_topology(make_torus(1, 0.3, 12, 8));
  EXPECT_EQ(torus.euler, 0);
  EXPECT_EQ(torus.genus, 1);
  const TopologyReport two = analyze_topology(two_cubes());
  EXPECT_EQ(two.components, 2u);
  EXPECT_EQ(two.euler, 4);
  EXPECT_EQ(two.genus, 0);
}

TEST(Topology, BoundaryEdgesAndLoops) {
  const PolyMesh grid = make_grid(3, 3);
  const TopologyReport r = analyze_topology(grid);
  EXPECT_EQ(r.boundary_edges, 12u);
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.euler, 1);
  EXPECT_EQ(r.genus, 0);
  const PolyMesh tube = make_cylinder(6, false);
  const EdgeTable edges = build_edge_table(tube);
  const auto loops = boundary_loops(tube, edges);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].size(), 6u);
  EXPECT_EQ(loops[1].size(), 6u);
  EXPECT_EQ(analyze_topology(tube).genus, 0);
  const auto kinds = classify_vertices(grid, build_edge_table(grid));
  EXPECT_EQ(kinds[0], VertexKind::boundary);
  EXPECT_EQ(kinds[5], VertexKind::interior);  // (1, 1)
}

TEST(Topology, NonManifoldEdgesAndPinchVertices) {
  // Three triangles on the edge 0-1.
  PolyMesh fin;
  fin.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  fin.add_face({0, 1, 2});
  fin.add_face({1, 0, 3});
  fin.add_face({0, 1, 4});
  const EdgeTable edges = build_edge_table(fin);
  const TopologyReport r = analyze_topology(fin);
  EXPECT_EQ(r.nonmanifold_edges, 1u);
  EXPECT_FALSE(r.manifold());
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_EQ(classify_vertices(fin, edges)[0], VertexKind::on_non_manifold_edge);
  // A bowtie: two triangles sharing only vertex 0.
  PolyMesh bowtie;
  bowtie.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0), Vec3(9, 9, 9)};
  bowtie.add_face({0, 1, 2});
  bowtie.add_face({0, 3, 4});
  const auto kinds = classify_vertices(bowtie, build_edge_table(bowtie));
  EXPECT_EQ(kinds[0], VertexKind::non_manifold_fan);
  EXPECT_EQ(kinds[1], VertexKind::boundary);
  EXPECT_EQ(kinds[5], VertexKind::isolated);
  const TopologyReport b = analyze_topology(bowtie);
  EXPECT_EQ(b.nonmanifold_vertices, 1u);
  EXPECT_EQ(b.unreferenced_vertices, 1u);
  EXPECT_EQ(b.components, 1u);
  EXPECT_EQ(b.boundary_loops, 1u);  // the two triangles' boundaries touch at the pinch
}

TEST(Topology, FlippedFaceBreaksTheOrientation) {
  PolyMesh cube = make_cube();
  std::reverse(cube.face_vertices.begin(), cube.face_vertices.begin() + 4);
  const EdgeTable edges = build_edge_table(cube);
  EXPECT_FALSE(is_consistently_oriented(cube, edges));
  const TopologyReport r = analyze_topology(cube);
  EXPECT_EQ(r.inconsistent_edges, 4u);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_TRUE(is_consistently_oriented(make_cube(), build_edge_table(make_cube())));
}

TEST(Topology, FaceComponentsLabelEachPiece) {
  size_t count = 0;
  const auto labels = face_components(two_cubes(), &count);
  EXPECT_EQ(count, 2u);
  EXPECT_EQ(labels[0], 0u);
  EXPECT_EQ(labels[11], 1u);
}

TEST(Topology, SharedDataMatchesTheManifest) {
  TESSERA_SHARED_FILE(res4, "meshes/bunny/bun_zipper_res4.ply");
  const TopologyReport r4 = analyze_topology(read_mesh(res4));
  EXPECT_EQ(r4.nonmanifold_edges, 70u);
  EXPECT_EQ(r4.boundary_loops, 4u);
  EXPECT_FALSE(r4.manifold());
  TESSERA_SHARED_FILE(res2, "meshes/bunny/bun_zipper_res2.ply");
  const TopologyReport r2 = analyze_topology(read_mesh(res2));
  EXPECT_EQ(r2.nonmanifold_edges, 150u);
  EXPECT_EQ(r2.boundary_loops, 5u);
  TESSERA_SHARED_FILE(bob, "meshes/bob/bob_quad.obj");
  const TopologyReport rb = analyze_topology(read_mesh(bob));
  EXPECT_EQ(rb.euler, 0);
  EXPECT_EQ(rb.genus, 1);
  TESSERA_SHARED_FILE(spot, "meshes/spot/spot_triangulated.obj");
  EXPECT_EQ(analyze_topology(read_mesh(spot)).genus, 0);
  TESSERA_SHARED_FILE(suzanne, "meshes/suzanne/suzanne.obj");
  const TopologyReport rs = analyze_topology(read_mesh(suzanne));
  EXPECT_EQ(rs.boundary_loops, 4u);
  EXPECT_EQ(rs.boundary_edges, 42u);
  EXPECT_EQ(rs.nonmanifold_edges, 0u);
}

}  // namespace
}  // namespace tessera
