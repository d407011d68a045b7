// Ray casting of triangle meshes: Tessera's MeshAccel (wide BVH collapsed from a binned-SAH tree) against Embree 3's
// rtcIntersect1 on the same mesh and rays in the same run. Incoherent rays (origins uniform in the mesh box scaled
// 1.1x, directions uniform on the sphere) and coherent primary rays (1024 x 1024 eye rays), on 1 thread, 2 threads and
// all threads; the incoherent rays also as streams (MeshAccel's span intersect against Embree's rtcIntersect1M, 1024
// rays a call); BVH build in Mprims/s against Embree's default (medium-quality) build. A table at the end gives the
// ratios Tessera / Embree from the median wall and process CPU times of the iterations, and both 2-thread scalings
// (wall).
//
//   cmake -S . -B build/h-accel -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_BENCH=ON
//   ninja -C build/h-accel bench_accel && build/h-accel/bench/bench_accel
//
// Meshes: the Stanford bunny (69K triangles, when TESSERA_SHARED_DATA has it) and a tessellated torus of 1.08M
// triangles.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <glm/geometric.hpp>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "embree_reference.hpp"
#include "tessera/accel/mesh_accel.hpp"
#include "tessera/accel/ray_workloads.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"

namespace {

using namespace tessera;

constexpr size_t kRandomRays = 1 << 20;
constexpr int kImage = 1024;

struct Workload {
  std::string name;
  TriMesh mesh;
  std::vector<Ray> random, primary;
  std::unique_ptr<MeshAccel> accel;
  std::unique_ptr<reference::EmbreeMesh> embree;
};

std::map<std::string, std::unique_ptr<Workload>> g_workloads;
/// "mesh/what/who/threads" -> rates from the median wall time and the median process CPU time of the iterations
/// (CPU time is the steadier measure on a loaded machine; wall time is what the 2-thread scaling needs).
struct Rates {
  double wall = 0, cpu = 0;
};
std::map<std::string, Rates> g_results;

/// Times one call: wall seconds and process CPU seconds (all threads).
template <class F>
std::pair<double, double> timed(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = bench::process_cpu_seconds();
  f();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
          bench::process_cpu_seconds() - cpu_start};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

Rates rates(double count, const std::vector<double>& wall, const std::vector<double>& cpu) {
  return {count / median(wall), count / median(cpu)};
}

Workload& workload(const std::string& name) {
  auto& slot = g_workloads[name];
  if (slot) return *slot;
  slot = std::make_unique<Workload>();
  Workload& w = *slot;
  w.name = name;
  if (name == "bunny") {
    w.mesh = to_tri_mesh(read_mesh(std::filesystem::path(TESSERA_SHARED_DATA) / "meshes/bunny/bun_zipper.ply"));
  } else {
    w.mesh = to_tri_mesh(make_torus(1.0, 0.4, 1200, 450));
  }
  AABB box;
  for (const Vec3& p : w.mesh.positions) box.expand(Vec3f(p));
  w.random = incoherent_rays(box, kRandomRays, 7);
  Camera cam;
  cam.center = Vec3(box.center());
  cam.eye = cam.center + 1.2 * double(glm::length(box.extent())) * glm::normalize(Vec3(0.3, 0.4, 1));
  w.primary = primary_rays(cam, kImage, kImage);
  w.accel = std::make_unique<MeshAccel>(w.mesh);
  w.embree = std::make_unique<reference::EmbreeMesh>(w.mesh);
  return w;
}

bool have_mesh(const std::string& name) {
  return name != "bunny" ||
         std::filesystem::exists(std::filesystem::path(TESSERA_SHARED_DATA) / "meshes/bunny/bun_zipper.ply");
}

std::string key(const std::string& mesh, const char* what, const char* who, int threads) {
  return mesh + "/" + what + "/" + who + "/" + std::to_string(threads);
}

constexpr int64_t kChunk = 1024;  // rays per parallel task (and per stream call)

/// Casts every ray in parallel chunks; returns the number of hits (kept so nothing is optimized away).
template <class Cast>
long cast_all(const std::vector<Ray>& rays, Cast&& cast) {
  std::atomic<long> hits{0};
  parallel_for(0, int64_t(rays.size()), kChunk, [&](int64_t begin, int64_t end) {
    long local = 0;
    for (int64_t i = begin; i < end; ++i) local += cast(rays[size_t(i)]);
    hits += local;
  });
  return hits;
}

/// Casts the rays as streams of up to kChunk rays (cast(rays) returns the hits of the span), in parallel.
template <class Cast>
long cast_streams(const std::vector<Ray>& rays, Cast&& cast) {
  std::atomic<long> hits{0};
  parallel_for(0, int64_t(rays.size()), kChunk, [&](int64_t begin, int64_t end) {
    hits += cast(std::span<const Ray>(rays).subspan(size_t(begin), size_t(end - begin)));
  });
  return hits;
}

long cast_stream_tessera(const MeshAccel& accel, std::span<const Ray> rays) {
  Hit hits[kChunk];
  accel.intersect(rays, std::span<Hit>(hits, rays.size()));
  return std::count_if(hits, hits + rays.size(), [](const Hit& h) { return h.prim >= 0; });
}

long cast_stream_embree(const reference::EmbreeMesh& embree, std::span<const Ray> rays) {
  int prims[kChunk];
  float t[kChunk];
  embree.intersect(rays, std::span<int>(prims, rays.size()), std::span<float>(t, rays.size()));
  return std::count_if(prims, prims + rays.size(), [](int p) { return p >= 0; });
}

bool cast_tessera(const MeshAccel& accel, const Ray& r) {
  Ray ray = r;
  Hit hit;
  return accel.intersect(ray, hit);
}

bool cast_embree(const reference::EmbreeMesh& embree, const Ray& r) {
  float t;
  return embree.intersect(r, t) >= 0;
}

/// Rays per second of one configuration: range(0) 0 = incoherent, 1 = primary; range(1) 0 = Tessera, 1 = Embree,
/// 2 = Tessera streams, 3 = Embree streams; range(2) threads (0 = all). The rates from the median times go to the
/// summary.
void BM_Rays(benchmark::State& state, const std::string& mesh) {
  if (!have_mesh(mesh)) {
    state.SkipWithError("mesh not available (TESSERA_SHARED_DATA)");
    return;
  }
  Workload& w = workload(mesh);
  const bool primary = state.range(0) == 1, embree = state.range(1) % 2 == 1, stream = state.range(1) >= 2;
  const int threads = int(state.range(2));
  const ThreadLimit limit(threads);
  const std::vector<Ray>& rays = primary ? w.primary : w.random;
  long hits = 0;
  std::vector<double> wall, cpu;
  for (auto _ : state) {
    const auto [seconds, cpu_seconds] = timed([&] {
      if (stream)
        hits = embree ? cast_streams(rays, [&](std::span<const Ray> s) { return cast_stream_embree(*w.embree, s); })
                      : cast_streams(rays, [&](std::span<const Ray> s) { return cast_stream_tessera(*w.accel, s); });
      else
        hits = embree ? cast_all(rays, [&](const Ray& r) { return cast_embree(*w.embree, r); })
                      : cast_all(rays, [&](const Ray& r) { return cast_tessera(*w.accel, r); });
    });
    wall.push_back(seconds);
    cpu.push_back(cpu_seconds);
    benchmark::DoNotOptimize(hits);
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(double(rays.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["hit_fraction"] = double(hits) / double(rays.size());
  const char* what = primary ? "primary" : stream ? "stream" : "random";
  g_results[key(mesh, what, embree ? "embree" : "tessera", threads)] = rates(double(rays.size()), wall, cpu);
}

/// BVH build in Mprims/s: range(0) 0 = Tessera, 1 = Embree; range(1) threads (0 = all).
void BM_Build(benchmark::State& state, const std::string& mesh) {
  if (!have_mesh(mesh)) {
    state.SkipWithError("mesh not available (TESSERA_SHARED_DATA)");
    return;
  }
  Workload& w = workload(mesh);
  const bool embree = state.range(0) == 1;
  const int threads = int(state.range(1));
  const ThreadLimit limit(threads);
  std::vector<double> wall, cpu;
  for (auto _ : state) {
    // Both include the float copy of the vertices; Embree's thread pool is sized at device creation (its TBB tasking
    // also honours the ThreadLimit).
    // The structures are freed outside the timed part, as before.
    std::optional<reference::EmbreeMesh> scene;
    std::optional<MeshAccel> accel;
    const auto [s, c] = timed([&] {
      if (embree) {
        scene.emplace(w.mesh, threads);
      } else {
        accel.emplace(w.mesh);
        benchmark::DoNotOptimize(accel->bvh().nodes().data());
      }
    });
    wall.push_back(s);
    cpu.push_back(c);
  }
  const Rates r = rates(double(w.mesh.triangle_count()), wall, cpu);
  state.counters["Mprims_per_s"] = r.wall * 1e-6;
  g_results[key(mesh, "build", embree ? "embree" : "tessera", threads)] = r;
}

void register_all() {
  for (const std::string mesh : {"bunny", "torus1M"}) {
    auto* rays = benchmark::RegisterBenchmark(("rays/" + mesh).c_str(), BM_Rays, mesh);
    rays->ArgNames({"primary", "embree", "threads"})->UseRealTime()->MeasureProcessCPUTime();
    rays->Unit(benchmark::kMillisecond);
    for (int primary : {0, 1})
      for (int threads : {1, 2, 0})
        for (int who : {0, 1, 2, 3})
          if (!primary || who < 2) rays->Args({primary, who, threads});
    auto* build = benchmark::RegisterBenchmark(("build/" + mesh).c_str(), BM_Build, mesh);
    build->ArgNames({"embree", "threads"})->UseRealTime()->MeasureProcessCPUTime();
    build->Unit(benchmark::kMillisecond);
    for (int threads : {1, 0})
      for (int embree : {0, 1}) build->Args({embree, threads});
  }
}

void print_summary() {
  std::printf("\n%-8s %-8s %-7s %12s %12s %8s %12s %12s %8s %10s %10s %9s\n", "mesh", "what", "threads", "tessera/s",
              "embree/s", "ratio", "tessera/cpu", "embree/cpu", "cpu-ratio", "2T-tessera", "2T-embree", "vs-1/cpu");
  for (const std::string mesh : {"bunny", "torus1M"})
    for (const char* what : {"random", "stream", "primary", "build"})
      for (int threads : {1, 2, 0}) {
        const auto t = g_results.find(key(mesh, what, "tessera", threads));
        const auto e = g_results.find(key(mesh, what, "embree", threads));
        if (t == g_results.end() || e == g_results.end()) continue;
        // The 2-thread row's wall rate over the 1-thread row's, of each.
        const auto scaling = [&](const char* who, double rate) {
          const auto one = g_results.find(key(mesh, what, who, 1));
          return threads == 2 && one != g_results.end() ? std::to_string(rate / one->second.wall).substr(0, 5) : "";
        };
        // Streams also against Embree's one-ray rtcIntersect1 on the same rays (per CPU second).
        const auto one_ray = g_results.find(key(mesh, "random", "embree", threads));
        const std::string vs_one = std::string(what) == "stream" && one_ray != g_results.end()
                                       ? std::to_string(t->second.cpu / one_ray->second.cpu).substr(0, 5)
                                       : "";
        std::printf("%-8s %-8s %-7s %12.4g %12.4g %8.3f %12.4g %12.4g %8.3f %10s %10s %9s\n", mesh.c_str(), what,
                    threads == 0 ? "all" : std::to_string(threads).c_str(), t->second.wall, e->second.wall,
                    t->second.wall / e->second.wall, t->second.cpu, e->second.cpu, t->second.cpu / e->second.cpu,
                    scaling("tessera", t->second.wall).c_str(), scaling("embree", e->second.wall).c_str(),
                    vs_one.c_str());
      }
  std::printf(
      "(rates from median times: rays/s, or primitives/s for build, per wall second and per CPU second of the\n"
      " whole process; stream = the random rays 1024 a call, MeshAccel's span intersect vs rtcIntersect1M,\n"
      " vs-1/cpu = the stream's CPU rate over Embree rtcIntersect1's on the same rays;\n"
      " %d hardware threads; load average %.2f)\n",
      tessera::thread_count(), bench::load_average());
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
