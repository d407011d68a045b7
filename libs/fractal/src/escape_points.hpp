#pragma once
// The escape-time loops over a batch of points, one per instruction set (private to the fractal module).
//
// Every loop computes, for each point i, exactly this sequence (the scalar reference, escape_time.cpp):
//   x = zr[i], y = zi[i], yy = y*y, m = fma(x, x, yy), n = 0
//   while !(m > bailout2): if n == max: stop (inside)
//                          x, y = fma(x, x, cr - yy), fma(x + x, y, ci);  yy = y*y;  m = fma(x, x, yy);  ++n
//   iterations[i] = n, norm2[i] = m
// The translation units of the SIMD loops are compiled with their instruction set and -ffp-contract=off, and include
// nothing from the standard library but <cstdint>/<cstddef>, so no inline function compiled for AVX can leak into the
// rest of the program.
#include <cstddef>
#include <cstdint>

namespace tessera::detail {

/// Structure-of-arrays batch: starting z and c of `count` points, and where their results go.
struct PointBatch {
  const double* zr;
  const double* zi;
  const double* cr;
  const double* ci;
  size_t count;
  uint32_t* iterations;
  double* norm2;
};

/// The loop's constants.
struct IterationLimits {
  uint32_t max_iterations;  ///< >= 1
  double bailout2;          ///< R^2
};

void escape_points_scalar(const PointBatch& batch, const IterationLimits& limits);
void escape_points_avx2(const PointBatch& batch, const IterationLimits& limits);
void escape_points_avx512(const PointBatch& batch, const IterationLimits& limits);

}  // namespace tessera::detail
