#include "tessera/fractal/escape_time.hpp"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "escape_points.hpp"
#include "tessera/core/cpu.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"

namespace tessera {
namespace detail {

// Two clones chosen at load time: with FMA hardware std::fma is one instruction, without it a (correctly rounded)
// library call; the results are the same bits either way.
__attribute__((target_clones("fma", "default"))) void escape_points_scalar(const PointBatch& batch,
                                                                           const IterationLimits& limits) {
  for (size_t i = 0; i < batch.count; ++i) {
    double x = batch.zr[i], y = batch.zi[i];
    const double cr = batch.cr[i], ci = batch.ci[i];
    double yy = y * y;
    double m = std::fma(x, x, yy);
    uint32_t n = 0;
    while (!(m > limits.bailout2) && n != limits.max_iterations) {
      const double xn = std::fma(x, x, cr - yy);
      y = std::fma(x + x, y, ci);
      x = xn;
      yy = y * y;
      m = std::fma(x, x, yy);
      ++n;
    }
    batch.iterations[i] = n;
    batch.norm2[i] = m;
  }
}

}  // namespace detail

namespace {

using PointLoop = void (*)(const detail::PointBatch&, const detail::IterationLimits&);

PointLoop point_loop(SimdPath path) {
  if (path == SimdPath::automatic) path = best_simd_path();
  if (!simd_supported(path))
    throw InvalidInput(fmt::format("this CPU cannot run the {} escape-time loop", simd_name(path)));
  switch (path) {
    case SimdPath::avx512:
      return detail::escape_points_avx512;
    case SimdPath::avx2:
      return detail::escape_points_avx2;
    default:
      return detail::escape_points_scalar;
  }
}

void check_options(const EscapeOptions& options) {
  if (options.max_iterations < 1)
    throw InvalidInput(fmt::format("iterations must be at least 1, got {}", options.max_iterations));
  if (!(options.escape_radius >= 2 && options.escape_radius <= 1e6))
    throw InvalidInput(fmt::format("escape radius must be in [2, 1e6], got {}", options.escape_radius));
}

void check_view(const ComplexView& view) {
  if (view.width <= 0 || view.height <= 0 || view.width > 65536 || view.height > 65536)
    throw InvalidInput(fmt::format("picture size {}x{} is invalid (1..65536 each)", view.width, view.height));
  if (!(view.scale > 0) || !std::isfinite(view.scale))
    throw InvalidInput(fmt::format("view scale (width in the complex plane) must be positive, got {}", view.scale));
  if (!std::isfinite(view.center.real()) || !std::isfinite(view.center.imag()))
    throw InvalidInput("view center must be finite");
}

/// A batch of points with its storage; `pixel` remembers where each point's result goes.
struct Batch {
  std::vector<double> zr, zi, cr, ci, norm2;
  std::vector<uint32_t> iterations;
  std::vector<int> pixel;

  void clear() {
    for (auto* v : {&zr, &zi, &cr, &ci}) v->clear();
    pixel.clear();
  }
  void add(std::complex<double> z0, std::complex<double> c, int index) {
    zr.push_back(z0.real()), zi.push_back(z0.imag()), cr.push_back(c.real()), ci.push_back(c.imag());
    pixel.push_back(index);
  }
  void run(PointLoop loop, const detail::IterationLimits& limits) {
    iterations.resize(zr.size());
    norm2.resize(zr.size());
    loop({zr.data(), zi.data(), cr.data(), ci.data(), zr.size(), iterations.data(), norm2.data()}, limits);
  }
};

/// Rows per parallel task: small enough to balance the uneven cost of rows, large enough to keep lanes busy.
constexpr int kRowsPerTask = 4;

/// Runs the escape-time loop over every pixel of `view`; `julia_c` selects Julia (z0 = pixel) over Mandelbrot.
EscapeImage escape_image(const ComplexView& view, const EscapeOptions& options, const std::complex<double>* julia_c) {
  check_view(view);
  check_options(options);
  const PointLoop loop = point_loop(options.simd);
  const detail::IterationLimits limits{uint32_t(options.max_iterations), options.escape_radius * options.escape_radius};
  EscapeImage out{Image<uint32_t>(view.width, view.height), Image<float>(view.width, view.height),
                  options.max_iterations, options.escape_radius};
  const bool checks = options.interior_checks && julia_c == nullptr;
  tbb::enumerable_thread_specific<Batch> batches;  // one per worker thread
  // Deep zooms and large pictures take seconds to minutes: rows done, on stderr as the CLI's --progress says.
  Progress progress(julia_c ? "julia: escape times" : "mandelbrot: escape times", view.height);
  parallel_for(0, view.height, kRowsPerTask, [&](int64_t y0, int64_t y1) {
    Batch& batch = batches.local();  // reused from strip to strip: no allocation per task once it has grown
    batch.clear();
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < view.width; ++x) {
        const std::complex<double> p = view.pixel_center(x, y);
        if (checks && in_cardioid_or_bulb(p)) {
          out.iterations(x, y) = limits.max_iterations;
          out.norm2(x, y) = 0;
        } else if (julia_c) {
          batch.add(p, *julia_c, y * view.width + x);
        } else {
          batch.add(0.0, p, y * view.width + x);
        }
      }
    batch.run(loop, limits);
    for (size_t i = 0; i < batch.pixel.size(); ++i) {
      out.iterations.pixels()[size_t(batch.pixel[i])] = batch.iterations[i];
      out.norm2.pixels()[size_t(batch.pixel[i])] = float(batch.norm2[i]);
    }
    progress.advance(y1 - y0);
  });
  return out;
}

}  // namespace

