// tessera bench raycast MESH: build a BVH over a mesh and measure primary and incoherent rays per second.
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <span>
#include <vector>

#include "camera_options.hpp"
#include "command.hpp"
#include "tessera/accel/mesh_accel.hpp"
#include "tessera/accel/ray_workloads.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera::cli {
namespace {

struct RaycastArgs {
  std::string mesh, hits_out;
  long long random_rays = 1 << 20;
  CameraOptions camera;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Casts every ray (parallel, fixed chunks); returns the number of hits. `record(i, hit or nullptr)` sees each result.
/// `stream`: each chunk through MeshAccel's span intersect (several rays interleaved: faster on incoherent rays, slower
/// on coherent ones, whose nodes are in cache anyway); the hits are the same either way.
template <class Record>
int64_t cast_all(const MeshAccel& accel, const std::vector<Ray>& rays, bool stream, Record&& record) {
  constexpr int64_t kChunk = 1024;
  std::atomic<int64_t> hits{0};
  parallel_for(0, int64_t(rays.size()), kChunk, [&](int64_t begin, int64_t end) {
    const std::span<const Ray> chunk = std::span<const Ray>(rays).subspan(size_t(begin), size_t(end - begin));
    std::vector<Hit> found(chunk.size());
    if (stream) {
      accel.intersect(chunk, found);
    } else {
      for (size_t i = 0; i < chunk.size(); ++i) {
        Ray ray = chunk[i];
        accel.intersect(ray, found[i]);
      }
    }
    int64_t local = 0;
    for (int64_t i = begin; i < end; ++i) {
      const Hit& hit = found[size_t(i - begin)];
      local += hit.prim >= 0;
      record(i, hit.prim >= 0 ? &hit : nullptr);
    }
    hits += local;
  });
  return hits;
}

void run_raycast(const RaycastArgs& a, const CommonOptions& common) {
  const auto [width, height] = a.camera.image_size();
  // The rays are made up front (36 bytes each): 2^27 of them take 4.5 GiB.
  constexpr long long kMaxRandomRays = 1LL << 27;
  if (a.random_rays < 0 || a.random_rays > kMaxRandomRays)
    throw InvalidInput(fmt::format("--random-rays: expected N in [0, {}], got {}", kMaxRandomRays, a.random_rays));
  // The rays against the memory budget, before the mesh is read: each ray, and with --hits-out each primary ray's
  // distance and primitive (8 bytes).
  const uint64_t per_primary = sizeof(Ray) + (a.hits_out.empty() ? 0 : sizeof(float) + sizeof(int));
  MemoryBudget::check(saturating_product({uint64_t(width), uint64_t(height), per_primary}) +
                          saturating_product({uint64_t(a.random_rays), sizeof(Ray)}),
                      fmt::format("casting {}x{} primary rays and {} random rays", width, height, a.random_rays));
  PhaseTimer timer;
  const PolyMesh poly = timer.time("read_s", [&] { return read_mesh_with_progress(a.mesh); });
  const TriMesh mesh = to_tri_mesh(poly);
  if (mesh.triangle_count() == 0) throw InvalidInput(fmt::format("{}: the mesh has no faces to cast rays at", a.mesh));
  const Bounds3 b = bounding_box(poly);
  const Camera camera = a.camera.camera(b.lo, b.hi);

  auto start = std::chrono::steady_clock::now();
  const MeshAccel accel(mesh);
  const double build_s = seconds_since(start);

  // Primary rays: the notes' eye rays through the pixel centers, row-major from the top row.
  const std::vector<Ray> primary = primary_rays(camera, width, height);
  std::vector<float> hit_t(a.hits_out.empty() ? 0 : primary.size());
  std::vector<int> hit_prim(hit_t.size());
  start = std::chrono::steady_clock::now();
  const int64_t primary_hits = a.hits_out.empty() ? cast_all(accel, primary, false, [](int64_t, const Hit*) {})
                                                  : cast_all(accel, primary, false, [&](int64_t i, const Hit* h) {
                                                      hit_t[size_t(i)] = h ? h->t : -1.0f;
                                                      hit_prim[size_t(i)] = h ? h->prim : -1;
                                                    });
  const double primary_s = seconds_since(start);

  const AABB box{Vec3f(b.lo), Vec3f(b.hi)};
  const std::vector<Ray> random = incoherent_rays(box, size_t(a.random_rays));
  start = std::chrono::steady_clock::now();
  const int64_t random_hits = cast_all(accel, random, true, [](int64_t, const Hit*) {});
  const double random_s = seconds_since(start);

  if (!a.hits_out.empty())
    timer.time("write_s", [&] {
      write_file_atomic(a.hits_out, [&](std::ostream& out) {
        for (size_t i = 0; i < hit_t.size(); ++i) {
          if (hit_prim[i] < 0)
            out << i << " -1 -1\n";
          else
            out << fmt::format("{} {:.9g} {}\n", i, hit_t[i], hit_prim[i]);
        }
      });
    });
  const double primary_rate = primary_s > 0 ? double(primary.size()) / primary_s : 0;
  const double random_rate = random_s > 0 && !random.empty() ? double(random.size()) / random_s : 0;
  if (!common.stats) {
    fmt::print("build_s={} primary_rays_per_s={} random_rays_per_s={}\n", stat_value(build_s), stat_value(primary_rate),
               stat_value(random_rate));
    return;
  }
  StatRows rows = {
      {"build_s", stat_value(build_s)},
      {"primary_rays_per_s", stat_value(primary_rate)},
      {"random_rays_per_s", stat_value(random_rate)},
      {"triangles", stat_value(double(mesh.triangle_count()))},
      {"bvh_nodes", stat_value(double(accel.bvh().nodes().size()))},
      {"bvh_depth", stat_value(accel.bvh().depth())},
      {"primary_rays", stat_value(double(primary.size()))},
      {"primary_hit_fraction", stat_value(double(primary_hits) / double(primary.size()))},
      {"random_rays", stat_value(double(random.size()))},
      {"random_hit_fraction", stat_value(random.empty() ? 0 : double(random_hits) / double(random.size()))},
      {"width", stat_value(width)},
      {"height", stat_value(height)},
      {"threads", stat_value(thread_count())},
      {"compute_s", stat_value(build_s + primary_s + random_s)}};
  for (auto& row : timer.rows()) rows.push_back(row);
  print_stats(rows);
}

}  // namespace

void setup_bench(CLI::App& bench, CommonOptions& common) {
  bench.require_subcommand(1);
  CLI::App* cmd = bench.add_subcommand("raycast", "Build a BVH over a mesh and measure primary and random rays/s");
  auto a = std::make_shared<RaycastArgs>();
  cmd->add_option("mesh", a->mesh, "Mesh file (.obj, .ply, .off, .stl)")->required();
  a->camera.view = View::front;  // the benchmark's rays stay those of earlier sessions' measurements
  a->camera.clip_planes = false;
  a->camera.add(*cmd);
  cmd->add_option("--random-rays", a->random_rays,
                  "Incoherent rays: origins uniform in the mesh box scaled 1.1x, directions uniform (0 skips)")
      ->capture_default_str();
  cmd->add_option("--hits-out", a->hits_out,
                  "Write one line per primary ray, row-major from the top row: index t prim (-1 -1 for a miss)");
  cmd->callback([a, &common] { run_raycast(*a, common); });
}

}  // namespace tessera::cli
