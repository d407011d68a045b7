#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <utility>

#include "shared_data.hpp"
#include "tessera/core/error.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/topology.hpp"

namespace tessera {
namespace {

using ::testing::HasSubstr;

std::string error_of(std::string_view text) {
  try {
    read_obj(text, "t.obj");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(ObjReader, ReadsPolygonsNegativeIndicesAndIgnoresGroupsAndMaterials) {
  const PolyMesh m = read_obj(
      "# a square and a triangle\nmtllib a.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\r\n"
      "g side\nusemtl red\ns 1\nf 1 2 3 4\nv 2 0 0\nf -4 -1 -3  # relative\n\n",
      "t.obj");
  ASSERT_EQ(m.vertex_count(), 5u);
  ASSERT_EQ(m.face_count(), 2u);
  EXPECT_EQ(m.face_size(0), 4u);
  EXPECT_THAT(std::vector<uint32_t>(m.face(1).begin(), m.face(1).end()), ::testing::ElementsAre(1, 4, 2));
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.corner_uvs.empty());
}

TEST(ObjReader, ConsistentReferencesBecomePerVertexOthersFaceVarying) {
  const PolyMesh per_vertex =
      read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n", "t.obj");
  EXPECT_EQ(per_vertex.uvs.size(), 3u);
  EXPECT_EQ(per_vertex.uvs[1], Vec2(1, 0));
  EXPECT_EQ(per_vertex.normals.size(), 3u);
  EXPECT_TRUE(per_vertex.corner_uvs.empty());
  // Vertex 1 uses vt 2 in one face and vt 4 in the other: a seam.
  const PolyMesh seam =
      read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\nf 1/1 2/2 3/3\nf 2/4 4/2 3/3\n",
               "t.obj");
  EXPECT_TRUE(seam.uvs.empty());
  ASSERT_EQ(seam.corner_uvs.size(), 6u);
  EXPECT_EQ(seam.corner_uvs[3], Vec2(0.5, 0.5));
  const PolyMesh normals_only = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n", "t.obj");
  EXPECT_EQ(normals_only.normals.size(), 3u);
}

TEST(ObjReader, ReadsOpenSubdivTagsAndVertexColors) {
  const PolyMesh m = read_obj(
      "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n"
      "t crease 2/1/0 0 1 4.5\nt corner 1/1/0 2 10\nt interpolateboundary 1/0/0 1\nt crease 3/1/0 0 1 2 1\n",
      "t.obj");
  ASSERT_EQ(m.creases.size(), 3u);
  EXPECT_EQ(m.creases[0].v0, 0u);
  EXPECT_EQ(m.creases[0].v1, 1u);
  EXPECT_FLOAT_EQ(m.creases[0].sharpness, 4.5f);
  EXPECT_EQ(m.creases[2].v0, 1u);
  ASSERT_EQ(m.corners.size(), 1u);
  EXPECT_EQ(m.corners[0].v, 2u);
  EXPECT_FLOAT_EQ(m.corners[0].sharpness, 10.0f);
  ASSERT_EQ(m.colors.size(), 3u);
  EXPECT_EQ(m.colors[2], Vec3(0, 0, 1));
}

TEST(ObjReader, ErrorsNameTheLineAndWhatWasExpected) {
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0\n"), HasSubstr("t.obj:2: expected a vertex coordinate"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"), HasSubstr("t.obj:4: vertex index 4 is out of range"));
  EXPECT_THAT(error_of("v 0 0 0\nf 1 -2 1\n"), HasSubstr("t.obj:2: vertex index -2"));
  EXPECT_THAT(error_of("v 0 0 0\nf 0 1 1\n"), HasSubstr("index 0"));
  EXPECT_THAT(error_of("v 0 nan 0\n"), HasSubstr("t.obj:1: expected a finite number"));
  EXPECT_THAT(error_of("v 0 0 inf\n"), HasSubstr("finite"));
  EXPECT_THAT(error_of("v 0 0 0\nbogus 1 2\n"), HasSubstr("t.obj:2: unknown OBJ statement 'bogus'"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nf 1 2\n"), HasSubstr("at least 3 vertices"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1/x 2 3\n"), HasSubstr("expected a texture coordinate index"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1/1 2 3\n"),
              HasSubstr("texture coordinate index 1 is out of range"));
  EXPECT_THAT(error_of("v 0 0 0 extra\n"), HasSubstr("t.obj:1: unexpected 'extra'"));
  EXPECT_THAT(error_of("v 0 0 0\nt crease 2/1/0 0 5 1\n"), HasSubstr("tag vertex index 5 is out of range"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nt crease 2/1/0 0 1\n"), HasSubstr("expected a tag sharpness"));
  EXPECT_THAT(error_of("v 0 0 0\nf 99999999999999999999 1 1\n"), HasSubstr("expected a vertex index"));
}

TEST(ObjWriter, RoundTripsPositionsFaceVaryingDataAndTags) {
  PolyMesh sphere = make_uv_sphere(12, 6);
  sphere.creases.push_back({0, 1, 2.5f});
  sphere.corners.push_back({3, 1.0f});
  std::ostringstream out;
  write_obj(out, sphere);
  const PolyMesh back = read_obj(out.str(), "round.obj");
  EXPECT_EQ(back.positions, sphere.positions);  // shortest round-trip formatting is exact
  EXPECT_EQ(back.face_vertices, sphere.face_vertices);
  EXPECT_EQ(back.face_offsets, sphere.face_offsets);
  EXPECT_EQ(back.corner_uvs, sphere.corner_uvs);
  EXPECT_EQ(back.normals, sphere.normals);
  ASSERT_EQ(back.creases.size(), 1u);
  EXPECT_FLOAT_EQ(back.creases[0].sharpness, 2.5f);
  EXPECT_EQ(back.corners[0].v, 3u);
  // Each distinct uv is written once (not once per corner): as many vt lines as distinct corner uvs.
  std::set<std::pair<double, double>> distinct;
  for (const Vec2& t : sphere.corner_uvs) distinct.emplace(t.x, t.y);
  size_t vt_lines = 0;
  std::istringstream lines(out.str());
  for (std::string line; std::getline(lines, line);) vt_lines += line.rfind("vt ", 0) == 0;
  EXPECT_EQ(vt_lines, distinct.size());
  EXPECT_LT(distinct.size(), sphere.corner_uvs.size());
}

TEST(ObjReader, SharedDataSpotAndBobHaveTheManifestTopology) {
  TESSERA_SHARED_FILE(spot, "meshes/spot/spot_control_mesh.obj");
  const PolyMesh cage = read_mesh(spot);
  EXPECT_EQ(cage.vertex_count(), 188u);
  EXPECT_EQ(cage.face_count(), 180u);
  EXPECT_EQ(analyze_topology(cage).genus, 0);
  TESSERA_SHARED_FILE(bob, "meshes/bob/bob_controlmesh.obj");
  const PolyMesh b = read_mesh(bob);
  EXPECT_EQ(b.vertex_count(), 334u);
  EXPECT_EQ(b.face_count(), 334u);
  EXPECT_EQ(analyze_topology(b).genus, 1);
  TESSERA_SHARED_FILE(suzanne, "meshes/suzanne/suzanne.obj");
  const PolyMesh s = read_mesh(suzanne);
  EXPECT_EQ(s.vertex_count(), 507u);
  EXPECT_EQ(s.face_count(), 500u);
  EXPECT_EQ(s.normals.size(), 507u);
}

}  // namespace
}  // namespace tessera
