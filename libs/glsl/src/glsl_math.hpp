#pragma once
// The executor's fast forms of GLSL built-ins (execute_impl.hpp calls them in its lane loops; the tests check them).
#include <algorithm>
#include <cstdint>
#include <cstring>

namespace tessera::glsl {

/// GLSL's pow(x, y) = exp2(y log2 x) for x > 0, branch-free so that the lane loop vectorizes (the library's powf is
/// a call per lane: a tenth of a per-pixel Phong program). log2 of the mantissa m in [sqrt(1/2), sqrt(2)) by the
/// series of atanh, t = (m - 1) / (m + 1): 2 / ln 2 (t + t^3/3 + ... + t^9/9), |t| < 0.172; 2^f for f in [-1/2, 1/2]
/// by Taylor's series of e^(f ln 2) to degree 7. Relative error below 2e-5 for |y| <= 128 (the test
/// compares with std::pow) where glsl_pow_covers(x, y).
inline float glsl_pow(float x, float y) {
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  int32_t exponent = int32_t(bits >> 23) - 127;
  uint32_t mantissa_bits = (bits & 0x7fffffu) | 0x3f800000u;  // m in [1, 2)
  float m;
  std::memcpy(&m, &mantissa_bits, sizeof m);
  const bool high = m > 1.41421356f;
  m = high ? m * 0.5f : m;
  exponent += high ? 1 : 0;
  const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  const float series = t * (1.0f + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7 + t2 * (1.0f / 9)))));
  const float log2x = float(exponent) + 2.88539008f * series;  // 2 / ln 2
  float z = y * log2x;
  z = std::min(std::max(z, -126.0f), 127.0f);
  const float n = __builtin_rintf(z), f = (z - n) * 0.693147181f;  // ln 2
  const float e =
      1.0f + f * (1.0f + f * (0.5f + f * (1.0f / 6 +
                                          f * (1.0f / 24 + f * (1.0f / 120 + f * (1.0f / 720 + f * (1.0f / 5040)))))));
  const uint32_t scale_bits = uint32_t(int32_t(n) + 127) << 23;
  float scale;
  std::memcpy(&scale, &scale_bits, sizeof scale);
  return e * scale;
}

/// Whether glsl_pow(x, y) is accurate: x a positive normal float, both finite.
inline bool glsl_pow_covers(float x, float y) {
  return x >= 1.17549435e-38f && x < 3.0e38f && y > -3.0e38f && y < 3.0e38f;
}

}  // namespace tessera::glsl
