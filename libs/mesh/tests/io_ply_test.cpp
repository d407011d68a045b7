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
    read_ply(data, "t.ply");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

/// Appends a scalar in the given byte order.
template <class T>
void put(std::string& s, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

TEST(PlyReader, AsciiWithUnknownPropertiesAndElementsSkipped) {
  const PolyMesh m = read_ply(
      "ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float confidence\nproperty list uchar int junk\nproperty float s\nproperty float t\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty int flags\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 0.5 2 7 7 0 0 255 0 0\n1 0 0 0.5 0 1 0 0 255 0\n1 1 0 0.5 1 9 1 1 0 0 255\n0 1 0 0.5 0 0 1 51 51 51\n"
      "4 0 1 2 3 17\n0 1\n",
      "t.ply");
  ASSERT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[2], Vec2(1, 1));
  ASSERT_EQ(m.colors.size(), 4u);
  EXPECT_EQ(m.colors[0], Vec3(1, 0, 0));
  EXPECT_NEAR(m.colors[3].x, 0.2, 1e-12);
  ASSERT_EQ(m.face_count(), 1u);
  EXPECT_EQ(m.face_size(0), 4u);
}

TEST(PlyReader, BinaryLittleAndBigEndianWithAnyIndexTypes) {
  for (bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    std::string d = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                    "property float nx\nproperty float ny\nproperty float nz\nproperty float texture_u\n"
                    "property float texture_v\nproperty float red\nproperty float green\nproperty float blue\n"
                    "element material 1\nproperty list ushort short stuff\n"
                    "element face 1\nproperty list ushort uint vertex_index\nend_header\n";
    for (int v = 0; v < 3; ++v) {
      put(d, double(v), big), put(d, double(v * 2), big), put(d, -1.5, big);
      put(d, 0.0f, big), put(d, 0.0f, big), put(d, 1.0f, big);
      put(d, 0.25f, big), put(d, 0.75f, big);
      put(d, 0.5f, big), put(d, 0.5f, big), put(d, 1.0f, big);
    }
    put(d, uint16_t(2), big), put(d, int16_t(-1), big), put(d, int16_t(5), big);
    put(d, uint16_t(3), big);
    for (uint32_t i : {2u, 1u, 0u}) put(d, i, big);
    const PolyMesh m = read_ply(d, "t.ply");
    ASSERT_EQ(m.vertex_count(), 3u);
    EXPECT_EQ(m.positions[2], Vec3(2, 4, -1.5));
    EXPECT_EQ(m.normals[1], Vec3(0, 0, 1));
    EXPECT_EQ(m.uvs[0], Vec2(0.25, 0.75));
    EXPECT_EQ(m.colors[0], Vec3(0.5, 0.5, 1));
    EXPECT_EQ(m.face_vertices, (std::vector<uint32_t>{2, 1, 0}));
  }
}

TEST(PlyReader, HostileAndTruncatedFilesAreRejectedWithTheirPlace) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body;
  for (int i = 0; i < 9; ++i) put(body, float(i), false);
  std::string face;
  put(face, uint8_t(3), false);
  for (int i : {0, 1, 2}) put(face, int32_t(i), false);
  EXPECT_EQ(read_ply(header + body + face, "t.ply").face_count(), 1u);
  // Truncated in the middle of the faces.
  EXPECT_THAT(error_of(header + body + face.substr(0, 7)), HasSubstr("t.ply: byte offset"));
  // An index out of range.
  std::string bad = face;
  bad[9] = 7;
  EXPECT_THAT(error_of(header + body + bad), HasSubstr("vertex index 7 is out of range"));
  // A huge element count is refused before any allocation.
  EXPECT_THAT(error_of("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                       "property float y\nproperty float z\nend_header\n" +
                       body),
              HasSubstr("declares 4000000000 rows"));
  // A huge list count.
  std::string huge;
  put(huge, uint32_t(0xFFFFFFFF), false);
  EXPECT_THAT(error_of("ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n" +
                       huge),
              HasSubstr("list count"));
  // NaN coordinates.
  std::string nan_body = body;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan_body.data() + 4, &nan, 4);
  EXPECT_THAT(error_of(header + nan_body + face), HasSubstr("non-finite"));
  EXPECT_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                       "end_header\n0 nan 0\n"),
              HasSubstr("t.ply:8: expected a finite number"));
  EXPECT_THAT(
      error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n"),
      HasSubstr("needs properties x, y and z"));
  EXPECT_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                       "end_header\n0 0\n\n\n\n"),
              HasSubstr("t.ply:8: expected a property value"));
  EXPECT_THAT(error_of("ply\nformat ascii 2.0\n"), HasSubstr("t.ply:2: expected format version 1.0"));
  EXPECT_THAT(error_of("PLY\n"), HasSubstr("t.ply:1: expected 'ply'"));
  EXPECT_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 1\n"), HasSubstr("expected 'end_header'"));
}

