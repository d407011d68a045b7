#pragma once
// Noise functions: Processing's noise() (what the notes' sketches call) and Ken Perlin's improved noise (2002).
//
// ProcessingNoise follows PApplet's algorithm step for step, in the same float arithmetic: a table of 4096 random
// floats from java.util.Random (JavaRandom below, the same 48-bit generator), looked up on the lattice x + 16 y + 256 z
// (wrapping every 4096 entries), blended with the cosine ease 0.5 (1 - cos(pi t)) read from Processing's 720-entry
// cosine table, summed over octaves that double the frequency and multiply the amplitude by the falloff (4 octaves,
// falloff 0.5, first amplitude 0.5: values in [0, 0.9375)); negative coordinates are mirrored (noise(-x) = noise(x)),
// as Processing's. After noise_seed(s) the values are Processing's after noiseSeed(s) (tested against
// java.util.Random and a Java port of the algorithm). Processing seeds an unseeded sketch from the clock; Tessera
// starts from noise_seed(0), so an unseeded run is repeatable.
#include <array>
#include <cstdint>

namespace tessera {

/// java.util.Random's generator (Knuth's 48-bit linear congruential generator with Java's multiplier 0x5DEECE66D and
/// increment 11, seeds scrambled by xor with the multiplier), exactly: the same seed gives Java's numbers.
class JavaRandom {
 public:
  /// new Random(seed).
  explicit JavaRandom(int64_t seed) { set_seed(seed); }
  /// setSeed(seed).
  void set_seed(int64_t seed);
  /// nextInt(): 32 random bits as a signed int.
  int32_t next_int() { return next(32); }
  /// nextFloat(): a uniform float in [0, 1) with 24 random bits.
  float next_float() { return float(next(24)) / float(1 << 24); }

 private:
  int32_t next(int bits);
  uint64_t state_ = 0;
};

/// Processing's noise(x, y, z), noiseSeed and noiseDetail, with their state (one per sketch).
class ProcessingNoise {
 public:
  /// The table of noise_seed(seed).
  explicit ProcessingNoise(int64_t seed = 0) { noise_seed(seed); }

  /// noise(x), noise(x, y), noise(x, y, z): smooth noise, in [0, 1) for falloffs up to 0.5 (the sum of the
  /// amplitudes 0.5 + 0.5 falloff + ... stays below 1); |coordinates| from 2^31 on saturate, as Java's (int) cast.
  float noise(float x, float y = 0, float z = 0) const;
  /// noiseSeed(seed): refills the table from java.util.Random(seed).
  void noise_seed(int64_t seed);
  /// noiseDetail(octaves): the number of octaves; values < 1 are ignored (as Processing).
  void noise_detail(int octaves);
  /// noiseDetail(octaves, falloff): also each octave's amplitude factor; a falloff <= 0 is ignored (as Processing).
  /// Falloffs above 0.5 can give values of 1 and more.
  void noise_detail(int octaves, double falloff);

  int octaves() const { return octaves_; }
  float falloff() const { return falloff_; }

 private:
  std::array<float, 4096> table_{};
  int octaves_ = 4;
  float falloff_ = 0.5f;
};

/// Ken Perlin's improved noise (SIGGRAPH 2002, the reference ImprovedNoise.java): gradient noise on the integer
/// lattice with his 256-entry permutation table (repeating every 256 units), 12 edge gradients picked by the hash's
/// low 4 bits and the fade 6t^5 - 15t^4 + 10t^3. Zero at every lattice point, in about [-1, 1]. Double precision;
/// values equal the reference's. A coordinate that is not finite gives NaN.
double perlin_noise(double x, double y, double z);

}  // namespace tessera
