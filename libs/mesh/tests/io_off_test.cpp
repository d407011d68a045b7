#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "shared_data.hpp"
#include "tessera/core/error.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/topology.hpp"

namespace tessera {
namespace {

using ::testing::HasSubstr;

std::string error_of(std::string_view data) {
  try {
    read_off(data, "t.off");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(OffReader, PlainColorAndNormalVariants) {
  const PolyMesh plain = read_off("# comment\nOFF\n4 1 4\n0 0 0\n1 0 0\n1 1 0\n\n0 1 0\n4 0 1 2 3 255 0 0\n", "t.off");
  EXPECT_EQ(plain.vertex_count(), 4u);
  EXPECT_EQ(plain.face_size(0), 4u);
  const PolyMesh inline_counts = read_off("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "t.off");
  EXPECT_EQ(inline_counts.face_count(), 1u);
  const PolyMesh colored =
      read_off("COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n", "t.off");
  ASSERT_EQ(colored.colors.size(), 3u);
  EXPECT_EQ(colored.colors[1], Vec3(0, 1, 0));
  const PolyMesh normals = read_off("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", "t.off");
  ASSERT_EQ(normals.normals.size(), 3u);
  const PolyMesh textured = read_off(
      "STCNOFF\n3 1 0\n0 0 0 0 0 1 1 1 1 0.5 0.5\n1 0 0 0 0 1 1 1 1 1 0\n0 1 0 0 0 1 1 1 1 0 1\n3 0 1 2\n", "t.off");
  EXPECT_EQ(textured.uvs[0], Vec2(0.5, 0.5));
  EXPECT_EQ(textured.colors[0], Vec3(1, 1, 1));
}

TEST(OffReader, ErrorsNameTheLine) {
  EXPECT_THAT(error_of("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"), HasSubstr("t.off:4: expected a vertex coordinate"));
  EXPECT_THAT(error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
              HasSubstr("t.off:6: vertex index 3 is out of range"));
  EXPECT_THAT(error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"), HasSubstr("expected a face vertex count"));
  EXPECT_THAT(error_of("OFF\n900000000 1 0\n0 0 0\n"), HasSubstr("larger than the rest of the file"));
  EXPECT_THAT(error_of("4OFF\n"), HasSubstr("t.off:1: expected the keyword OFF"));
  EXPECT_THAT(error_of("OFF\n1 0 0\n0 inf 0\n"), HasSubstr("finite"));
  EXPECT_THAT(error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\nextra\n"),
              HasSubstr("t.off:7: expected the end of the file"));
}

TEST(OffWriter, RoundTrips) {
  PolyMesh m = make_dodecahedron();
  m.colors.assign(m.vertex_count(), Vec3(0.25, 0.5, 1));
  std::ostringstream out;
  write_off(out, m);
  const PolyMesh back = read_off(out.str(), "round.off");
  EXPECT_EQ(back.positions, m.positions);
  EXPECT_EQ(back.face_vertices, m.face_vertices);
  EXPECT_EQ(back.colors, m.colors);
}

TEST(OffWriter, KeepsNormalsColorsAndUvs) {
  PolyMesh m = make_dodecahedron();
  m.colors.assign(m.vertex_count(), Vec3(0.25, 0.5, 1));
  m.normals.resize(m.vertex_count());
  m.uvs.resize(m.vertex_count());
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    m.normals[v] = glm::normalize(m.positions[v]);
    m.uvs[v] = Vec2(m.positions[v].x, 0.1 * double(v));
  }
  std::ostringstream out;
  write_off(out, m);
  EXPECT_EQ(out.str().substr(0, 8), "STCNOFF\n");
  const PolyMesh back = read_off(out.str(), "round.off");
  EXPECT_EQ(back.positions, m.positions);
  EXPECT_EQ(back.normals, m.normals);
  EXPECT_EQ(back.colors, m.colors);
  EXPECT_EQ(back.uvs, m.uvs);
}

TEST(OffReader, SharedDataFilesMatchTheirSources) {
  TESSERA_SHARED_FILE(spot, "meshes/off/spot_control_mesh.off");
  const PolyMesh s = read_mesh(spot);
  EXPECT_EQ(s.vertex_count(), 188u);
  EXPECT_EQ(s.face_count(), 180u);
  EXPECT_EQ(analyze_topology(s).euler, 2);
  TESSERA_SHARED_FILE(bunny, "meshes/off/bun_zipper_res4.off");
  const TopologyReport r = analyze_topology(read_mesh(bunny));
  EXPECT_EQ(r.faces, 948u);
  EXPECT_EQ(r.nonmanifold_edges, 70u);
}

}  // namespace
}  // namespace tessera
