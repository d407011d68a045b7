// Escape-time speed (Mandelbrot and Julia, iterations per second) on every SIMD path the CPU has, on 1 and 2
// threads, against the floating-point limit of the same machine measured in the same run: independent FMA chains of
// the same vector width. At the end a table gives each path's share of that limit and its 2-thread scaling.
//
// Flops per iteration, counted honestly: z^2 + c is x^2, y^2, xy (3 mul) and x^2 - y^2 + cx, 2xy + cy (4 add); the
// escape test adds |z|^2 = x^2 + y^2 (1 add) and a compare (not counted): 8 flops. The loop issues them as
// 1 mul + 2 add + 3 fma (+ 1 compare). An FMA counts 2 flops in the peak.
//
//   cmake -S . -B build/bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_BENCH=ON
//   ninja -C build/bench bench_fractal && build/bench/bench/bench_fractal
#include <benchmark/benchmark.h>
#include <immintrin.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/fractal/escape_time.hpp"

namespace {

using tessera::SimdPath;

constexpr double kFlopsPerIteration = 8;
constexpr int64_t kChainSteps = 1 << 20;

// Independent multiply-add chains acc = acc * m + a (they converge, so no overflow or denormals): 12 accumulators
// for scalar and AVX2 (16 registers), 24 for AVX-512 (32 registers) cover latency x pipes on current cores.
__attribute__((target("fma"))) double chains_scalar(int64_t steps) {
  double acc[12];
  for (int k = 0; k < 12; ++k) acc[k] = 1.0 + k;
  for (int64_t i = 0; i < steps; ++i)
#pragma GCC unroll 12
    for (int k = 0; k < 12; ++k) acc[k] = __builtin_fma(acc[k], 0.999999, 1e-7);
  double s = 0;
  for (double a : acc) s += a;
  return s;
}

__attribute__((target("avx2,fma"))) double chains_avx2(int64_t steps) {
  __m256d acc[12];
  for (int k = 0; k < 12; ++k) acc[k] = _mm256_set1_pd(1.0 + k);
  const __m256d m = _mm256_set1_pd(0.999999), a = _mm256_set1_pd(1e-7);
  for (int64_t i = 0; i < steps; ++i)
#pragma GCC unroll 12
    for (int k = 0; k < 12; ++k) acc[k] = _mm256_fmadd_pd(acc[k], m, a);
  __m256d s = acc[0];
  for (int k = 1; k < 12; ++k) s = _mm256_add_pd(s, acc[k]);
  alignas(32) double out[4];
  _mm256_store_pd(out, s);
  return out[0] + out[1] + out[2] + out[3];
}

__attribute__((target("avx512f,fma"))) double chains_avx512(int64_t steps) {
  __m512d acc[24];
  for (int k = 0; k < 24; ++k) acc[k] = _mm512_set1_pd(1.0 + k);
  const __m512d m = _mm512_set1_pd(0.999999), a = _mm512_set1_pd(1e-7);
  for (int64_t i = 0; i < steps; ++i)
#pragma GCC unroll 24
    for (int k = 0; k < 24; ++k) acc[k] = _mm512_fmadd_pd(acc[k], m, a);
  __m512d s = acc[0];
  for (int k = 1; k < 24; ++k) s = _mm512_add_pd(s, acc[k]);
  return _mm512_reduce_add_pd(s);
}

struct Chains {
  double (*run)(int64_t);
  int lanes, accumulators;
};

Chains chains(SimdPath path) {
  switch (path) {
    case SimdPath::avx512:
      return {chains_avx512, 8, 24};
    case SimdPath::avx2:
      return {chains_avx2, 4, 12};
    default:
      return {chains_scalar, 1, 12};
  }
}

// Peak double-precision flops of one core at the path's width.
void BM_FpPeak(benchmark::State& state, SimdPath path) {
  const Chains c = chains(path);
  for (auto _ : state) benchmark::DoNotOptimize(c.run(kChainSteps));
  const double flops = 2.0 * c.lanes * c.accumulators * double(kChainSteps);
  state.counters["flop/s"] = benchmark::Counter(flops * double(state.iterations()), benchmark::Counter::kIsRate);
}

struct Workload {
  const char* name;
  bool julia;
  tessera::ComplexView view;
  std::complex<double> c;
};

// Seahorse valley (a wide spread of escape times, some interior) and Douady's rabbit (c = -0.123 + 0.745i, a
// connected Julia set whose interior runs to the cap).
const Workload kWorkloads[] = {
    {"mandelbrot", false, {{-0.7453, 0.1127}, 0.02, 640, 480}, {}},
    {"julia", true, {{0.0, 0.0}, 3.2, 640, 480}, {-0.123, 0.745}},
};

void BM_Escape(benchmark::State& state, const Workload& w, SimdPath path, int threads) {
  const tessera::ThreadLimit limit(threads);
  tessera::EscapeOptions options;
  options.max_iterations = 2000;
  options.interior_checks = false;  // every counted iteration is computed
  options.simd = path;
  uint64_t iterations = 0;
  for (auto _ : state) {
    const tessera::EscapeImage image =
        w.julia ? tessera::julia(w.c, w.view, options) : tessera::mandelbrot(w.view, options);
    iterations += tessera::iteration_count(image);
    benchmark::DoNotOptimize(image.iterations.pixels().data());
  }
  state.counters["iter/s"] = benchmark::Counter(double(iterations), benchmark::Counter::kIsRate);
}

// Keeps every run's rate counter for the summary.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs)
      for (const char* key : {"flop/s", "iter/s"})
        if (auto it = run.counters.find(key); it != run.counters.end()) rates[run.run_name.function_name] = it->second;
  }
  std::map<std::string, double> rates;
};

