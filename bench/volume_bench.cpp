// Marching cubes (classic and topological, extract_iso_surface: float output as the peers') on 256^3 and 512^3 float
// fields, on 1 and 2 threads, against VTK's vtkFlyingEdges3D and vtkMarchingCubes and scikit-image's
// marching_cubes(method='lorensen') on the same field in the same run; and direct volume rendering (256^3 at
// 512 x 512; render_volume and a prepared VolumeRenderer) against VTK's fixed-point ray cast mapper where it can run
// (under xvfb-run; TESSERA_DVR_IMAGE_DIR=dir writes both pictures there). The peers run in a /usr/bin/python3
// subprocess (bench/peers/volume_peers.py) on the field written to /tmp as raw float32; they report their best wall
// time of a few runs. A table at the end gives the speedups (peer ms / Tessera ms), the triangle counts and the load
// average.
//
//   cmake -S . -B build/h-vbench -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_BENCH=ON -DTESSERA_BUILD_TESTS=OFF
//   ninja -C build/h-vbench bench_volume && build/h-vbench/bench/bench_volume
//
// TESSERA_VOLUME_BENCH_SIZES=256 (comma-separated) limits the sizes; the 512^3 peers run their slow members once.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_util.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/procedural.hpp"
#include "tessera/volume/volume_render.hpp"

namespace {

using namespace tessera;
using bench::load_average;
using bench::process_cpu_seconds;

// Where the peers' script lies: next to this file in the source tree (CMake passes absolute source paths).
const std::filesystem::path kPeersScript = std::filesystem::path(__FILE__).parent_path() / "peers" / "volume_peers.py";
constexpr const char* kPython = "/usr/bin/python3";  // Debian's, with python3-vtk9 and python3-skimage

// Fields with a realistic surface density: a gyroid with 8 periods across the grid (32 voxels per period at 256^3,
// a dense porous surface) and 4-octave value noise (CT-like clutter, finest octave ~4 voxels per lattice cell at
// 256^3).
struct FieldSpec {
  const char* name;
  float iso;
  Volume<float> (*make)(int);
};
const FieldSpec kFields[] = {
    {"gyroid", 0.0f, [](int n) { return make_gyroid(n, 8); }},
    {"noise", 0.0f, [](int n) { return make_noise(n, 1); }},
};

// One field at a time is kept (a 512^3 field is 512 MiB), with its raw file for the peers.
struct Field {
  std::string key;
  Volume<float> volume;
  std::filesystem::path raw;
};
Field g_field;

const Volume<float>& field(const FieldSpec& spec, int n, bool with_raw) {
  const std::string key = fmt::format("{}-{}", spec.name, n);
  if (g_field.key != key) {
    if (!g_field.raw.empty()) std::filesystem::remove(g_field.raw);
    g_field = {key, Volume<float>(), {}};
    g_field.volume = spec.make(n);
  }
  if (with_raw && g_field.raw.empty()) {
    g_field.raw = std::filesystem::temp_directory_path() / fmt::format("tessera_volume_bench_{}_{}.f32", getpid(), key);
    std::ofstream out(g_field.raw, std::ios::binary);
    const auto voxels = g_field.volume.voxels();  // x fastest, little-endian on the machines this runs on
    out.write(reinterpret_cast<const char*>(voxels.data()), std::streamsize(voxels.size_bytes()));
  }
  return g_field.volume;
}

// Results for the final table, keyed by "field size".
struct Timing {
  double ms = 0, cpu_ms = 0;
  size_t tris = 0;
  std::string note;  // peers: backend and threads used
  bool ok = false;
};
struct Group {
  double load_before = 0, load_after = 0;
  std::map<std::string, Timing> runs;  // "classic/1", "topological/2", "vtk_flying_edges/2", ...
};
std::map<std::string, Group> g_groups;
std::vector<std::string> g_order;

Group& group(const std::string& key) {
  if (!g_groups.count(key)) g_order.push_back(key);
  return g_groups[key];
}

void tessera_mc(benchmark::State& state, const FieldSpec& spec, int n, bool topological, int threads) {
  const Volume<float>& volume = field(spec, n, false);
  Group& g = group(fmt::format("{} {}", spec.name, n));
  if (g.runs.empty()) g.load_before = load_average();
  const ThreadLimit limit(threads);
  const MarchingCubesOptions options{.iso = spec.iso, .topological = topological};
  Timing best{.ms = std::numeric_limits<double>::infinity()};
  for (auto _ : state) {
    const double cpu0 = process_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    // extract_iso_surface: float positions and normals and 3 indices a triangle, as the peers output.
    const IsoSurface mesh = extract_iso_surface(volume, options);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = process_cpu_seconds() - cpu0;
    state.SetIterationTime(wall);  // the mesh is freed outside the timed part, as the peers' outputs are
    if (wall * 1e3 < best.ms) best = {wall * 1e3, cpu * 1e3, mesh.triangle_count(), "", true};
    benchmark::DoNotOptimize(mesh.positions.data());
  }
  state.counters["tris"] = double(best.tris);
  state.counters["best_ms"] = best.ms;
  state.counters["cpu_ms"] = best.cpu_ms;
  g.runs[fmt::format("{}/{}", topological ? "topological" : "classic", threads)] = best;
  g.load_after = load_average();
}

// Runs the peers' script and parses its key=value line. Returns false (with `error`) when it did not run.
bool run_peer_script(const std::string& args, std::map<std::string, std::string>& values, std::string& error) {
  const std::string command = fmt::format("{} {} {} 2>&1", kPython, kPeersScript.string(), args);
  std::string output;
  const int status = bench::run_command(command, output);
  if (status == -1) {
    error = "popen failed";
    return false;
  }
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("peer=", 0) == 0) {
      std::istringstream words(line);
      for (std::string word; words >> word;)
        if (const size_t eq = word.find('='); eq != std::string::npos) values[word.substr(0, eq)] = word.substr(eq + 1);
    }
  if (status != 0 || values.empty()) {
    error = fmt::format("peer failed (status {}): {}", status, output.substr(0, 300));
    return false;
  }
  return true;
}

