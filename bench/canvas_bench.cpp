// Canvas benchmarks: lines per second (the notes' DDA, Bresenham, Wu; short and long) and filled pixels per second
// of the scanline rasterizer (one large concave polygon, many small triangles; aliased and antialiased).
//
//   ninja -C build/release bench_canvas && build/release/bench/bench_canvas
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "tessera/raster2d/lines.hpp"
#include "tessera/raster2d/path.hpp"

namespace {

using namespace tessera;

constexpr int kSize = 1024;

// Lines of a given length at random angles and positions inside a kSize x kSize image, plotted into it.
void lines(benchmark::State& state, LineAlgorithm algorithm) {
  const double length = double(state.range(0));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> pos(length, kSize - length), angle(0, 2 * kPi);
  std::vector<std::pair<Vec2, Vec2>> segments(4096);
  for (auto& [a, b] : segments) {
    a = {pos(rng), pos(rng)};
    const double t = angle(rng);
    b = a + length * Vec2(std::cos(t), std::sin(t));
  }
  ImageRGBA image(kSize, kSize, Vec4f(0, 0, 0, 1));
  size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = segments[i++ % segments.size()];
    draw_line(image, a, b, Vec4f(1, 1, 1, 0.5f), algorithm);
  }
  benchmark::DoNotOptimize(image.pixels().data());
  state.counters["lines/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["pixels/s"] =
      benchmark::Counter(double(state.iterations()) * length, benchmark::Counter::kIsRate);  // ~ major-axis steps
}

void BM_LineDda(benchmark::State& state) { lines(state, LineAlgorithm::dda); }
void BM_LineBresenham(benchmark::State& state) { lines(state, LineAlgorithm::bresenham); }
void BM_LineWu(benchmark::State& state) { lines(state, LineAlgorithm::wu); }
BENCHMARK(BM_LineDda)->Arg(10)->Arg(500);
BENCHMARK(BM_LineBresenham)->Arg(10)->Arg(500);
BENCHMARK(BM_LineWu)->Arg(10)->Arg(500);

// A large concave star with a hole covering much of a 2048 x 2048 image; pixels/s counts the covered pixels.
void BM_FillLargePolygon(benchmark::State& state) {
  const bool antialias = state.range(0) != 0;
  const int size = 2048;
  Path path;
  path.contours.emplace_back();
  for (int i = 0; i < 64; ++i) {
    const double a = 2 * kPi * i / 64, r = i % 2 ? 700 : 1000;
    path.contours[0].push_back({1024 + r * std::cos(a), 1024 + r * std::sin(a)});
  }
  path.contours.emplace_back();
  for (int i = 0; i < 32; ++i) {
    const double a = -2 * kPi * i / 32;
    path.contours[1].push_back({1024 + 300 * std::cos(a), 1024 + 300 * std::sin(a)});
  }
  ImageRGBA image(size, size, Vec4f(0));
  fill_path(image, path, FillRule::non_zero, Vec4f(1), antialias);
  double covered = 0;
  for (const Vec4f& p : image.pixels()) covered += p.w;
  for (auto _ : state) fill_path(image, path, FillRule::non_zero, Vec4f(0.2f, 0.5f, 0.9f, 0.8f), antialias);
  state.counters["pixels/s"] = benchmark::Counter(double(state.iterations()) * covered, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FillLargePolygon)->ArgName("aa")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Many small random triangles (about 50 pixels each) in a 1024 x 1024 image, one fill_path call each.
void BM_FillSmallTriangles(benchmark::State& state) {
  const bool antialias = state.range(0) != 0;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> pos(0, kSize - 12), off(0, 12);
  std::vector<Path> tris(4096);
  for (Path& t : tris) {
    const Vec2 o(pos(rng), pos(rng));
    t.contours = {{o + Vec2(off(rng), off(rng)), o + Vec2(off(rng), off(rng)), o + Vec2(off(rng), off(rng))}};
  }
  ImageRGBA image(kSize, kSize, Vec4f(0));
  double area = 0;
  for (const Path& t : tris) {
    const auto& c = t.contours[0];
    area += 0.5 * std::fabs((c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[2].x - c[0].x) * (c[1].y - c[0].y));
  }
  size_t i = 0;
  for (auto _ : state) fill_path(image, tris[i++ % tris.size()], FillRule::non_zero, Vec4f(1, 0.5f, 0, 1), antialias);
  state.counters["triangles/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["pixels/s"] =
      benchmark::Counter(double(state.iterations()) * area / double(tris.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FillSmallTriangles)->ArgName("aa")->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
