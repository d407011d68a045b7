#include "tessera/core/atomic_file.hpp"

#include <unistd.h>

#include <filesystem>

#include <gtest/gtest.h>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {
namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tessera_atomic_" + std::to_string(::getpid()) +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  size_t file_count() const { return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator())); }
  fs::path dir_;
};

TEST_F(AtomicFileTest, WritesAndRenames) {
  write_file_atomic(dir_ / "a.txt", "hello");
  EXPECT_EQ(read_file(dir_ / "a.txt"), "hello");
  EXPECT_EQ(file_count(), 1u);
}

TEST_F(AtomicFileTest, FailureLeavesNoFileAndKeepsOldOne) {
  write_file_atomic(dir_ / "a.txt", "old");
  EXPECT_THROW(write_file_atomic(dir_ / "a.txt", [](std::ostream& out) {
                 out << "partial";
                 throw InvalidInput("boom");
               }),
               InvalidInput);
  EXPECT_EQ(read_file(dir_ / "a.txt"), "old");
  EXPECT_EQ(file_count(), 1u);
  EXPECT_THROW(write_file_atomic(dir_ / "b.txt", [](std::ostream&) { throw InvalidInput("boom"); }), InvalidInput);
  EXPECT_FALSE(fs::exists(dir_ / "b.txt"));
  EXPECT_EQ(file_count(), 1u);
}

TEST_F(AtomicFileTest, MissingDirectoryIsIoError) {
  EXPECT_THROW(write_file_atomic(dir_ / "no" / "such" / "a.txt", "x"), IoError);
  EXPECT_THROW(read_file(dir_ / "missing.txt"), IoError);
}

}  // namespace
}  // namespace tessera
