#include "tessera/core/cpu.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace tessera {
namespace {

// The flags Linux reports for the first CPU in /proc/cpuinfo (the kernel drops those the OS does not enable):
// an independent reading of the same features. Empty where there is no such file.
std::set<std::string> proc_cpuinfo_flags() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    std::set<std::string> flags;
    for (std::string w; words >> w;) flags.insert(w);
    return flags;
  }
  return {};
}

TEST(Cpu, FeaturesAgreeWithProcCpuinfo) {
  const std::set<std::string> flags = proc_cpuinfo_flags();
  if (flags.empty()) GTEST_SKIP() << "no /proc/cpuinfo flags";
  const CpuFeatures& f = cpu_features();
  EXPECT_EQ(f.avx2, flags.count("avx2") == 1);
  EXPECT_EQ(f.fma, flags.count("fma") == 1);
  EXPECT_EQ(f.avx512f, flags.count("avx512f") == 1);
  EXPECT_EQ(f.avx512bw, flags.count("avx512bw") == 1);
  EXPECT_EQ(f.avx512vl, flags.count("avx512vl") == 1);
  EXPECT_EQ(f.avx512dq, flags.count("avx512dq") == 1);
  EXPECT_EQ(&cpu_features(), &f);  // asked once
}

TEST(Cpu, LevelNeedsEveryFeatureOfIt) {
  CpuFeatures f;
  EXPECT_EQ(simd_level(f), SimdLevel::baseline);
  f.avx2 = true;
  EXPECT_EQ(simd_level(f), SimdLevel::baseline);  // AVX2 without FMA is not the avx2 level
  f.fma = true;
  EXPECT_EQ(simd_level(f), SimdLevel::avx2);
  f.avx512f = f.avx512bw = f.avx512vl = true;
  EXPECT_EQ(simd_level(f), SimdLevel::avx2);  // DQ missing
  f.avx512dq = true;
  EXPECT_EQ(simd_level(f), SimdLevel::avx512);
  f.fma = false;
  EXPECT_EQ(simd_level(f), SimdLevel::baseline);
  EXPECT_STREQ(simd_level_name(SimdLevel::avx512), "avx512");
  EXPECT_STREQ(simd_level_name(SimdLevel::baseline), "baseline");
}

}  // namespace
}  // namespace tessera