void peer_mc(benchmark::State& state, const FieldSpec& spec, int n, const std::string& peer, int threads, int repeat) {
  field(spec, n, true);
  Group& g = group(fmt::format("{} {}", spec.name, n));
  std::map<std::string, std::string> v;
  std::string error;
  Timing t;
  for (auto _ : state) {
    const bool ok = run_peer_script(
        fmt::format("mc {} {} {} {} {} {} {} {}", g_field.raw.string(), n, n, n, spec.iso, peer, threads, repeat), v,
        error);
    if (!ok) {
      static std::string message;  // SkipWithError keeps the pointer
      message = error;
      state.SkipWithError(message.c_str());
      return;
    }
    t = {std::stod(v["best_ms"]), std::stod(v["cpu_ms"]), size_t(std::stoull(v["tris"])),
         fmt::format("{} backend, {} thread(s)", v["backend"], v["threads"]), true};
    state.SetIterationTime(t.ms / 1e3);
  }
  state.counters["tris"] = double(t.tris);
  state.counters["best_ms"] = t.ms;
  state.counters["cpu_ms"] = t.cpu_ms;
  state.counters["threads"] = std::stod(v["threads"]);
  state.SetLabel(t.note);
  g.runs[fmt::format("{}/{}", peer, threads)] = t;
  g.load_after = load_average();
}

// Direct volume rendering: the noise field seen from a corner, a translucent transfer function (clear below 0), the
// default step (half a voxel), shading and empty-space skipping on.
constexpr int kDvrSize = 256, kDvrImage = 512;
const FieldSpec& dvr_field() { return kFields[1]; }

VolumeRenderOptions dvr_options() {
  VolumeRenderOptions o;
  o.camera.eye = {2.2, 1.6, 2.8};
  o.camera.center = {0, 0, 0};
  o.camera.up = {0, 1, 0};
  o.camera.fovy = radians(40.0);
  o.width = o.height = kDvrImage;
  o.transfer = TransferFunction(
      {{0.0f, {0.9f, 0.6f, 0.4f}, 0.0f}, {0.2f, {0.9f, 0.6f, 0.4f}, 0.5f}, {0.6f, {1.0f, 1.0f, 0.9f}, 1.0f}});
  return o;
}

