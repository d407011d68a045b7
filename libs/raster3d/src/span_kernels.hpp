#pragma once
// The span kernels' shared parts (private to raster3d): the per-pixel arithmetic of the depth plane, the two span
// loops every instruction set compiles, and how a set's kernels become a SpanKernels table. Included by
// span_kernels.cpp (the baseline, and the choice of a set), span_avx2.cpp and span_avx512.cpp: each is compiled with
// its own -m flags (CMakeLists.txt) and -ffp-contract=off, and makes the same IEEE operations (the multiply-adds are
// explicit fmaf calls, a library call in the baseline; no other contraction), so every set gives the same pixels.
#include <cstddef>
#include <utility>

#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d::detail {

/// The window z of the fragment at image pixel (i, row r) from the triangle's float depth plane, in llvmpipe's
/// arithmetic (Mesa 22.3, lp_bld_interp.c): a0 + dadx i, then + dady r, each a fused multiply-add.
[[gnu::always_inline]] inline float fragment_depth(float za, float zdx, float zdy, float i, float r) {
  return __builtin_fmaf(zdy, r, __builtin_fmaf(zdx, i, za));
}

/// A fragment's window z to the stored 24-bit value as llvmpipe converts it (lp_build_clamped_float_to_unsigned_norm
/// for 24 bits): clamped to [0, 1] (NaN to 0), times 2^24 - 1 in float, rounded to nearest with ties to even.
[[gnu::always_inline]] inline uint32_t depth24(float z) {
  z = z > 0.0f ? z : 0.0f;
  z = z < 1.0f ? z : 1.0f;
  return uint32_t(int32_t(__builtin_rintf(z * float(kDepthMax))));
}

/// One constant color over image-row pixels [lo, hi) of image row r with the depth plane (za, zdx, zdy): depth test,
/// depth and color writes, branch-free (the loop vectorizes; restrict lets the compiler keep the rows apart).
template <DepthFunc F, bool WriteDepth>
[[gnu::always_inline]] inline void fill_span_pixels(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo,
                                                    int hi, float za, float zdx, float zdy, float r, uint32_t c32) {
  for (int i = lo; i < hi; ++i) {
    const uint32_t d = depth24(fragment_depth(za, zdx, zdy, float(i), r));
    const uint32_t stored = depth[i];
    const uint32_t old_color = color[i];
    const bool pass = depth_passes<F>(d, stored);
    if constexpr (WriteDepth) depth[i] = pass ? d : stored;
    color[i] = pass ? c32 : old_color;
  }
}

/// The depth test of image-row pixels [lo, hi) of row r (early z): their depths into d[i - lo], the outcome into
/// pass[i - lo].
template <DepthFunc F>
[[gnu::always_inline]] inline void test_span_pixels(const uint32_t* __restrict depth, int lo, int hi, float za,
                                                    float zdx, float zdy, float r, uint32_t* __restrict d,
                                                    bool* __restrict pass) {
  for (int i = lo; i < hi; ++i) {
    d[i - lo] = depth24(fragment_depth(za, zdx, zdy, float(i), r));
    pass[i - lo] = depth_passes<F>(d[i - lo], depth[i]);
  }
}

/// The table of a set `Set`: its kernels as the constexpr pointers Set::fill<F, write depth>, Set::test<F> and
/// Set::gouraud<F>, for each DepthFunc F.
template <class Set>
constexpr SpanKernels span_kernel_table() {
  SpanKernels k{};
  [&]<size_t... I>(std::index_sequence<I...>) {
    ((k.fill[I][0] = Set::template fill<DepthFunc(I), false>, k.fill[I][1] = Set::template fill<DepthFunc(I), true>,
      k.test[I] = Set::template test<DepthFunc(I)>, k.gouraud[I] = Set::template gouraud<DepthFunc(I)>),
     ...);
  }
  (std::make_index_sequence<kDepthFuncs>());
  return k;
}

/// Explicit instantiations of a set's fill and test kernels for every depth function (tests call them by name).
#define TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, F) \
  template FillSpan fill<DepthFunc::F, false>;       \
  template FillSpan fill<DepthFunc::F, true>;        \
  template TestSpan test<DepthFunc::F>;
// The invocations end without semicolons, which clang-format cannot lay out stably.
// clang-format off
#define TESSERA_SPAN_INSTANTIATE(fill, test)          \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, never)    \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, less)     \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, equal)    \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, lequal)   \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, greater)  \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, notequal) \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, gequal)   \
  TESSERA_SPAN_INSTANTIATE_FUNC(fill, test, always)
// clang-format on

/// The tables of the vector sets (span_avx2.cpp, span_avx512.cpp), read only where the CPU has the set.
extern const SpanKernels kSpanKernelsAvx2;
extern const SpanKernels kSpanKernelsAvx512;

}  // namespace tessera::raster3d::detail
