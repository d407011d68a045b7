#include "tessera/mesh/mesh_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera_test/scratch_dir.hpp"

namespace tessera {
namespace {

namespace fs = std::filesystem;

using MeshFiles = testing::ScratchDirTest;

TEST_F(MeshFiles, EveryFormatRoundTripsThroughFiles) {
  const PolyMesh cube = make_cube();
  for (const char* ext : {".obj", ".ply", ".off"}) {
    for (bool binary : {true, false}) {
      SCOPED_TRACE(std::string(ext) + (binary ? " binary" : " ascii"));
      const fs::path path = dir_ / (std::string("cube") + ext);
      write_mesh(path, cube, {.binary = binary, .double_precision = true});
      const PolyMesh back = read_mesh(path);
      EXPECT_EQ(back.positions, cube.positions);
      EXPECT_EQ(back.face_vertices, cube.face_vertices);
    }
  }
  // STL stores float triangles: the cube comes back triangulated, welded, within float precision.
  write_mesh(dir_ / "cube.STL", cube);
  const PolyMesh stl = read_mesh(dir_ / "cube.STL");
  EXPECT_EQ(stl.vertex_count(), 8u);
  EXPECT_EQ(stl.face_count(), 12u);
}

/// The uv, normal and color a face corner ends up with, whether stored per corner or per vertex.
struct CornerData {
  Vec3 position;
  Vec2 uv;
  Vec3 normal, color;
};
CornerData corner_data(const PolyMesh& m, size_t c) {
  const uint32_t v = m.face_vertices[c];
  return {m.positions[v], m.corner_uvs.empty() ? m.uvs[v] : m.corner_uvs[c],
          m.corner_normals.empty() ? m.normals[v] : m.corner_normals[c], m.colors[v]};
}

TEST_F(MeshFiles, EveryAttributeSurvivesEveryFormatThatCanHoldIt) {
  // A uv sphere: face-varying uvs (a seam and the poles), per-vertex normals; plus colors k/255 (exact in a uchar)
  // and a crease tag.
  PolyMesh m = make_uv_sphere(8, 4);
  ASSERT_FALSE(m.corner_uvs.empty());
  ASSERT_EQ(m.normals.size(), m.vertex_count());
  for (size_t v = 0; v < m.vertex_count(); ++v) m.colors.emplace_back(double(v) / 255, double(3 * v) / 255, 1.0);
  m.creases.push_back({m.face_vertices[0], m.face_vertices[1], 2.0f});
  EXPECT_TRUE(unsupported_properties(m, MeshFormat::obj).empty());
  for (const char* ext : {".obj", ".ply", ".off"}) {
    for (bool binary : {true, false}) {
      SCOPED_TRACE(std::string(ext) + (binary ? " binary" : " ascii"));
      const fs::path path = dir_ / (std::string("sphere") + ext);
      write_mesh(path, m, {.binary = binary, .double_precision = true});
      const PolyMesh back = read_mesh(path);
      ASSERT_EQ(back.face_offsets, m.face_offsets);
      for (size_t c = 0; c < m.face_vertices.size(); ++c) {
        const CornerData a = corner_data(m, c), b = corner_data(back, c);
        EXPECT_EQ(b.position, a.position);
        EXPECT_EQ(b.uv, a.uv);
        EXPECT_EQ(b.normal, a.normal);
        EXPECT_EQ(b.color, a.color);
      }
      // OBJ keeps the welded vertices and the crease; PLY and OFF split the seam's vertices (one per distinct uv).
      EXPECT_EQ(back.vertex_count() == m.vertex_count(), std::string(ext) == ".obj");
      EXPECT_EQ(back.creases.size(), std::string(ext) == ".obj" ? 1u : 0u);
    }
  }
  EXPECT_EQ(unsupported_properties(m, MeshFormat::ply), std::vector<std::string>{"creases"});
  EXPECT_EQ(unsupported_properties(m, MeshFormat::off), std::vector<std::string>{"creases"});
  EXPECT_EQ(unsupported_properties(m, MeshFormat::stl),
            (std::vector<std::string>{"texture coordinates", "normals", "vertex colors", "creases"}));
  EXPECT_TRUE(unsupported_properties(make_cube(), MeshFormat::stl).empty());
}

TEST_F(MeshFiles, ReadingReportsTheBytesParsed) {
  // Just over 4 MiB of vertices: reported every MiB, as plain lines at the 10% steps crossed (25%, 50%, 75%).
  std::string obj;
  while (obj.size() < (4u << 20)) obj += "v 0.125 0.25 0.5\n";
  obj += "f 1 2 3\n";
  Progress::set_mode(Progress::Mode::plain);
  ::testing::internal::CaptureStderr();
  {
    Progress progress("read big.obj", int64_t(obj.size()));
    const PolyMesh m = read_mesh(obj, MeshFormat::obj, "big.obj", &progress);
    progress.done();
    EXPECT_EQ(m.face_count(), 1u);
  }
  const std::string log = ::testing::internal::GetCapturedStderr();
  Progress::set_mode(Progress::Mode::automatic);
  EXPECT_THAT(log, ::testing::HasSubstr("read big.obj: 20%\nread big.obj: 40%\nread big.obj: 70%\n"));
}

TEST_F(MeshFiles, UnknownExtensionsAndMissingFilesAreReported) {
  EXPECT_EQ(mesh_format_from_path("a/b.Obj"), MeshFormat::obj);
  EXPECT_THROW(mesh_format_from_path("a.xyz"), InvalidInput);
  EXPECT_THROW(write_mesh(dir_ / "cube.xyz", make_cube()), InvalidInput);
  EXPECT_FALSE(fs::exists(dir_ / "cube.xyz"));
  EXPECT_THROW(read_mesh(dir_ / "missing.obj"), IoError);
}

TEST_F(MeshFiles, MalformedFilesNameThePath) {
  const fs::path path = dir_ / "bad.obj";
  write_file_atomic(path, std::string_view("v 0 0 0\nv 1 x 0\n"));
  try {
    read_mesh(path);
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr(path.string() + ":2:"));
  }
}

}  // namespace
}  // namespace tessera
