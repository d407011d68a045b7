#pragma once
// Sample patterns for distribution ray tracing: stratified 2D points per pixel (Kensler's correlated multi-jittered
// sampling, stratified in 2D and in each 1D projection for any sample count) and warps from the unit square.
#include <cstdint>

#include "tessera/math/types.hpp"

namespace tessera {

/// Sample `s` of an `n`-sample stratified pattern over [0, 1)^2, scrambled by `pattern` (Kensler 2013, "Correlated
/// Multi-Jittered Sampling"). The n points of one pattern fall in distinct cells of a ceil(sqrt n) grid and in distinct
/// 1/n strata along each axis (exactly when n is a product m x ceil(n/m) of the grid sides).
Vec2f stratified_sample(uint32_t s, uint32_t n, uint32_t pattern);

/// A pseudo-random permutation of [0, n) evaluated at i (Kensler 2013), a bijection for every pattern.
uint32_t permute_index(uint32_t i, uint32_t n, uint32_t pattern);

/// A well-mixed 32-bit hash of several values (for per-pixel, per-dimension patterns).
uint32_t hash_u32(uint64_t a, uint64_t b = 0, uint64_t c = 0);

/// Uniform point on the unit disk (concentric map, Shirley and Chiu 1997).
Vec2f sample_disk(const Vec2f& u);

/// Direction around +z with density (exponent + 1) / (2 pi) cos^exponent(theta): the Phong lobe used for glossy
/// reflection (cos theta = u.x^(1 / (exponent + 1))).
Vec3f sample_phong_lobe(const Vec2f& u, float exponent);

}  // namespace tessera
