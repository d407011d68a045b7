// Color conversions per second: every ordered pair of models (tessera::convert_many on 1M colors), and the direct
// RGB -> model functions. The peer, Python's colorsys, is timed once in a python3 subprocess at start-up and shown in
// the context header as CPU nanoseconds per value (skipped when there is no python3); items_per_second below are
// per CPU second too, so the two compare under any machine load. docs/color.md quotes the figures.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "tessera/color/color.hpp"
#include "tessera/color/model.hpp"

namespace {

using tessera::ColorModel;

constexpr size_t kColors = 1 << 20;

// 1M colors in model `m`: random RGB in [0, 1]^3 converted into m (so every input is a valid color of m).
const std::vector<double>& inputs(ColorModel m) {
  static std::vector<std::vector<double>> cache(tessera::kColorModels.size());
  std::vector<double>& values = cache[size_t(m)];
  if (values.empty()) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> rgb(kColors * 3);
    for (double& v : rgb) v = u(rng);
    values.resize(kColors * size_t(tessera::component_count(m)));
    tessera::convert_many(ColorModel::rgb, m, rgb, values);
  }
  return values;
}

void BM_convert(benchmark::State& state) {
  const auto from = ColorModel(state.range(0)), to = ColorModel(state.range(1));
  const std::vector<double>& in = inputs(from);
  std::vector<double> out(kColors * size_t(tessera::component_count(to)));
  for (auto _ : state) {
    tessera::convert_many(from, to, in, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kColors));
  state.SetLabel(std::string(tessera::model_name(from)) + "->" + std::string(tessera::model_name(to)));
}

void every_pair(benchmark::internal::Benchmark* b) {
  for (ColorModel from : tessera::kColorModels)
    for (ColorModel to : tessera::kColorModels)
      if (from != to) b->Args({int64_t(from), int64_t(to)});
}
BENCHMARK(BM_convert)->Apply(every_pair)->Unit(benchmark::kMillisecond)->MinTime(0.2);

// The direct functions, without the model table: the cost of the formulas alone.
template <tessera::Vec3 (*F)(const tessera::Vec3&)>
void BM_direct(benchmark::State& state) {
  const std::vector<double>& in = inputs(ColorModel::rgb);
  std::vector<tessera::Vec3> out(kColors);
  for (auto _ : state) {
    for (size_t i = 0; i < kColors; ++i) out[i] = F(tessera::Vec3(in[3 * i], in[3 * i + 1], in[3 * i + 2]));
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kColors));
}
BENCHMARK(BM_direct<tessera::rgb_to_hsv>)->Name("BM_direct/rgb_to_hsv")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_direct<tessera::rgb_to_hls>)->Name("BM_direct/rgb_to_hls")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_direct<tessera::rgb_to_yiq>)->Name("BM_direct/rgb_to_yiq")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_direct<tessera::hsv_to_rgb>)->Name("BM_direct/hsv_to_rgb")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_direct<tessera::rgb_to_xyz>)->Name("BM_direct/rgb_to_xyz")->Unit(benchmark::kMillisecond);

// Times colorsys's functions on 100k random colors in a python3 subprocess: "name ns_per_value" lines.
void add_colorsys_context() {
  const char* script =
      "import colorsys, random, time, timeit\n"
      "random.seed(1)\n"
      "v = [(random.random(), random.random(), random.random()) for _ in range(100000)]\n"
      "for n in ('rgb_to_hsv', 'hsv_to_rgb', 'rgb_to_hls', 'hls_to_rgb', 'rgb_to_yiq', 'yiq_to_rgb'):\n"
      "    f = getattr(colorsys, n)\n"
      "    t = min(timeit.repeat(lambda: [f(*c) for c in v], number=1, repeat=3, timer=time.process_time))\n"
      "    print(n, round(t / len(v) * 1e9, 1))\n";
  FILE* python = popen(("command -v python3 >/dev/null && python3 -c \"" + std::string(script) + "\"").c_str(), "r");
  if (!python) return;
  char name[64];
  double ns = 0;
  while (std::fscanf(python, "%63s %lf", name, &ns) == 2)
    benchmark::AddCustomContext(std::string("colorsys.") + name, std::to_string(ns) + " ns/value");
  pclose(python);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  add_colorsys_context();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