std::string name(const char* what, SimdPath path, int threads = 1) {
  return std::string(what) + "/" + std::string(tessera::simd_name(path)) + "/threads:" + std::to_string(threads);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<SimdPath> paths;
  for (SimdPath p : {SimdPath::scalar, SimdPath::avx2, SimdPath::avx512})
    if (tessera::simd_supported(p)) paths.push_back(p);
  for (SimdPath p : paths) {
    benchmark::RegisterBenchmark(name("fp_peak", p).c_str(), BM_FpPeak, p)->Unit(benchmark::kMillisecond);
    for (const Workload& w : kWorkloads) {
      // One thread on CPU time (the share of the FP peak, robust on a shared machine: TBB runs a 1-thread limit
      // on the calling thread), then 1 and 2 threads on wall time (the scaling).
      benchmark::RegisterBenchmark(name(w.name, p).append("/cpu").c_str(), BM_Escape, w, p, 1)
          ->Unit(benchmark::kMillisecond)
          ->MinTime(0.5);
      for (int threads : {1, 2})
        benchmark::RegisterBenchmark(name(w.name, p, threads).c_str(), BM_Escape, w, p, threads)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(0.5);
    }
  }
  benchmark::Initialize(&argc, argv);
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  const double load = tessera::bench::load_average();
  std::printf(
      "\nper core (CPU time): peak = FMA chains, share = 8 flops x iter/s / peak; scaling on wall time "
      "(load average %.1f)\n",
      load);
  std::printf("%-10s %-7s %12s %12s %10s %14s %14s %9s\n", "workload", "path", "peak Gflop/s", "Giter/s", "of peak",
              "wall 1T Git/s", "wall 2T Git/s", "2T scale");
  for (SimdPath p : paths) {
    const double peak = reporter.rates[name("fp_peak", p)];
    for (const Workload& w : kWorkloads) {
      const double cpu = reporter.rates[name(w.name, p).append("/cpu")];
      const double one = reporter.rates[name(w.name, p, 1)], two = reporter.rates[name(w.name, p, 2)];
      if (peak <= 0 || cpu <= 0 || one <= 0) continue;
      std::printf("%-10s %-7s %12.2f %12.3f %9.1f%% %14.3f %14.3f %8.2fx\n", w.name,
                  std::string(tessera::simd_name(p)).c_str(), peak * 1e-9, cpu * 1e-9,
                  100.0 * cpu * kFlopsPerIteration / peak, one * 1e-9, two * 1e-9, two / one);
    }
  }
  benchmark::Shutdown();
  return 0;
}
