#include "tessera/mesh/soup.hpp"

#include <gtest/gtest.h>

#include "tessera/core/error.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/topology.hpp"

namespace tessera {
namespace {

TEST(Soup, RoundTripThroughSoupWeldsBackToTheSameMesh) {
  const PolyMesh cube = make_cube();
  const PolygonSoup soup = to_soup(cube);
  EXPECT_EQ(soup.points.size(), 24u);
  EXPECT_EQ(soup.face_count(), 6u);
  const PolyMesh welded = weld(soup);
  EXPECT_EQ(welded.vertex_count(), 8u);
  EXPECT_EQ(welded.face_count(), 6u);
  for (size_t f = 0; f < 6; ++f)
    for (size_t i = 0; i < 4; ++i) EXPECT_EQ(welded.positions[welded.face(f)[i]], cube.positions[cube.face(f)[i]]);
}

TEST(Soup, ExactWeldingMergesSignedZeros) {
  const std::vector<Vec3> points{Vec3(0.0, 1, 2), Vec3(-0.0, 1, 2), Vec3(0, 1, 2.0000001)};
  const WeldedPoints w = weld_points(points);
  EXPECT_EQ(w.points.size(), 2u);
  EXPECT_EQ(w.remap, (std::vector<uint32_t>{0, 0, 1}));
}

TEST(Soup, ToleranceWeldingFindsNeighboursAcrossCells) {
  // 0.0999 and 0.1001 lie in different cells of size 0.01 but within the tolerance.
  const std::vector<Vec3> points{Vec3(0.0999, 0, 0), Vec3(0.1001, 0, 0), Vec3(0.2, 0, 0), Vec3(0.1, 0.005, -0.005)};
  const WeldedPoints w = weld_points(points, 0.01);
  EXPECT_EQ(w.points.size(), 2u);
  EXPECT_EQ(w.remap, (std::vector<uint32_t>{0, 0, 1, 0}));
  EXPECT_THROW(weld_points(points, -1), InvalidInput);
}

TEST(Soup, WeldingDropsCollapsedFacesAndRemapsTags) {
  PolyMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1e-9, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  mesh.add_face({0, 1, 3});
  mesh.add_face({0, 2, 1});  // collapses to an edge
  mesh.add_face({2, 1, 4, 3});
  mesh.corner_uvs.resize(mesh.face_vertices.size(), Vec2(0.5));
  mesh.creases.push_back({2, 1, 3.0f});
  weld_vertices(mesh, 1e-6);
  EXPECT_EQ(mesh.vertex_count(), 4u);
  ASSERT_EQ(mesh.face_count(), 2u);
  EXPECT_EQ(mesh.face_size(1), 4u);
  EXPECT_EQ(mesh.corner_uvs.size(), mesh.face_vertices.size());
  EXPECT_EQ(mesh.creases[0].v0, 0u);
}

// Two unit squares side by side, each with its own uv square (as two Bezier patches): welding the shared edge keeps
// every corner's uv, now per corner; uvs that agree stay per vertex.
TEST(Soup, WeldingKeepsDifferingUvsPerCorner) {
  PolyMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                    Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(1, 1, 0)};
  mesh.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  mesh.add_face({0, 1, 2, 3});
  mesh.add_face({4, 5, 6, 7});
  PolyMesh same_uvs = mesh;
  EXPECT_EQ(weld_vertices(mesh), 2u);
  EXPECT_EQ(mesh.vertex_count(), 6u);
  EXPECT_TRUE(mesh.uvs.empty());
  ASSERT_EQ(mesh.corner_uvs.size(), 8u);
  EXPECT_EQ(mesh.face_vertices[4], mesh.face_vertices[1]);  // the shared edge
  EXPECT_EQ(mesh.corner_uvs[1], Vec2(1, 0));
  EXPECT_EQ(mesh.corner_uvs[4], Vec2(0, 0));
  EXPECT_EQ(mesh.corner_uvs[6], Vec2(1, 1));

  for (size_t v = 0; v < same_uvs.vertex_count(); ++v) same_uvs.uvs[v] = Vec2(same_uvs.positions[v]);
  weld_vertices(same_uvs);
  EXPECT_TRUE(same_uvs.corner_uvs.empty());
  EXPECT_EQ(same_uvs.uvs.size(), 6u);
}

// Two triangles touching at one vertex (a bowtie) and a closed tetrahedron: only the bowtie's vertex splits.
TEST(Soup, SplittingPinchedVerticesGivesEachFanItsOwnVertex) {
  PolyMesh bowtie;
  bowtie.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
  bowtie.colors = {Vec3(0.5), Vec3(1), Vec3(1), Vec3(1), Vec3(1)};
  bowtie.add_face({0, 1, 2});
  bowtie.add_face({0, 3, 4});
  EXPECT_EQ(split_pinched_vertices(bowtie), 1u);
  ASSERT_EQ(bowtie.vertex_count(), 6u);
  EXPECT_EQ(bowtie.face(0)[0], 0u);
  EXPECT_EQ(bowtie.face(1)[0], 5u);
  EXPECT_EQ(bowtie.positions[5], Vec3(0, 0, 0));
  EXPECT_EQ(bowtie.colors[5], Vec3(0.5));
  EXPECT_EQ(analyze_topology(bowtie).nonmanifold_vertices, 0u);

  PolyMesh tetra;
  tetra.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tetra.add_face({0, 2, 1});
  tetra.add_face({0, 1, 3});
  tetra.add_face({1, 2, 3});
  tetra.add_face({0, 3, 2});
  EXPECT_EQ(split_pinched_vertices(tetra), 0u);
  EXPECT_EQ(tetra.vertex_count(), 4u);
}

}  // namespace
}  // namespace tessera
