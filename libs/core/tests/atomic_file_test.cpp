#include "tessera/core/atomic_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "tessera/core/error.hpp"
#include "tessera_test/scratch_dir.hpp"

namespace tessera {
namespace {
namespace fs = std::filesystem;

using AtomicFileTest = testing::ScratchDirTest;

TEST_F(AtomicFileTest, WritesAndRenames) {
  write_file_atomic(dir_ / "a.txt", "hello");
  EXPECT_EQ(read_file(dir_ / "a.txt"), "hello");
  EXPECT_EQ(file_count(), 1u);
}

TEST_F(AtomicFileTest, FailureLeavesNoFileAndKeepsOldOne) {
  write_file_atomic(dir_ / "a.txt", "old");
  EXPECT_THROW(write_file_atomic(dir_ / "a.txt",
                                 [](std::ostream& out) {
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

TEST_F(AtomicFileTest, PlantedSymlinksAtGuessableNamesAreNeverFollowed) {
  // The old temporary names were "<target>.tmp-<pid>-<counter>": plant links there (and at a few neighbouring pids)
  // to a victim file, as an attacker sharing the folder could.
  const fs::path victim = dir_ / "victim.txt";
  write_file_atomic(victim, "precious");
  const fs::path target = dir_ / "out.txt";
  for (int pid = ::getpid() - 2; pid <= ::getpid() + 2; ++pid)
    for (int n = 0; n < 8; ++n)
      fs::create_symlink(victim, dir_ / ("out.txt.tmp-" + std::to_string(pid) + "-" + std::to_string(n)));
  for (int i = 0; i < 4; ++i) write_file_atomic(target, "new " + std::to_string(i));
  EXPECT_EQ(read_file(victim), "precious");
  EXPECT_EQ(read_file(target), "new 3");
  EXPECT_FALSE(fs::is_symlink(target));
}

TEST_F(AtomicFileTest, TemporaryIsAFreshUnpredictableRegularFile) {
  AtomicFile a(dir_ / "x.bin");
  AtomicFile b(dir_ / "x.bin");
  EXPECT_NE(a.temporary(), b.temporary());
  EXPECT_EQ(a.temporary().filename().string().find("x.bin.tmp-" + std::to_string(::getpid())), std::string::npos);
  struct stat st {};
  ASSERT_EQ(::lstat(a.temporary().c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode));
}

TEST_F(AtomicFileTest, SymlinkAtTheTargetIsReplacedNotWrittenThrough) {
  // A link to the victim in place of the target itself is replaced by the rename, never written through.
  const fs::path victim = dir_ / "victim.txt";
  write_file_atomic(victim, "precious");
  fs::create_symlink(victim, dir_ / "out.txt");
  write_file_atomic(dir_ / "out.txt", "data");
  EXPECT_EQ(read_file(victim), "precious");
  EXPECT_FALSE(fs::is_symlink(dir_ / "out.txt"));
  EXPECT_EQ(read_file(dir_ / "out.txt"), "data");
}

TEST_F(AtomicFileTest, FatalSignalRemovesTemporaryAndKeepsTheSignalAsStatus) {
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      AtomicFile file(dir_ / "big.bin");
      file.stream() << std::string(1 << 20, 'x');
      ::raise(sig);
      ::_exit(0);  // not reached: the default action ends the process
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << sig;
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_EQ(file_count(), 0u) << "signal " << sig << " left a temporary behind";
  }
}

TEST_F(AtomicFileTest, ReadingAFolderSaysSo) {
  try {
    read_file(dir_);
    FAIL() << "no exception";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory, expected a file"), std::string::npos) << e.what();
  }
}

TEST_F(AtomicFileTest, ReadsPipesAndEmptyFiles) {
  write_file_atomic(dir_ / "empty", "");
  EXPECT_EQ(read_file(dir_ / "empty"), "");
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::ofstream(fifo) << "through a pipe";
    ::_exit(0);
  }
  EXPECT_EQ(read_file(fifo), "through a pipe");
  ::waitpid(child, nullptr, 0);
}

}  // namespace
}  // namespace tessera
