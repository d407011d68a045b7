#include "tessera/math/noise.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

namespace tessera {
namespace {

// Reference values from ProcessingNoiseReference.java (this folder) (java.util.Random, PApplet's noise in Java floats,
// Ken Perlin's ImprovedNoise), as float and double bit patterns: the C++ must match them bit for bit.
float float_bits(uint32_t bits) { return std::bit_cast<float>(bits); }

TEST(JavaRandom, MatchesJavaUtilRandom) {
  // new Random(s).nextInt(): the widely published values for 0 and 42, and one negative seed.
  EXPECT_EQ(JavaRandom(0).next_int(), -1155484576);
  EXPECT_EQ(JavaRandom(42).next_int(), -1170105035);
  EXPECT_EQ(JavaRandom(-7).next_int(), 1155869324);
  JavaRandom r(12345);
  EXPECT_EQ(std::bit_cast<uint32_t>(r.next_float()), 1052327488u);
  EXPECT_EQ(std::bit_cast<uint32_t>(r.next_float()), 1057186227u);
  EXPECT_EQ(std::bit_cast<uint32_t>(r.next_float()), 1064229033u);
}

TEST(ProcessingNoise, MatchesPAppletBitForBit) {
  struct Case {
    int64_t seed;
    float x, y, z;
    uint32_t bits;
  };
  const Case cases[] = {
      {0, 0.1f, 0, 0, 1060302087u},
      {0, 1.5f, 0, 0, 1057173645u},
      {0, 3.7f, 2.2f, 0, 1052132651u},
      {0, -3.7f, 2.2f, 0, 1052132651u},
      {0, 12.34f, 5.67f, 8.9f, 1057203623u},
      {0, 100.01f, 0.5f, 0.25f, 1053938463u},
      {0, 0.5f, 0.5f, 0.5f, 1052381983u},
      {42, 0.1f, 0, 0, 1058486187u},
      {42, 1.5f, 0, 0, 1048714940u},
      {42, 3.7f, 2.2f, 0, 1051381232u},
      {42, -3.7f, 2.2f, 0, 1051381232u},
      {42, 12.34f, 5.67f, 8.9f, 1054168453u},
      {42, 100.01f, 0.5f, 0.25f, 1055081657u},
      {42, 0.5f, 0.5f, 0.5f, 1055312663u},
  };
  for (const Case& c : cases) {
    const ProcessingNoise noise(c.seed);
    EXPECT_EQ(noise.noise(c.x, c.y, c.z), float_bits(c.bits)) << c.seed << ": " << c.x << ", " << c.y << ", " << c.z;
  }
  // noiseDetail(8, 0.65) after noiseSeed(42).
  ProcessingNoise noise;
  noise.noise_seed(42);
  noise.noise_detail(8, 0.65);
  EXPECT_EQ(noise.noise(3.7f, 2.2f, 1.1f), float_bits(1060834404u));
}

TEST(ProcessingNoise, DefaultsAndDetailAsProcessing) {
  ProcessingNoise noise;
  EXPECT_EQ(noise.octaves(), 4);
  EXPECT_EQ(noise.falloff(), 0.5f);
  // The one- and two-argument forms are z = 0 (and y = 0).
  EXPECT_EQ(noise.noise(2.5f), noise.noise(2.5f, 0, 0));
  EXPECT_EQ(noise.noise(2.5f, 1.5f), noise.noise(2.5f, 1.5f, 0));
  // Values <= 0 are ignored, as Processing ignores them.
  noise.noise_detail(0, -1);
  EXPECT_EQ(noise.octaves(), 4);
  EXPECT_EQ(noise.falloff(), 0.5f);
  // One octave at a lattice point is half the table's value there: the first table entry is Random(0)'s first float.
  noise.noise_detail(1);
  EXPECT_EQ(noise.noise(0), 0.5f * JavaRandom(0).next_float());
}

TEST(ProcessingNoise, RangeAndSmoothness) {
  // With 4 octaves and falloff 0.5 every value lies in [0, 0.5 + 0.25 + 0.125 + 0.0625) and nearby points differ
  // little (the eased lattice blend is continuous).
  const ProcessingNoise noise(7);
  float lo = 1, hi = 0;
  for (int i = 0; i < 20000; ++i) {
    const float x = float(i) * 0.013f, y = float(i % 97) * 0.21f;
    const float v = noise.noise(x, y, 0.3f);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    EXPECT_LT(std::fabs(noise.noise(x + 1e-3f, y, 0.3f) - v), 0.02f);
  }
  EXPECT_GE(lo, 0.0f);
  EXPECT_LT(hi, 0.9375f);
  EXPECT_LT(lo, 0.3f);  // and it spreads over the range
  EXPECT_GT(hi, 0.65f);
  // Huge and non-finite coordinates stay defined (Java's saturating (int) cast).
  for (const float v : {3e9f, -3e9f, INFINITY, NAN}) EXPECT_TRUE(std::isfinite(noise.noise(v, 1, 2)));
}

TEST(PerlinNoise, MatchesTheReferenceImplementation) {
  // 0.13691995878400012 at (3.14, 42, 7) is the value published with ports of ImprovedNoise; the others come from the
  // Java reference.
  EXPECT_EQ(std::bit_cast<int64_t>(perlin_noise(3.14, 42, 7)), 4594101081693409077);
  EXPECT_DOUBLE_EQ(perlin_noise(3.14, 42, 7), 0.13691995878400012);
  EXPECT_EQ(perlin_noise(0.5, 0.5, 0.5), -0.25);
  EXPECT_EQ(std::bit_cast<int64_t>(perlin_noise(-1.25, 2.75, 10.125)), -4627878197399126016);
  EXPECT_EQ(std::bit_cast<int64_t>(perlin_noise(123.456, -78.9, 0.001)), 4591181624187429060);
}

TEST(PerlinNoise, LatticeZerosPeriodAndFade) {
  // Zero at every lattice point; period 256; the fade has zero first and second derivatives at the lattice, so the
  // noise is flat there to second order along each axis.
  for (int i = -3; i < 4; ++i) EXPECT_EQ(perlin_noise(i, 2 * i, 5 - i), 0.0);
  EXPECT_EQ(perlin_noise(0.3125, 1.75, 2.125), perlin_noise(256.3125, 1.75 - 512, 2.125 + 256));
  const double h = 1e-3;
  EXPECT_NEAR(perlin_noise(4 + h, 7, 9) + perlin_noise(4 - h, 7, 9), 0, 1e-6);  // odd about the lattice point
  EXPECT_TRUE(std::isnan(perlin_noise(INFINITY, 0, 0)));
  // Within [-1, 1] over a sample of points.
  for (int i = 0; i < 5000; ++i) {
    const double v = perlin_noise(i * 0.37, i * 0.011 - 3, i * 0.0071);
    EXPECT_LE(std::fabs(v), 1.0);
  }
}

}  // namespace
}  // namespace tessera
