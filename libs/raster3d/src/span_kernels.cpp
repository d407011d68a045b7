// The baseline span kernels (x86-64: SSE2), and the choice of a set: the widest the CPU has, asked once (core's
// simd_level), under span_isa_cap.
#include "span_kernels.hpp"

#include <algorithm>

#include "tessera/core/cpu.hpp"

namespace tessera::raster3d::detail {

template <DepthFunc F, bool WriteDepth>
void fill_span_loop(uint32_t* __restrict depth, AliasedU32* __restrict color, int lo, int hi, float za, float zdx,
                    float zdy, float r, uint32_t c32) {
  fill_span_pixels<F, WriteDepth>(depth, color, lo, hi, za, zdx, zdy, r, c32);
}

template <DepthFunc F>
void test_span_loop(const uint32_t* __restrict depth, int lo, int hi, float za, float zdx, float zdy, float r,
                    uint32_t* __restrict d, bool* __restrict pass) {
  test_span_pixels<F>(depth, lo, hi, za, zdx, zdy, r, d, pass);
}

TESSERA_SPAN_INSTANTIATE(fill_span_loop, test_span_loop)

namespace {

struct Baseline {
  template <DepthFunc F, bool WriteDepth>
  static constexpr FillSpan* fill = fill_span_loop<F, WriteDepth>;
  template <DepthFunc F>
  static constexpr TestSpan* test = test_span_loop<F>;
  template <DepthFunc F>
  static constexpr GouraudRect* gouraud = nullptr;  // the scalar loop of raster_tile
};

constinit const SpanKernels kSpanKernelsBaseline = span_kernel_table<Baseline>();

}  // namespace

int& span_isa_cap() {
  static int cap = -1;
  return cap;
}

int span_isa() {
  static const int isa = int(simd_level());  // 0 baseline, 1 avx2, 2 avx512 (SimdLevel's order)
  return span_isa_cap() < 0 ? isa : std::min(isa, span_isa_cap());
}

const SpanKernels& span_kernels() {
  switch (span_isa()) {
    case 2:
      return kSpanKernelsAvx512;
    case 1:
      return kSpanKernelsAvx2;
    default:
      return kSpanKernelsBaseline;
  }
}

}  // namespace tessera::raster3d::detail
