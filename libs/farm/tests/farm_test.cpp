#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <random>
#include <thread>
#include <vector>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/farm/frames.hpp"
#include "tessera/farm/manifest.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera_test/scratch_dir.hpp"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(FrameRange, ParsesRangesAndSingleFrames) {
  EXPECT_EQ(parse_frame_range("0:239", "--frames").last, 239);
  EXPECT_EQ(parse_frame_range("7", "--frames").first, 7);
  EXPECT_EQ(parse_frame_range("7", "--frames").count(), 1);
  EXPECT_EQ(parse_frame_range("3:5", "--frames").count(), 3);
  for (const char* bad : {"5:3", "-1:4", "a:b", "1:2:3", "", "0:99999999"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(parse_frame_range(bad, "--frames"), InvalidInput);
  }
}

TEST(Tiles, BandsOfRowsCoverTheFrameOnce) {
  EXPECT_EQ(parse_tile("2/8", "--tile").index, 2);
  for (const char* bad : {"8/8", "-1/4", "3", "1/0", "1/5000", "a/b"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(parse_tile(bad, "--tile"), InvalidInput);
  }
  for (int n : {1, 2, 3, 7, 480}) {
    int next = 0;
    for (int k = 0; k < n; ++k) {
      const PixelRect r = tile_rect({k, n}, 640, 480);
      EXPECT_EQ(r.y0, next);
      EXPECT_GT(r.y1, r.y0);
      EXPECT_EQ(r.x1, 640);
      next = r.y1;
    }
    EXPECT_EQ(next, 480);
  }
  EXPECT_THROW(tile_rect({0, 481}, 640, 480), InvalidInput);
  EXPECT_EQ(tile_file("out/f_0007.png", {2, 8}), fs::path("out/f_0007.tile-2-of-8.png"));
}

class Assemble : public testing::ScratchDirTest {};

// Tiles cut from a frame and written in each lossless format stitch back into exactly the bytes of the frame's own
// file.
TEST_F(Assemble, StitchedTilesGiveTheFramesBytes) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(0.f, 1.2f);
  ImageRGB frame(37, 29);
  for (auto& p : frame.pixels()) p = glm::vec3(value(rng), value(rng), value(rng));
  for (const char* ext : {".png", ".pfm", ".hdr", ".ppm", ".bmp", ".tga"}) {
    SCOPED_TRACE(ext);
    const fs::path whole = path(std::string("whole") + ext), split = path(std::string("split") + ext);
    write_image(whole, frame);
    for (int k = 0; k < 5; ++k) {
      const PixelRect r = tile_rect({k, 5}, frame.width(), frame.height());
      ImageRGB tile(r.x1 - r.x0, r.y1 - r.y0);
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) tile(x - r.x0, y - r.y0) = frame(x, y);
      write_image(tile_file(split, {k, 5}), tile);
    }
    assemble_tiles(split, 5);
    EXPECT_EQ(read_file(split), read_file(whole));
  }
}

TEST_F(Assemble, MissingOrMismatchedTilesAndJpegAreRefused) {
  const fs::path frame = path("f.png");
  write_image(tile_file(frame, {0, 2}), ImageRGB(8, 2));
  try {
    assemble_tiles(frame, 2);
    ADD_FAILURE() << "a missing tile was not noticed";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("f.tile-1-of-2.png': tile 1 of 2 is missing"));
  }
  write_image(tile_file(frame, {1, 2}), ImageRGB(9, 2));
  EXPECT_THROW(assemble_tiles(frame, 2), InvalidInput);
  write_image(tile_file(frame, {1, 2}), ImageRGB(8, 5));  // 7 rows split in two are 3 + 4, not 2 + 5
  EXPECT_THROW(assemble_tiles(frame, 2), InvalidInput);
  EXPECT_FALSE(fs::exists(frame));
  EXPECT_THROW(assemble_tiles(path("f.jpg"), 2), InvalidInput);
}

class ManifestTest : public testing::ScratchDirTest {};

TEST_F(ManifestTest, RecordsVerifiesAndNoticesChangedFiles) {
  write_file_atomic(path("a.png"), std::string("abc"));
  EXPECT_TRUE(Manifest::read(path("")).entries().empty());
  ManifestEntry e{.frame = 3,
                  .tile = 1,
                  .tiles = 4,
                  .crc32 = file_crc32(path("a.png")),
                  .bytes = 3,
                  .seconds = 0.5,
                  .host = host_name()};
  EXPECT_EQ(e.crc32, 0x352441c2u);  // CRC-32 of "abc" (the check value of zlib's and PNG's CRC)
  Manifest::record(path(""), "a.png", e);
  const Manifest m = Manifest::read(path(""));
  ASSERT_NE(m.find("a.png"), nullptr);
  EXPECT_EQ(m.find("a.png")->tile, 1);
  EXPECT_EQ(m.find("a.png")->tiles, 4);
  EXPECT_DOUBLE_EQ(m.find("a.png")->seconds, 0.5);
  EXPECT_TRUE(m.verified(path(""), "a.png"));
  write_file_atomic(path("a.png"), std::string("abd"));  // same size, other bytes
  EXPECT_FALSE(m.verified(path(""), "a.png"));
  EXPECT_FALSE(m.verified(path(""), "b.png"));
  write_file_atomic(Manifest::path_in(path("")), std::string("{\"files\": {\"a.png\": {\"frame\": \"x\"}}}"));
  EXPECT_THROW(Manifest::read(path("")), InvalidInput);
}

// Processes recording at once (as a farm's tasks finishing together) keep every entry.
TEST_F(ManifestTest, ConcurrentRecordsLoseNothing) {
  constexpr int kProcesses = 4, kEach = 25;
  std::vector<pid_t> children;
  for (int p = 0; p < kProcesses; ++p) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      for (int i = 0; i < kEach; ++i)
        Manifest::record(path(""), "f" + std::to_string(p * kEach + i), ManifestEntry{.frame = p * kEach + i});
      _exit(0);
    }
    children.push_back(pid);
  }
  for (const pid_t pid : children) {
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  EXPECT_EQ(Manifest::read(path("")).entries().size(), size_t(kProcesses * kEach));
}

}  // namespace
}  // namespace tessera
