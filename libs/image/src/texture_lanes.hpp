#pragma once
// The SIMD half of Texture2D::sample_lanes (private to the image module).
#include "tessera/image/texture.hpp"

namespace tessera {

/// Texture2D::sample_lanes of an 8-bit texture with bilinear or trilinear filtering and repeat or clamp wrapping,
/// eight points at a time (count a multiple of 8; level 0's texels indexable by int32): texture_avx2.cpp, called only
/// where the CPU has AVX2.
void sample_lanes_avx2(const Texture2D& t, const float* u, const float* v, const float* lod, float* const out[4],
                       int count);

}  // namespace tessera