std::complex<double> ComplexView::pixel_center(int x, int y) const {
  const double h = pixel_size();
  return {center.real() + (x + 0.5 - 0.5 * width) * h, center.imag() - (y + 0.5 - 0.5 * height) * h};
}

bool simd_supported(SimdPath path) {
  switch (path) {
    case SimdPath::avx512:
      return cpu_features().avx512f && cpu_features().fma;
    case SimdPath::avx2:
      return cpu_features().avx2 && cpu_features().fma;
    default:
      return true;
  }
}

SimdPath best_simd_path() {
  if (simd_supported(SimdPath::avx512)) return SimdPath::avx512;
  if (simd_supported(SimdPath::avx2)) return SimdPath::avx2;
  return SimdPath::scalar;
}

std::string_view simd_name(SimdPath path) {
  switch (path) {
    case SimdPath::scalar:
      return "scalar";
    case SimdPath::avx2:
      return "avx2";
    case SimdPath::avx512:
      return "avx512";
    default:
      return "auto";
  }
}

SimdPath parse_simd_path(std::string_view name) {
  for (SimdPath p : {SimdPath::automatic, SimdPath::scalar, SimdPath::avx2, SimdPath::avx512})
    if (simd_name(p) == name) return p;
  throw InvalidInput(fmt::format("unknown SIMD path '{}' (auto, scalar, avx2, avx512)", name));
}

EscapeImage mandelbrot(const ComplexView& view, const EscapeOptions& options) {
  return escape_image(view, options, nullptr);
}

EscapeImage julia(std::complex<double> c, const ComplexView& view, const EscapeOptions& options) {
  if (!std::isfinite(c.real()) || !std::isfinite(c.imag())) throw InvalidInput("julia: c must be finite");
  return escape_image(view, options, &c);
}

bool julia_is_connected(std::complex<double> c, int max_iterations) {
  std::complex<double> z = 0;
  for (int n = 0; n < max_iterations; ++n) {
    z = z * z + c;
    if (std::norm(z) > 4) return false;
  }
  return true;
}

bool in_cardioid_or_bulb(std::complex<double> c) {
  const double x = c.real(), y = c.imag();
  const double xq = x - 0.25;
  const double q = xq * xq + y * y;
  if (q * (q + xq) <= 0.25 * y * y) return true;  // main cardioid
  return (x + 1) * (x + 1) + y * y <= 0.0625;     // period-2 bulb: |c + 1| <= 1/4
}

uint64_t iteration_count(const EscapeImage& image) {
  uint64_t total = 0;
  for (uint32_t n : image.iterations.pixels()) total += n;
  return total;
}

double mandelbrot_area(int size, const EscapeOptions& options) {
  if (size < 2 || size % 2 != 0 || size > 65536)
    throw InvalidInput(fmt::format("area grid size must be even and in [2, 65536], got {}", size));
  check_options(options);
  const PointLoop loop = point_loop(options.simd);
  const detail::IterationLimits limits{uint32_t(options.max_iterations), options.escape_radius * options.escape_radius};
  const ComplexView view{{-0.75, 0.0}, 2.5, size, size};
  std::atomic<int64_t> inside{0};
  tbb::enumerable_thread_specific<Batch> batches;  // one per worker thread
  parallel_for(0, size / 2, kRowsPerTask, [&](int64_t y0, int64_t y1) {
    Batch& batch = batches.local();
    batch.clear();
    int64_t count = 0;
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < size; ++x) {
        const std::complex<double> c = view.pixel_center(x, y);
        if (options.interior_checks && in_cardioid_or_bulb(c))
          ++count;
        else
          batch.add(0.0, c, 0);
      }
    batch.run(loop, limits);
    count += std::count(batch.iterations.begin(), batch.iterations.end(), limits.max_iterations);
    inside += count;
  });
  const double h = view.pixel_size();
  return 2.0 * double(inside.load()) * h * h;
}

}  // namespace tessera
