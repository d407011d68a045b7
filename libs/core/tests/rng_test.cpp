#include "tessera/core/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tessera {
namespace {

TEST(Rng, MatchesPcg32ReferenceStream) {
  // First outputs of the PCG32 reference (pcg32-demo, seed 42, sequence 54).
  Rng rng(54, 42);
  const uint32_t expected[] = {0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e};
  for (uint32_t e : expected) EXPECT_EQ(rng.next_u32(), e);
}

TEST(Rng, UniformIsInUnitIntervalAndUnbiased) {
  Rng rng(7);
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float u = rng.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
  }
  // Mean of U(0,1) has standard deviation 1/sqrt(12 n); allow 5 sigma.
  EXPECT_NEAR(sum / n, 0.5, 5 / std::sqrt(12.0 * n));
}

TEST(Rng, BelowIsUniformChiSquare) {
  Rng rng(3);
  const int bins = 10, n = 100000;
  std::vector<int> count(bins);
  for (int i = 0; i < n; ++i) count[rng.below(bins)]++;
  double chi2 = 0;
  for (int c : count) chi2 += (c - n / bins) * double(c - n / bins) / (n / bins);
  EXPECT_LT(chi2, 27.88);  // chi-square, 9 degrees of freedom, p = 0.001
}

TEST(Rng, SequencesAreIndependentAndDeterministic) {
  Rng a(1), b(2), c(1);
  EXPECT_NE(a.next_u32(), b.next_u32());
  Rng a2(1);
  EXPECT_EQ(a2.next_u32(), c.next_u32());
}

}  // namespace
}  // namespace tessera
