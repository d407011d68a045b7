#include "tessera/core/memory_budget.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <limits>

namespace tessera {
namespace {

constexpr uint64_t kKiB = 1024, kMiB = kKiB * 1024, kGiB = kMiB * 1024;

TEST(MemoryBudget, ParsesSizesWithBinarySuffixes) {
  EXPECT_EQ(parse_memory_size("512M", "--max-memory"), 512 * kMiB);
  EXPECT_EQ(parse_memory_size("4G", "--max-memory"), 4 * kGiB);
  EXPECT_EQ(parse_memory_size("4g", "--max-memory"), 4 * kGiB);
  EXPECT_EQ(parse_memory_size("1.5G", "--max-memory"), 3 * kGiB / 2);
  EXPECT_EQ(parse_memory_size("64KiB", "--max-memory"), 64 * kKiB);
  EXPECT_EQ(parse_memory_size("2MB", "--max-memory"), 2 * kMiB);
  EXPECT_EQ(parse_memory_size("1T", "--max-memory"), 1024 * kGiB);
  EXPECT_EQ(parse_memory_size("1000000", "--max-memory"), 1000000u);
  for (const char* bad : {"", "M", "0", "0M", "-1G", "4X", "1e3", "4 G G", "1.2.3M", "99999999999T"})
    EXPECT_THROW(parse_memory_size(bad, "--max-memory"), InvalidInput) << bad;
  try {  // the message quotes the value through printable(): no escape sequence reaches the terminal
    parse_memory_size("\x1b[2J4G", "--max-memory");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("got '\\x1b[2J4G'"), std::string::npos) << e.what();
  }
}

TEST(MemoryBudget, ParsesCgroupAndMeminfoText) {
  EXPECT_EQ(parse_cgroup_limit("4294967296\n"), 4 * kGiB);
  EXPECT_EQ(parse_cgroup_limit("max\n"), std::nullopt);                  // v2: no limit
  EXPECT_EQ(parse_cgroup_limit("9223372036854771712\n"), std::nullopt);  // v1: no limit
  EXPECT_EQ(parse_cgroup_limit("garbage"), std::nullopt);
  EXPECT_EQ(parse_mem_available("MemTotal:       16384000 kB\nMemFree:  1 kB\nMemAvailable:    2048 kB\n"), 2 * kMiB);
  EXPECT_EQ(parse_mem_available("MemTotal: 1 kB\n"), std::nullopt);
}

TEST(MemoryBudget, DefaultHonoursTheSmallestLimit) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "memory_budget_test";
  std::filesystem::create_directories(dir);
  const auto write = [&](const char* name, const char* text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  MemorySources sources;
  sources.cgroup_v2 = write("memory.max", "4294967296\n");
  sources.cgroup_v1 = dir / "absent";
  sources.meminfo = write("meminfo", "MemTotal: 67108864 kB\nMemAvailable: 33554432 kB\n");
  EXPECT_EQ(usable_memory(sources), 4 * kGiB);  // the 4 GiB container, not the 32 GiB available
  EXPECT_EQ(MemoryBudget::default_bytes(sources), 3 * kGiB);
  sources.cgroup_v2 = write("memory.max", "max\n");
  sources.cgroup_v1 = write("limit_in_bytes", "1073741824\n");
  EXPECT_EQ(usable_memory(sources), 1 * kGiB);
  sources.cgroup_v1 = dir / "absent";
  EXPECT_EQ(usable_memory(sources), 32 * kGiB);  // no cgroup limit: MemAvailable
}

TEST(MemoryBudget, CheckNamesTheEstimateAndTheBudget) {
  MemoryBudget::set_limit(1 * kMiB);
  EXPECT_EQ(MemoryBudget::bytes(), 1 * kMiB);
  EXPECT_NO_THROW(MemoryBudget::check(kMiB, "a 512x512 canvas"));
  try {
    MemoryBudget::check(31 * kGiB + kGiB / 2, "SVG canvas 46000x46000");
    FAIL() << "expected MemoryBudgetError";
  } catch (const MemoryBudgetError& e) {
    EXPECT_STREQ(e.what(),
                 "SVG canvas 46000x46000 needs about 31.5 GiB, the memory budget is 1.0 MiB (raise it with "
                 "--max-memory SIZE)");
  }
  MemoryBudget::set_limit(0);
  EXPECT_GT(MemoryBudget::bytes(), 0u);
}

TEST(MemoryBudget, FormatsAndMultiplies) {
  EXPECT_EQ(format_bytes(512), "512 bytes");
  EXPECT_EQ(format_bytes(1536), "1.5 KiB");
  EXPECT_EQ(format_bytes(5 * kGiB), "5.0 GiB");
  EXPECT_EQ(saturating_product({46000, 46000, 16}), uint64_t(46000) * 46000 * 16);
  EXPECT_EQ(saturating_product({uint64_t(1) << 40, uint64_t(1) << 40}), std::numeric_limits<uint64_t>::max());
  EXPECT_EQ(saturating_product({uint64_t(1) << 40, uint64_t(1) << 40, 0}), 0u);
}

}  // namespace
}  // namespace tessera