// `prepared`: the volume is prepared once (VolumeRenderer) and only the renders are timed, as VTK's renders are
// (its mapper keeps its gradients between renders); otherwise render_volume(), preparation included.
void tessera_dvr(benchmark::State& state, int threads, bool prepared) {
  const Volume<float>& volume = field(dvr_field(), kDvrSize, false);
  Group& g = group(fmt::format("dvr {}", kDvrSize));
  if (g.runs.empty()) g.load_before = load_average();
  const ThreadLimit limit(threads);
  const VolumeRenderOptions options = dvr_options();
  std::optional<VolumeRenderer> renderer;  // prepared outside the timing, and only where it is used
  if (prepared) renderer.emplace(volume);
  Timing best{.ms = std::numeric_limits<double>::infinity()};
  for (auto _ : state) {
    const double cpu0 = process_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    const ImageRGB image = prepared ? renderer->render(options) : render_volume(volume, options);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(wall);
    if (wall * 1e3 < best.ms) best = {wall * 1e3, (process_cpu_seconds() - cpu0) * 1e3, 0, "", true};
    benchmark::DoNotOptimize(image.row(0));
  }
  state.counters["best_ms"] = best.ms;
  state.counters["cpu_ms"] = best.cpu_ms;
  const char* dir = std::getenv("TESSERA_DVR_IMAGE_DIR");  // the peer writes its picture there too
  if (dir && prepared)  // both variants render the same image (tested): write it once
    write_image(std::filesystem::path(dir) / fmt::format("dvr_tessera_{}.png", threads), renderer->render(options));
  g.runs[fmt::format("{}/{}", prepared ? "prepared" : "render", threads)] = best;
  g.load_after = load_average();
}

void peer_dvr(benchmark::State& state, int threads) {
  field(dvr_field(), kDvrSize, true);
  Group& g = group(fmt::format("dvr {}", kDvrSize));
  const double step = 0.5 * 2.0 / (kDvrSize - 1);  // Tessera's default step: half the spacing
  std::map<std::string, std::string> v;
  std::string error;
  for (auto _ : state) {
    if (!run_peer_script(fmt::format("dvr {} {} {} {} {} {} {} {} 3", g_field.raw.string(), kDvrSize, kDvrSize,
                                     kDvrSize, kDvrImage, kDvrImage, step, threads),
                         v, error) ||
        v.count("status")) {
      static std::string message;
      message = v.count("reason") ? "vtkFixedPointVolumeRayCastMapper did not run: " + v["reason"] : error;
      g.runs[fmt::format("vtk_fixed_point_ray_cast/{}", threads)] = {.note = message};
      state.SkipWithError(message.c_str());
      return;
    }
    state.SetIterationTime(std::stod(v["best_ms"]) / 1e3);
  }
  g.runs[fmt::format("vtk_fixed_point_ray_cast/{}", threads)] = {std::stod(v["best_ms"]), std::stod(v["cpu_ms"]), 0,
                                                                 fmt::format("{} backend", v["backend"]), true};
  state.counters["best_ms"] = std::stod(v["best_ms"]);
}

std::vector<int> bench_sizes() {
  std::vector<int> sizes;
  const char* env = std::getenv("TESSERA_VOLUME_BENCH_SIZES");
  std::istringstream in(env ? env : "256,512");
  for (std::string s; std::getline(in, s, ',');) sizes.push_back(std::stoi(s));
  return sizes;
}

