// The viewer's file-type dispatch: extensions, built-in scene names, procedural volumes, and the errors for what it
// cannot show.
#include "tessera/view/viewable.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

namespace fs = std::filesystem;

fs::path scratch_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "tessera-view-test";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

TEST(Viewable, KindFromTheExtension) {
  EXPECT_EQ(viewable_kind("a.obj"), ViewableKind::mesh);
  EXPECT_EQ(viewable_kind("dir/b.PLY"), ViewableKind::mesh);
  EXPECT_EQ(viewable_kind("c.off"), ViewableKind::mesh);
  EXPECT_EQ(viewable_kind("d.Stl"), ViewableKind::mesh);
  EXPECT_EQ(viewable_kind("e.json"), ViewableKind::scene);
  EXPECT_EQ(viewable_kind("f.nrrd"), ViewableKind::volume);
  EXPECT_EQ(viewable_kind("g.nhdr"), ViewableKind::volume);
  EXPECT_EQ(viewable_kind("h.mhd"), ViewableKind::volume);
  EXPECT_EQ(viewable_kind("i.raw"), ViewableKind::volume);
  EXPECT_EQ(viewable_kind("teapot.bpt"), ViewableKind::patches);
}

TEST(Viewable, BuiltInScenesAndProceduralVolumesByName) {
  EXPECT_EQ(viewable_kind("cornell"), ViewableKind::scene);
  EXPECT_EQ(viewable_kind("whitted"), ViewableKind::scene);
  EXPECT_EQ(viewable_kind("sphere:32"), ViewableKind::volume);
  EXPECT_EQ(viewable_kind("noise:16:3"), ViewableKind::volume);
  EXPECT_EQ(kind_name(ViewableKind::patches), "patches");
}

TEST(Viewable, UnknownNamesAreErrorsThatSayWhatIsViewable) {
  try {
    viewable_kind("no-such-thing");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cornell"), std::string::npos) << e.what();
  }
  const fs::path text = scratch_file("notes.txt", "hello\n");
  try {
    viewable_kind(text.string());
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(".obj .ply .off .stl"), std::string::npos) << e.what();
  }
}

TEST(Viewable, ReadsEachKind) {
  const fs::path obj = scratch_file("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const Viewable mesh = read_viewable(obj.string());
  EXPECT_EQ(mesh.kind, ViewableKind::mesh);
  EXPECT_EQ(mesh.mesh.face_count(), 1u);
  const Viewable volume = read_viewable("sphere:12");
  ASSERT_TRUE(volume.volume);
  EXPECT_EQ(volume.volume->dims(), glm::ivec3(12));
  const Viewable scene = read_viewable("cornell");
  ASSERT_TRUE(scene.scene);
  EXPECT_FALSE(scene.scene->objects.empty());
}

TEST(Viewable, RefusesWhatHasNothingToShow) {
  EXPECT_THROW(read_viewable(scratch_file("points.obj", "v 0 0 0\nv 1 0 0\n").string()), InvalidInput);
  EXPECT_THROW(read_viewable(scratch_file("none.bpt", "0\n").string()), InvalidInput);
  try {
    read_viewable(scratch_file("voxels.raw", "abcdefgh").string());
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(".mhd"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_viewable("missing.ply"), IoError);
}

TEST(Viewable, TeapotFromSharedDataWhenPresent) {
  const char* env = std::getenv("TESSERA_SHARED_DATA");
  const fs::path path = fs::path(env ? env : TESSERA_SHARED_DATA) / "bezier/teapot.bpt";
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const Viewable v = read_viewable(path.string());
  EXPECT_EQ(v.kind, ViewableKind::patches);
  EXPECT_EQ(v.patches.size(), 32u);  // Newell's teapot
}

}  // namespace
}  // namespace tessera
