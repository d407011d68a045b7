#pragma once
// Sample patterns for distribution ray tracing: stratified 2D points per pixel (Kensler's correlated multi-jittered
// sampling, stratified in 2D and in each 1D projection for any sample count) and warps from the unit square.
#include <cstdint>
#include <span>

#include "tessera/math/types.hpp"

namespace tessera {

/// Sample `s` of an `n`-sample stratified pattern over [0, 1)^2, scrambled by `pattern` (Kensler 2013, "Correlated
/// Multi-Jittered Sampling"). The n points of one pattern fall in distinct cells of a ceil(sqrt n) grid and in distinct
/// 1/n strata along each axis (exactly when n is a product m x ceil(n/m) of the grid sides).
Vec2f stratified_sample(uint32_t s, uint32_t n, uint32_t pattern);

/// A pseudo-random permutation of [0, n) evaluated at i (Kensler 2013), a bijection for every pattern.
uint32_t permute_index(uint32_t i, uint32_t n, uint32_t pattern);

/// permute_index(., n, pattern) with its per-permutation constants (mask, rotation) computed once.
class Permutation {
 public:
  Permutation() = default;
  Permutation(uint32_t n, uint32_t pattern);
  /// The image of i in [0, n).
  uint32_t operator()(uint32_t i) const;

 private:
  uint32_t n_ = 1, mask_ = 0, pattern_ = 0, offset_ = 0;
};

/// One n-sample stratified pattern with its per-pattern constants (grid sides, masks, scrambles) computed once:
/// sample(s) == stratified_sample(s, n, pattern), bit for bit, without the per-call square root and divisions.
class StratifiedPattern {
 public:
  StratifiedPattern(uint32_t n, uint32_t pattern);
  /// Sample s in [0, n) of the pattern.
  Vec2f sample(uint32_t s) const;
  /// Samples first, first + 1, ... into out (all < n): the same numbers as sample(), computed in one loop whose
  /// iterations overlap (each sample is a long chain of dependent integer multiplications).
  void samples(uint32_t first, std::span<Vec2f> out) const;

 private:
  uint32_t m_ = 1, rows_count_ = 1, jitter_x_ = 0, jitter_y_ = 0;  // grid sides, jitter scrambles
  Permutation order_, columns_, rows_;
};

/// A well-mixed 32-bit hash of several values (for per-pixel, per-dimension patterns).
uint32_t hash_u32(uint64_t a, uint64_t b = 0, uint64_t c = 0);

/// Uniform point on the unit disk (concentric map, Shirley and Chiu 1997).
Vec2f sample_disk(const Vec2f& u);

/// Direction around +z with density (exponent + 1) / (2 pi) cos^exponent(theta): the Phong lobe used for glossy
/// reflection (cos theta = u.x^(1 / (exponent + 1))).
Vec3f sample_phong_lobe(const Vec2f& u, float exponent);

}  // namespace tessera