void register_all() {
  for (int n : bench_sizes())
    for (const FieldSpec& spec : kFields) {
      // Tessera and its peers back to back on the same field, so that they see about the same machine load.
      const int iterations = n >= 512 ? 3 : 5, slow_repeat = n >= 512 ? 1 : 2;
      for (const bool topological : {false, true})
        for (const int threads : {1, 2})
          benchmark::RegisterBenchmark(
              fmt::format("mc/tessera_{}/{}/{}/threads:{}", topological ? "topological" : "classic", spec.name, n,
                          threads)
                  .c_str(),
              [=, &spec](benchmark::State& s) { tessera_mc(s, spec, n, topological, threads); })
              ->Iterations(iterations)
              ->UseManualTime()
              ->Unit(benchmark::kMillisecond);
      const struct {
        const char* peer;
        int threads, repeat;
      } peers[] = {{"vtk_flying_edges", 1, iterations},
                   {"vtk_flying_edges", 2, iterations},
                   {"vtk_marching_cubes", 1, slow_repeat},
                   {"skimage_lorensen", 1, slow_repeat}};
      for (const auto& p : peers)
        benchmark::RegisterBenchmark(
            fmt::format("mc/{}/{}/{}/threads:{}", p.peer, spec.name, n, p.threads).c_str(),
            [=, &spec](benchmark::State& s) { peer_mc(s, spec, n, p.peer, p.threads, p.repeat); })
            ->Iterations(1)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
    }
  for (const int threads : {1, 2}) {
    for (const bool prepared : {false, true})
      benchmark::RegisterBenchmark(fmt::format("dvr/tessera{}/noise/{}/{}x{}/threads:{}", prepared ? "_prepared" : "",
                                               kDvrSize, kDvrImage, kDvrImage, threads)
                                       .c_str(),
                                   [=](benchmark::State& s) { tessera_dvr(s, threads, prepared); })
          ->Iterations(3)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(
        fmt::format("dvr/vtk_fixed_point_ray_cast/noise/{}/{}x{}/threads:{}", kDvrSize, kDvrImage, kDvrImage, threads)
            .c_str(),
        [=](benchmark::State& s) { peer_dvr(s, threads); })
        ->Iterations(1)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
}

std::string ratio(const Group& g, const std::string& peer, const std::string& ours) {
  const auto p = g.runs.find(peer), t = g.runs.find(ours);
  if (p == g.runs.end() || t == g.runs.end() || !p->second.ok || !t->second.ok) return "—";
  return fmt::format("{:.2f}x (cpu {:.2f}x)", p->second.ms / t->second.ms, p->second.cpu_ms / t->second.cpu_ms);
}

void print_summary() {
  std::printf("\nSpeedup = peer best wall ms / Tessera best wall ms (cpu: the same with process CPU time). %d cores.\n",
              int(std::thread::hardware_concurrency()));
  for (const std::string& key : g_order) {
    const Group& g = g_groups.at(key);
    std::printf("\n== %s   (load average %.2f before, %.2f after)\n", key.c_str(), g.load_before, g.load_after);
    for (const auto& [name, t] : g.runs) {
      if (t.ok)
        std::printf("  %-28s %10.1f ms  cpu %10.1f ms  %s  %s\n", name.c_str(), t.ms, t.cpu_ms,
                    t.tris ? fmt::format("tris {:10}", t.tris).c_str() : "", t.note.c_str());
      else
        std::printf("  %-28s %s\n", name.c_str(), t.note.c_str());
    }
    if (key.rfind("dvr", 0) == 0) {
      for (const char* th : {"1", "2"})
        std::printf("  %s thread(s) vs vtkFixedPointVolumeRayCastMapper: render_volume %s   prepared %s\n", th,
                    ratio(g, fmt::format("vtk_fixed_point_ray_cast/{}", th), fmt::format("render/{}", th)).c_str(),
                    ratio(g, fmt::format("vtk_fixed_point_ray_cast/{}", th), fmt::format("prepared/{}", th)).c_str());
      continue;
    }
    for (const char* th : {"1", "2"}) {
      const std::string ours = fmt::format("classic/{}", th);
      std::printf("  classic %s thread(s):  vs vtkFlyingEdges3D (%s thr) %s   vs vtkMarchingCubes %s   vs skimage %s\n",
                  th, th, ratio(g, fmt::format("vtk_flying_edges/{}", th), ours).c_str(),
                  ratio(g, "vtk_marching_cubes/1", ours).c_str(), ratio(g, "skimage_lorensen/1", ours).c_str());
    }
    const auto tris = [&](const std::string& name) {
      const auto it = g.runs.find(name);
      return it != g.runs.end() && it->second.ok ? fmt::format("{}", it->second.tris) : std::string("—");
    };
    std::printf(
        "  triangles: classic %s  vtkMarchingCubes %s  vtkFlyingEdges3D %s  skimage lorensen %s  topological %s\n",
        tris("classic/1").c_str(), tris("vtk_marching_cubes/1").c_str(), tris("vtk_flying_edges/2").c_str(),
        tris("skimage_lorensen/1").c_str(), tris("topological/1").c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  if (!g_field.raw.empty()) std::filesystem::remove(g_field.raw);
  return 0;
}
