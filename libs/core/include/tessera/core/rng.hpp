#pragma once
// Deterministic random numbers: PCG32 (O'Neill 2014) seeded per pixel and sample, so that renders are identical
// for any thread count and any tile order.
#include <cstdint>

namespace tessera {

/// PCG32 (XSH-RR output, 64-bit LCG state). Small, fast and statistically good; one stream per seed pair.
class Rng {
 public:
  /// A generator for `sequence` (e.g. a pixel index) started at `seed` (e.g. a frame or user seed).
  explicit Rng(uint64_t sequence = 0, uint64_t seed = 0x853c49e6748fea9bULL) {
    state_ = 0;
    inc_ = (sequence << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }

  /// A uniform 32-bit integer.
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const auto xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const auto rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  /// A uniform float in [0, 1).
  float uniform() { return float(next_u32() >> 8) * 0x1p-24f; }

  /// A uniform double in [0, 1).
  double uniform_double() {
    const uint64_t hi = next_u32(), lo = next_u32();
    return double(((hi << 32) | lo) >> 11) * 0x1p-53;
  }

  /// A uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform_double(); }

  /// A uniform integer in [0, bound) without modulo bias (Lemire's method).
  uint32_t below(uint32_t bound) {
    uint64_t m = uint64_t(next_u32()) * bound;
    auto low = uint32_t(m);
    if (low < bound) {
      const uint32_t threshold = -bound % bound;
      while (low < threshold) {
        m = uint64_t(next_u32()) * bound;
        low = uint32_t(m);
      }
    }
    return uint32_t(m >> 32);
  }

 private:
  uint64_t state_;
  uint64_t inc_;
};

}  // namespace tessera
