// The viewer's frame rate: `tessera view`'s Viewer run headless by the sketch runner over a turntable of the Stanford
// bunny (69,451 triangles, from TESSERA_SHARED_DATA) at 1280 x 720 on 2 threads, one benchmark per shading mode (the
// issue asks for at least 30 frames per second). Each iteration runs a 30-frame turntable; `frames_per_s` counts
// frames over the wall time of the runs (setup included), `render_frames_per_s` over the viewer's own render time.
//
//   cmake -S . -B build/bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_BENCH=ON
//   ninja -C build/bench bench_view && build/bench/bench/bench_view
//
// The same figure from the command line: tessera view bun_zipper.ply --headless --orbit 60 --stats --threads 2.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "bench_util.hpp"
#include "tessera/sketch/runner.hpp"
#include "tessera/view/viewer.hpp"

namespace {

using namespace tessera;

constexpr int kFrames = 30;

const Viewable* bunny() {
  static const std::optional<Viewable> v = []() -> std::optional<Viewable> {
    const std::filesystem::path path = std::filesystem::path(TESSERA_SHARED_DATA) / "meshes/bunny/bun_zipper.ply";
    if (!std::filesystem::exists(path)) return std::nullopt;
    return read_viewable(path.string());
  }();
  return v ? &*v : nullptr;
}

void BM_ViewBunny(benchmark::State& state) {
  const Viewable* v = bunny();
  if (!v) {
    state.SkipWithError("no bunny in TESSERA_SHARED_DATA");
    return;
  }
  ViewerOptions options;
  options.shading = ViewShading(state.range(0));
  options.orbit_frames = kFrames;
  RunOptions run;
  run.frames = kFrames;
  run.threads = 2;
  double render_seconds = 0;
  int renders = 0;
  for (auto _ : state) {
    Viewer viewer(*v, options);
    run_sketch(viewer, run);
    render_seconds += viewer.stats().render_seconds;
    renders += viewer.stats().renders;
  }
  state.SetLabel(std::string(shading_name(options.shading)));
  state.counters["frames_per_s"] = benchmark::Counter(double(kFrames), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["render_frames_per_s"] = renders / render_seconds;
  state.counters["load"] = bench::load_average();
}
BENCHMARK(BM_ViewBunny)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
