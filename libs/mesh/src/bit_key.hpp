#pragma once
// Keys made of the bit patterns of doubles, for maps that must tell exactly equal values (a uv, a normal, a split
// vertex) apart: the reader's distinct-value tables and the seam splitter share this hash.
#include <array>
#include <cstddef>
#include <cstdint>

namespace tessera::detail {

/// Hashes an array of 64-bit words (a splitmix-style mix of each word into the running value).
struct BitKeyHash {
  template <size_t N>
  size_t operator()(const std::array<uint64_t, N>& key) const {
    uint64_t h = 0x9E3779B97F4A7C15ULL;
    for (uint64_t w : key) h = (h ^ w) * 0xBF58476D1CE4E5B9ULL, h ^= h >> 31;
    return size_t(h);
  }
};

}  // namespace tessera::detail
