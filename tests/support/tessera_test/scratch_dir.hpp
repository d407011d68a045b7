#pragma once
// A GoogleTest fixture for tests that write files: each test gets its own fresh folder, removed afterwards. The
// folder is named after the process and the test, because ctest runs a fixture's tests at once and a shared folder
// would let one test's TearDown delete another's files.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iterator>
#include <string>

namespace tessera::testing {

class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           fmt::format("tessera-{}-{}-{}", info->test_suite_name(), ::getpid(), info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// The path of `name` in this test's folder.
  std::filesystem::path path(const std::string& name) const { return dir_ / name; }
  /// How many entries the folder holds (a failed write must leave none behind).
  size_t file_count() const {
    return size_t(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()));
  }

  std::filesystem::path dir_;
};

}  // namespace tessera::testing
