// Stratified patterns (Kensler 2013) and warps.
#include "tessera/raytrace/sampling.hpp"

#include <cmath>

namespace tessera {

Permutation::Permutation(uint32_t n, uint32_t pattern)
    : n_(n), mask_(n > 0 ? n - 1 : 0), pattern_(pattern), offset_(n > 0 ? pattern % n : 0) {
  mask_ |= mask_ >> 1;
  mask_ |= mask_ >> 2;
  mask_ |= mask_ >> 4;
  mask_ |= mask_ >> 8;
  mask_ |= mask_ >> 16;
}

uint32_t Permutation::operator()(uint32_t i) const {
  if (n_ <= 1) return 0;
  const uint32_t w = mask_, p = pattern_, n = n_;
  do {  // a bijective hash on [0, w]; cycle-walk until the value lands in [0, n)
    i ^= p;
    i *= 0xe170893d;
    i ^= p >> 16;
    i ^= (i & w) >> 4;
    i ^= p >> 8;
    i *= 0x0929eb3f;
    i ^= p >> 23;
    i ^= (i & w) >> 1;
    i *= 1 | p >> 27;
    i *= 0x6935fa69;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3;
    i ^= (i & w) >> 2;
    i *= 0xc860a3df;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  // The final rotation by p mod n (Kensler's (i + p) % n, which loses the bijection when i + p wraps around 2^32).
  i += offset_;
  return i >= n ? i - n : i;
}

uint32_t permute_index(uint32_t i, uint32_t n, uint32_t p) { return Permutation(n, p)(i); }

namespace {
float hashed_float(uint32_t i, uint32_t p) {
  i ^= p;
  i ^= i >> 17;
  i ^= i >> 10;
  i *= 0xb36534e5;
  i ^= i >> 12;
  i ^= i >> 21;
  i *= 0x93fc4795;
  i ^= 0xdf6e307f;
  i ^= i >> 17;
  i *= 1 | p >> 18;
  return std::min(float(i) * (1.0f / 4294967808.0f), 0x1.fffffep-1f);
}
}  // namespace

uint32_t hash_u32(uint64_t a, uint64_t b, uint64_t c) {
  uint64_t h = a * 0x9e3779b97f4a7c15ULL ^ (b + 0x632be59bd9b4e019ULL) * 0xbf58476d1ce4e5b9ULL ^
               (c + 0x7f4a7c159e3779b9ULL) * 0x94d049bb133111ebULL;
  h ^= h >> 31;
  h *= 0xd6e8feb86659fd93ULL;
  h ^= h >> 32;
  return uint32_t(h);
}

StratifiedPattern::StratifiedPattern(uint32_t n, uint32_t p)
    : m_(uint32_t(std::ceil(std::sqrt(double(n))))),  // grid columns
      rows_count_((n + m_ - 1) / m_),
      jitter_x_(p * 0x967a889b),
      jitter_y_(p * 0x368cc8b7),
      order_(n, p * 0x51633e2d),
      columns_(m_, p * 0x68bc21eb),
      rows_(rows_count_, p * 0x02e5be93) {}

Vec2f StratifiedPattern::sample(uint32_t s) const {
  const uint32_t m = m_, rows = rows_count_;
  s = order_(s);
  const uint32_t col = s % m, row = s / m;
  const uint32_t sx = columns_(col), sy = rows_(row);
  const float jx = hashed_float(s, jitter_x_), jy = hashed_float(s, jitter_y_);
  return {std::min((float(col) + (float(sy) + jx) / float(rows)) / float(m), 0x1.fffffep-1f),
          std::min((float(row) + (float(sx) + jy) / float(m)) / float(rows), 0x1.fffffep-1f)};
}

void StratifiedPattern::samples(uint32_t first, std::span<Vec2f> out) const {
  for (size_t i = 0; i < out.size(); ++i) out[i] = sample(first + uint32_t(i));
}

Vec2f stratified_sample(uint32_t s, uint32_t n, uint32_t p) { return StratifiedPattern(n, p).sample(s); }

Vec2f sample_disk(const Vec2f& u) {
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  const float quarter = float(kPi) / 4.0f;
  if (std::abs(a) > std::abs(b)) return a * Vec2f(std::cos(quarter * b / a), std::sin(quarter * b / a));
  const float phi = 2.0f * quarter - quarter * a / b;
  return b * Vec2f(std::cos(phi), std::sin(phi));
}

Vec3f sample_phong_lobe(const Vec2f& u, float exponent) {
  const float cos_t = std::pow(1.0f - u.x, 1.0f / (exponent + 1.0f));  // 1 - u.x in (0, 1]: never below the axis
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  const float phi = 2.0f * float(kPi) * u.y;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

}  // namespace tessera