TEST(PlyWriter, DoublePrecisionRoundTripsExactly) {
  PolyMesh m = make_quad_sphere(3);
  m.uvs.assign(m.vertex_count(), Vec2(0.125, 0.5));
  m.colors.assign(m.vertex_count(), Vec3(1, 0, 0.2));
  for (bool binary : {true, false}) {
    std::ostringstream out;
    write_ply(out, m, {.binary = binary, .double_precision = true});
    const PolyMesh back = read_ply(out.str(), "round.ply");
    EXPECT_EQ(back.positions, m.positions);
    EXPECT_EQ(back.normals, m.normals);
    EXPECT_EQ(back.uvs, m.uvs);
    EXPECT_EQ(back.colors, m.colors);
    EXPECT_EQ(back.face_vertices, m.face_vertices);
    EXPECT_EQ(back.face_offsets, m.face_offsets);
  }
}

// The default stores float32 (as Blender, MeshLab and Open3D write PLY) with the uvs named s t: every value reads
// back as the nearest float to what was written.
TEST(PlyWriter, FloatIsTheDefaultAndUvsAreNamedST) {
  PolyMesh m = make_quad_sphere(2);
  m.uvs.resize(m.vertex_count());
  for (size_t v = 0; v < m.vertex_count(); ++v) m.uvs[v] = Vec2(m.positions[v].x * 0.3 + 0.5, 1.0 / 3.0);
  const auto f = [](double x) {
    volatile float rounded = float(x);  // volatile: keeps the optimizer from folding the round trip away
    return double(rounded);
  };
  for (bool binary : {true, false}) {
    std::ostringstream out;
    write_ply(out, m, {.binary = binary});
    const std::string text = out.str();
    EXPECT_THAT(text, HasSubstr("property float x\nproperty float y\nproperty float z\n"));
    EXPECT_THAT(text, HasSubstr("property float nx\nproperty float ny\nproperty float nz\n"));
    EXPECT_THAT(text, HasSubstr("property float s\nproperty float t\n"));
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const PolyMesh back = read_ply(text, "float.ply");
    ASSERT_EQ(back.vertex_count(), m.vertex_count());
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      const Vec3 &p = m.positions[v], &n = m.normals[v];
      EXPECT_EQ(back.positions[v], Vec3(f(p.x), f(p.y), f(p.z)));
      EXPECT_EQ(back.normals[v], Vec3(f(n.x), f(n.y), f(n.z)));
      EXPECT_EQ(back.uvs[v], Vec2(f(m.uvs[v].x), f(m.uvs[v].y)));
    }
  }
}

TEST(PlyReader, ReadsUvAsUVOrST) {
  for (const char* names : {"u v", "s t", "texture_u texture_v"}) {
    const std::string n(names);
    const std::string a = n.substr(0, n.find(' ')), b = n.substr(n.find(' ') + 1);
    const PolyMesh m = read_ply(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nproperty float " +
            a + "\nproperty float " + b +
            "\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "property uchar alpha\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0 0.25 0.75 255 0 51 255\n1 0 0 1 0 0 255 0 0\n"
            "0 1 0 0 1 0 0 255 128\n3 0 1 2\n",
        "uv.ply");
    ASSERT_EQ(m.uvs.size(), 3u) << names;
    EXPECT_EQ(m.uvs[0], Vec2(0.25, 0.75));
    EXPECT_EQ(m.colors[0], Vec3(1, 0, 0.2));
  }
}

TEST(PlyReader, SharedDataBunnyHasTheManifestTopology) {
  TESSERA_SHARED_FILE(path, "meshes/bunny/bun_zipper.ply");
  const PolyMesh bunny = read_mesh(path);
  EXPECT_EQ(bunny.vertex_count(), 35947u);
  EXPECT_EQ(bunny.face_count(), 69451u);
  const TopologyReport r = analyze_topology(bunny);
  EXPECT_EQ(r.boundary_loops, 5u);
  EXPECT_EQ(r.boundary_edges, 223u);
  EXPECT_EQ(r.unreferenced_vertices, 1113u);
  EXPECT_EQ(r.euler, -3);
  EXPECT_TRUE(r.manifold());
}

}  // namespace
}  // namespace tessera
