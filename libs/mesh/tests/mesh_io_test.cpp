#include "tessera/mesh/mesh_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/mesh/primitives.hpp"

namespace tessera {
namespace {

namespace fs = std::filesystem;

class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per process and test: ctest runs this fixture's tests at once, and a shared folder let one test's
    // TearDown delete the other's files.
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / fmt::format("tessera-mesh-io-{}-{}", ::getpid(), info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(MeshFiles, EveryFormatRoundTripsThroughFiles) {
  const PolyMesh cube = make_cube();
  for (const char* ext : {".obj", ".ply", ".off"}) {
    for (bool binary : {true, false}) {
      SCOPED_TRACE(std::string(ext) + (binary ? " binary" : " ascii"));
      const fs::path path = dir_ / (std::string("cube") + ext);
      write_mesh(path, cube, {binary});
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

TEST_F(MeshFiles, UnknownExtensionsAndMissingFilesAreReported) {
  EXPECT_EQ(mesh_format_from_path("a/b.Obj"), MeshFormat::Obj);
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
