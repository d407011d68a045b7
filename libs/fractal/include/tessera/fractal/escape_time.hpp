#pragma once
// Escape-time pictures of z -> z^2 + c (the notes' "Complex Numbers", "Julia Set" and "Mandelbrot Set"):
//   Julia set for one c:  z0 comes from the pixel, c is fixed for the whole picture;
//   Mandelbrot set:       z0 = 0, c comes from the pixel.
// A point "escapes" at the first n with |z_n| > R; points that have not escaped after max_iterations count as inside.
//
// One iteration is computed by every path (scalar, AVX2, AVX-512) with exactly these operations, so the iteration
// counts and final |z|^2 are bit-identical whichever path and however many threads run:
//   yy = y*y;  |z|^2 = fma(x, x, yy);  x' = fma(x, x, cx - yy);  y' = fma(x + x, y, cy)
#include <complex>
#include <cstdint>
#include <string_view>

#include "tessera/image/image.hpp"

namespace tessera {

/// A square-pixel window of the complex plane mapped onto a width x height picture. `scale` is the width of the view
/// in the complex plane (DESIGN.md section 4); row 0 is the top (largest imaginary part).
struct ComplexView {
  std::complex<double> center{-0.5, 0.0};  ///< the point at the middle of the picture
  double scale = 3.0;                      ///< width of the view in the complex plane (> 0)
  int width = 800;                         ///< pixels (> 0)
  int height = 600;                        ///< pixels (> 0)

  /// Side of one pixel in the complex plane.
  double pixel_size() const { return scale / width; }
  /// The complex number at the center of pixel (x, y): center + ((x + 0.5 - w/2), -(y + 0.5 - h/2)) * pixel_size.
  std::complex<double> pixel_center(int x, int y) const;
};

/// The instruction set an escape-time loop runs on.
enum class SimdPath {
  automatic,  ///< the widest the CPU supports (AVX-512, else AVX2 with FMA, else scalar)
  scalar,     ///< one point at a time: the reference
  avx2,       ///< 4 doubles per vector (needs AVX2 and FMA)
  avx512,     ///< 8 doubles per vector (needs AVX-512F)
};

/// True when this CPU can run `path` (Auto and Scalar always can). Asks core's cpu_features().
bool simd_supported(SimdPath path);
/// The path Auto resolves to on this CPU.
SimdPath best_simd_path();
/// "auto", "scalar", "avx2" or "avx512".
std::string_view simd_name(SimdPath path);
/// Parses a name of simd_name(); throws InvalidInput for anything else.
SimdPath parse_simd_path(std::string_view name);

/// Settings of an escape-time computation.
struct EscapeOptions {
  int max_iterations = 1000;            ///< iteration cap (>= 1); points that have not escaped by then are inside
  double escape_radius = 256;           ///< R in [2, 1e6]: |z| > R escapes (a large R makes smooth coloring smoother)
  bool interior_checks = true;          ///< Mandelbrot only: c in the main cardioid or period-2 bulb is inside at once
  SimdPath simd = SimdPath::automatic;  ///< which loop runs; throws InvalidInput when the CPU lacks it
};

/// Per-pixel result of an escape-time computation.
struct EscapeImage {
  Image<uint32_t> iterations;  ///< escape count n (|z_n| > R first), or max_iterations for points inside
  Image<float> norm2;          ///< |z_n|^2 where the orbit stopped (0 for points decided by the interior checks)
  int max_iterations = 0;      ///< the cap used
  double escape_radius = 0;    ///< the R used

  /// True when pixel (x, y) never escaped.
  bool inside(int x, int y) const { return iterations(x, y) >= uint32_t(max_iterations); }
};

/// Escape times of the Mandelbrot set (z0 = 0, c = pixel) over `view`, in parallel over rows.
/// Throws InvalidInput for a bad view or options.
EscapeImage mandelbrot(const ComplexView& view, const EscapeOptions& options = {});

/// Escape times of the Julia set of `c` (z0 = pixel, c fixed) over `view`. Throws InvalidInput for bad arguments.
EscapeImage julia(std::complex<double> c, const ComplexView& view, const EscapeOptions& options = {});

/// The notes' connectedness test: the Julia set of c is connected iff the orbit of 0 under z^2 + c stays bounded,
/// i.e. c is in the Mandelbrot set; decided as |z_n| <= 2 for n <= max_iterations (false means "dust").
bool julia_is_connected(std::complex<double> c, int max_iterations = 10000);

/// True when c lies in the main cardioid or the period-2 bulb of the Mandelbrot set (closed-form tests).
bool in_cardioid_or_bulb(std::complex<double> c);

/// The sum of the escape counts over all pixels (max_iterations for every inside point, also for those the interior
/// checks decided without iterating: a benchmark that counts work turns the checks off).
uint64_t iteration_count(const EscapeImage& image);

/// Area of the Mandelbrot set by pixel counting: the square [-2, 0.5] x [-1.25, 1.25] (which holds the whole set) on
/// a size x size grid (size even, >= 2), area = inside pixels * pixel area. Only the upper half is iterated: the set
/// and the grid are exactly symmetric about the real axis. Converges to 1.5066 (Foerstemann's pixel counts).
double mandelbrot_area(int size, const EscapeOptions& options);

}  // namespace tessera
