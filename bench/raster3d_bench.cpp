// The 3D pipeline against Mesa's llvmpipe (OSMesa, fixed-function OpenGL 1.x) in the same run, on the same thread
// counts (LP_NUM_THREADS = Tessera's threads):
//   immediate  1M lit Gouraud triangles of ~16 px at 1280x720 (17 full-screen layers of a wavy grid, back to front)
//              through glBegin/glEnd and through the gt immediate-mode layer; triangles/s
//   batched    the same mesh through vertex arrays (glDrawElements) and through the batched draw; triangles/s
//   fill       z-tested flat fill at 1920x1080, 32 full-screen layers back to front (every fragment passes and
//              writes); pixels/s, and as a share of the machine's memory bandwidth (12 bytes per pixel: depth read,
//              depth write, color write)
//   textured   8 full-screen layers at 1280x720 back to front, a 512 x 512 texture repeated 4 times across (about
//              1.6 texels per pixel: trilinear between MIPmap levels 0 and 1), GL_REPLACE against raster3d's surface
//              shaders (unlit, the texel as the color); pixels/s
//   bandwidth  a STREAM-like copy and triad over 128 MiB arrays (3 of them: far beyond the caches) with oneTBB on
//              1 and on 2 threads; the fill's share is taken against the same thread count
// Threads: with LP_NUM_THREADS = N llvmpipe rasterizes on N threads beside the application's thread, which transforms,
// sets up and bins. Tessera has the same structure: under ThreadLimit(N) the calling thread collects, runs the vertex
// stage and sets up and bins the chunks of a batch's pass for as long as the framebuffer's raster thread is busy; the
// raster job sets up the rest once it is free and rasterizes the pass's tiles. The loops of each side run on up to
// N - 1 threads while the other side is busy (the other side's thread is one of the N), so with N = 2 on two cores
// no oneTBB worker competes with the two pipeline threads. So both "1 thread" figures may use two cores, and the
// per-CPU-second ratio is reported next to the wall-time one; caller_cpu_ms and others_cpu_ms split the fastest
// frame's CPU time between the calling thread and the others. immediate/tessera_unpipelined draws
// the same batches waiting for each before collecting the next (the schedule before session 4): the gain of the
// overlap in the same run.
// Each measurement is the best frame of a few (a frame = clear + draw + glFinish / return), in wall time and in
// CPU time of all the process's threads (the steadier figure on a loaded machine). llvmpipe reads
// LP_NUM_THREADS once per process, so every llvmpipe measurement runs in a child process (this program re-executed
// with --llvmpipe-child=CASE,THREADS). The Tessera benchmarks carry the ratios as counters (x_llvmpipe = Tessera's
// rate / llvmpipe's), and a table at the end repeats them with the load average.
//
//   cmake -S . -B build/bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_BENCH=ON
//   ninja -C build/bench bench_raster3d && build/bench/bench/bench_raster3d --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <dirent.h>
#include <fmt/format.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "osmesa_renderer.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/gt.hpp"
#include "tessera/raster3d/surface_shader.hpp"

namespace {

using namespace tessera;
using reference::GlState;
using reference::GlSubmit;

// ---------------------------------------------------------------------------------------------------------------
// Workloads, built identically in the parent and in the llvmpipe children.

enum class Case { immediate, batched, fill, textured };
const char* case_name(Case c) {
  return c == Case::immediate ? "immediate" : c == Case::batched ? "batched" : c == Case::fill ? "fill" : "textured";
}

constexpr int kTriWidth = 1280, kTriHeight = 720;
constexpr int kFillWidth = 1920, kFillHeight = 1080, kFillLayers = 32;
constexpr int kTexturedLayers = 8, kTextureSize = 512;
constexpr int kFrames = 3;  // best of

// The camera of the triangle workloads: 60 degrees vertical field of view, looking down -z.
constexpr double kFovy = 60.0;
Mat4 tri_projection() { return perspective(radians(kFovy), double(kTriWidth) / kTriHeight, 1.0, 20.0); }

// 17 layers of a 226 x 130 grid (2 triangles per cell: 998,920 triangles), each layer filling the view at its depth
// (so every triangle covers 1280/226 x 720/130 / 2 = 15.7 pixels) with a gentle wave in z for varied normals. Layers
// go back to front: every fragment passes the depth test, the heaviest and steadiest load.
TriMesh layered_grid() {
  constexpr int kLayers = 17, kNx = 226, kNy = 130;
  const double tan_half = std::tan(radians(kFovy) / 2), aspect = double(kTriWidth) / kTriHeight;
  TriMesh mesh;
  mesh.positions.reserve(size_t(kLayers) * (kNx + 1) * (kNy + 1));
  mesh.normals.reserve(mesh.positions.capacity());
  mesh.indices.reserve(size_t(kLayers) * kNx * kNy * 6);
  for (int layer = 0; layer < kLayers; ++layer) {
    const double depth = 12.0 - 0.5 * layer;  // 12 (far) .. 4 (near)
    const double half_h = depth * tan_half * 0.999, half_w = half_h * aspect;
    const double amplitude = 0.02 * depth, phase = 0.7 * layer;
    const auto base = uint32_t(mesh.positions.size());
    for (int j = 0; j <= kNy; ++j)
      for (int i = 0; i <= kNx; ++i) {
        const double u = double(i) / kNx, v = double(j) / kNy;
        const double a = 6 * kPi * u + phase, b = 4 * kPi * v;
        const double x = (2 * u - 1) * half_w, y = (2 * v - 1) * half_h;
        const double z = -depth + amplitude * std::sin(a) * std::cos(b);
        // Normal of z = f(x, y): (-df/dx, -df/dy, 1), normalized.
        const double dfdx = amplitude * std::cos(a) * std::cos(b) * 6 * kPi / (2 * half_w);
        const double dfdy = -amplitude * std::sin(a) * std::sin(b) * 4 * kPi / (2 * half_h);
        mesh.positions.emplace_back(x, y, z);
        mesh.normals.push_back(glm::normalize(Vec3(-dfdx, -dfdy, 1)));
      }
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) {
        const uint32_t v00 = base + uint32_t(j * (kNx + 1) + i), v10 = v00 + 1, v01 = v00 + kNx + 1, v11 = v01 + 1;
        mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
      }
  }
  return mesh;
}

// `layers` full-screen quads at window depths from 0.97 down to 0.03 (back to front), identity matrices; `textured`:
// with texture coordinates 0..4 across, 0..4 * 9/16 up (square texels on a 16:9 screen), and normals +z.
TriMesh fill_layers(int layers, bool textured) {
  TriMesh mesh;
  for (int layer = 0; layer < layers; ++layer) {
    const double z_ndc = 2 * (0.97 - 0.94 * layer / (layers - 1)) - 1;
    const auto base = uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {{-1, -1, z_ndc}, {1, -1, z_ndc}, {1, 1, z_ndc}, {-1, 1, z_ndc}});
    if (textured) {
      mesh.uvs.insert(mesh.uvs.end(), {{0, 0}, {4, 0}, {4, 2.25}, {0, 2.25}});
      mesh.normals.insert(mesh.normals.end(), 4, Vec3(0, 0, 1));
    }
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  return mesh;
}

// The textured case's texture: smooth color waves with a fine checker on top (texel (i, j) from the bottom-left).
reference::GlTexture bench_texture() {
  reference::GlTexture t{kTextureSize, kTextureSize, std::vector<uint8_t>(size_t(kTextureSize) * kTextureSize * 4, 255),
                         reference::GlFilter::linear_mipmap_linear};
  for (int j = 0; j < kTextureSize; ++j)
    for (int i = 0; i < kTextureSize; ++i) {
      uint8_t* texel = &t.rgba[(size_t(j) * kTextureSize + i) * 4];
      const int check = ((i / 4 + j / 4) % 2) * 40;
      texel[0] = uint8_t(100 + 80 * std::sin(i * 0.05) + check / 2);
      texel[1] = uint8_t(100 + 80 * std::cos(j * 0.03) + check / 2);
      texel[2] = uint8_t(60 + check * 3);
    }
  return t;
}

// The fixed-function state of the triangle workloads: a white directional light from the upper right, a bluish
// plastic (diffuse + white highlight, shininess 32), smooth shading.
GlState tri_gl_state() {
  GlState s;
  s.projection = Mat4f(tri_projection());
  s.modelview = Mat4f(1.0f);
  s.lighting = true;
  s.light.position = Vec4f(glm::normalize(Vec3f(0.4f, 0.6f, 1.0f)), 0.0f);
  s.material.diffuse = {0.3f, 0.5f, 0.9f, 1};
  s.material.ambient = {0.3f, 0.5f, 0.9f, 1};
  s.material.specular = {0.6f, 0.6f, 0.6f, 1};
  s.material.shininess = 32;
  s.background = {0.1f, 0.1f, 0.1f};
  return s;
}

GlState fill_gl_state() {
  GlState s;
  s.smooth = false;
  s.color = {0.8f, 0.4f, 0.2f};
  return s;
}

GlState textured_gl_state() {
  static const reference::GlTexture texture = bench_texture();
  GlState s;
  s.texture = &texture;
  return s;
}

GlState gl_state(Case c) {
  return c == Case::fill ? fill_gl_state() : c == Case::textured ? textured_gl_state() : tri_gl_state();
}

struct Workload {
  int width, height;
  TriMesh mesh;
  double pixels_per_frame;  // fill: layers x width x height; triangles: 0
};

const Workload& workload(Case c) {
  static std::map<Case, std::unique_ptr<Workload>> cache;
  auto& w = cache[c];
  if (!w) {
    if (c == Case::fill)
      w = std::make_unique<Workload>(Workload{kFillWidth, kFillHeight, fill_layers(kFillLayers, false),
                                              double(kFillLayers) * kFillWidth * kFillHeight});
    else if (c == Case::textured)
      w = std::make_unique<Workload>(Workload{kTriWidth, kTriHeight, fill_layers(kTexturedLayers, true),
                                              double(kTexturedLayers) * kTriWidth * kTriHeight});
    else
      w = std::make_unique<Workload>(Workload{kTriWidth, kTriHeight, layered_grid(), 0});
  }
  return *w;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Wall and CPU seconds of one frame (CPU: every thread of the process, so llvmpipe's rasterizer threads and TBB's
// workers count; on a loaded machine the CPU time is the steadier measure of the work done).
struct Timing {
  double wall = 1e30, cpu = 1e30;
  void keep_best(const Timing& t) {
    wall = std::min(wall, t.wall);
    cpu = std::min(cpu, t.cpu);
  }
};

class Stopwatch {
 public:
  Timing elapsed() const { return {seconds_since(wall0_), process_cpu_seconds() - cpu0_}; }

 private:
  std::chrono::steady_clock::time_point wall0_ = std::chrono::steady_clock::now();
  double cpu0_ = process_cpu_seconds();
};

// CPU seconds of each thread of this process by thread id (the first field of /proc/self/task/TID/schedstat, in
// nanoseconds): for the split of a frame's CPU time between the calling thread and the others.
std::map<int, double> thread_cpu_seconds() {
  std::map<int, double> out;
  std::unique_ptr<DIR, int (*)(DIR*)> dir(opendir("/proc/self/task"), closedir);
  if (!dir) return out;
  while (const dirent* entry = readdir(dir.get())) {
    if (entry->d_name[0] == '.') continue;
    const std::string path = fmt::format("/proc/self/task/{}/schedstat", entry->d_name);
    if (FILE* f = std::fopen(path.c_str(), "r")) {
      double ns = 0;
      if (std::fscanf(f, "%lf", &ns) == 1) out[std::atoi(entry->d_name)] = 1e-9 * ns;
      std::fclose(f);
    }
  }
  return out;
}

// The CPU seconds the calling thread spent between two thread_cpu_seconds() snapshots, and all the other threads.
struct ThreadSplit {
  double caller = 0, others = 0;
};
ThreadSplit thread_split(const std::map<int, double>& before, const std::map<int, double>& after) {
  ThreadSplit split;
  const int self = int(gettid());
  for (const auto& [tid, seconds] : after) {
    const auto then = before.find(tid);
    const double spent = seconds - (then == before.end() ? 0.0 : then->second);
    (tid == self ? split.caller : split.others) += spent;
  }
  return split;
}

double load_average() {
  double one = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &one) != 1) one = 0;
    std::fclose(f);
  }
  return one;
}

// ---------------------------------------------------------------------------------------------------------------
// llvmpipe: one child process per (case, threads).

// The child: renders kFrames frames of the case and prints the best frame time.
int llvmpipe_child(Case c, int threads) {
  const Workload& w = workload(c);
  const reference::GlMesh mesh(w.mesh);
  reference::OsmesaContext context(w.width, w.height, threads);
  const GlState state = gl_state(c);
  const GlSubmit submit = c == Case::immediate ? GlSubmit::immediate : GlSubmit::vertex_arrays;
  Timing best;
  for (int frame = 0; frame < kFrames + 1; ++frame) {  // frame 0 warms up (shader compilation, allocations)
    const Stopwatch watch;
    context.begin(state);
    context.draw(mesh, submit);
    context.finish();
    if (frame > 0) best.keep_best(watch.elapsed());
  }
  std::printf("llvmpipe seconds=%.9g cpu_seconds=%.9g lp_num_threads=%d\n", best.wall, best.cpu,
              reference::OsmesaContext::rasterizer_threads());
  return 0;
}

std::string g_self;  // this program's path, for the children

// Runs a child and returns its best frame times, or an error message.
bool run_llvmpipe(Case c, int threads, Timing& timing, std::string& error) {
  const std::string command = fmt::format("'{}' --llvmpipe-child={},{} 2>&1", g_self, case_name(c), threads);
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) {
    error = "popen failed";
    return false;
  }
  std::string output;
  char buffer[4096];
  while (size_t got = std::fread(buffer, 1, sizeof buffer, pipe.get())) output.append(buffer, got);
  const int status = pclose(pipe.release());
  const size_t at = output.find("llvmpipe seconds=");
  if (status != 0 || at == std::string::npos) {
    error = fmt::format("llvmpipe child failed (status {}): {}", status, output.substr(0, 300));
    return false;
  }
  timing.wall = std::strtod(output.c_str() + at + std::strlen("llvmpipe seconds="), nullptr);
  const size_t cpu_at = output.find("cpu_seconds=", at);
  timing.cpu =
      cpu_at == std::string::npos ? 0 : std::strtod(output.c_str() + cpu_at + std::strlen("cpu_seconds="), nullptr);
  return true;
}

// Results for the ratios and the final table, keyed "case/threads".
struct Rates {
  double llvmpipe = 0, tessera = 0;          // triangles/s or pixels/s of wall time (best of the repetitions)
  double llvmpipe_cpu = 0, tessera_cpu = 0;  // the same per CPU second
};
std::map<std::string, Rates> g_rates;
std::map<int, double> g_bandwidth;  // bytes/s by thread count (the best of copy and triad)

std::string key(Case c, int threads) { return fmt::format("{}/{}", case_name(c), threads); }

double rate_of(Case c, double seconds) {
  const Workload& w = workload(c);
  return (w.pixels_per_frame > 0 ? w.pixels_per_frame : double(w.mesh.triangle_count())) / seconds;
}

// Sets a finished measurement's counters and keeps its best rates (wall and CPU) for the ratios.
const Rates& record(benchmark::State& state, Case c, int threads, const Timing& timing, bool peer) {
  const double rate = rate_of(c, timing.wall);
  state.counters[workload(c).pixels_per_frame > 0 ? "pixels_per_s" : "tris_per_s"] = rate;
  if (c == Case::fill && g_bandwidth[threads] > 0) state.counters["bandwidth_share"] = rate * 12 / g_bandwidth[threads];
  state.counters["cpu_ms"] = 1e3 * timing.cpu;
  Rates& r = g_rates[key(c, threads)];
  double& best_wall = peer ? r.llvmpipe : r.tessera;
  double& best_cpu = peer ? r.llvmpipe_cpu : r.tessera_cpu;
  best_wall = std::max(best_wall, rate);
  best_cpu = std::max(best_cpu, rate_of(c, timing.cpu));
  return r;
}

void BM_Llvmpipe(benchmark::State& state, Case c, int threads) {
  Timing timing;
  std::string error;
  for (auto _ : state) {
    if (!run_llvmpipe(c, threads, timing, error)) {
      static std::string message;  // SkipWithError keeps the pointer
      message = error;
      state.SkipWithError(message.c_str());
      return;
    }
    state.SetIterationTime(timing.wall);
  }
  record(state, c, threads, timing, true);
}

// ---------------------------------------------------------------------------------------------------------------
// Memory bandwidth: STREAM's copy (16 bytes per element) and triad (24 bytes), best of 5, on `threads` threads.

void BM_Bandwidth(benchmark::State& state, bool triad, int threads) {
  const ThreadLimit limit(threads);
  constexpr int64_t kN = int64_t(1) << 24;  // 128 MiB per array, far beyond the caches
  constexpr int64_t kGrain = int64_t(1) << 16;
  std::unique_ptr<double[]> a(new double[kN]), b(new double[kN]), c(new double[kN]);
  parallel_for(0, kN, kGrain, [&](int64_t i0, int64_t i1) {  // first touch by the threads that will use the pages
    for (int64_t i = i0; i < i1; ++i) a[i] = 1.0, b[i] = 2.0, c[i] = 0.0;
  });
  const double bytes = double(kN) * (triad ? 24 : 16);
  double best = 1e30;
  for (auto _ : state) {
    for (int rep = 0; rep < 5; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      if (triad)
        parallel_for(0, kN, kGrain, [&](int64_t i0, int64_t i1) {
          for (int64_t i = i0; i < i1; ++i) a[i] = b[i] + 3.0 * c[i];
        });
      else
        parallel_for(0, kN, kGrain, [&](int64_t i0, int64_t i1) {
          for (int64_t i = i0; i < i1; ++i) c[i] = a[i];
        });
      best = std::min(best, seconds_since(t0));
    }
    state.SetIterationTime(best);
  }
  benchmark::DoNotOptimize(a[kN / 2] + c[kN / 3]);
  state.counters["bytes_per_s"] = bytes / best;
  g_bandwidth[threads] = std::max(g_bandwidth[threads], bytes / best);
}

// ---------------------------------------------------------------------------------------------------------------
// Tessera: the same state through the Context (the light placed in eye space, as the GL state does).

void set_tessera_state(raster3d::Context& ctx, Case c) {
  const GlState gl = gl_state(c);
  ctx.matrix_mode(raster3d::MatrixMode::projection);
  ctx.load_matrix(Mat4(gl.projection));
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  ctx.load_identity();
  if (gl.lighting) {
    ctx.light(0, raster3d::Light{gl.light.position, Vec3f(gl.light.ambient), Vec3f(gl.light.diffuse),
                                 Vec3f(gl.light.specular)});
    ctx.material(raster3d::Material{Vec3f(gl.material.ambient), Vec3f(gl.material.diffuse), Vec3f(gl.material.specular),
                                    Vec3f(gl.material.emission), gl.material.shininess});
    ctx.shading(raster3d::ShadingModel::gouraud);
  } else {
    ctx.shading(raster3d::ShadingModel::unlit);
    ctx.color(gl.color);
  }
  ctx.load_matrix(Mat4(gl.modelview));
}

// The immediate-mode frame through the notes' gt layer: one gtNormal + gtVertex per triangle corner. `unpipelined`
// ends the shape and waits for the drawing (Context::flush) after every immediate-mode batch's worth of triangles:
// the same batches drawn without overlapping the collection of the next one (the schedule before session 4).
void draw_immediate(const raster3d::VertexArrays& arrays, bool unpipelined) {
  constexpr size_t kBatchCorners = 3 * size_t(raster3d::detail::kChunkTriangles) * raster3d::detail::kPassChunks;
  gt::gtBeginShape(gt::GT_TRIANGLES);
  for (size_t k = 0; k < arrays.indices.size(); ++k) {
    if (unpipelined && k > 0 && k % kBatchCorners == 0) {
      gt::gtEndShape();
      gt::gtCurrent().flush();
      gt::gtBeginShape(gt::GT_TRIANGLES);
    }
    const uint32_t i = arrays.indices[k];
    const Vec3f& n = arrays.normals[i];
    const Vec3f& p = arrays.positions[i];
    gt::gtNormal(n.x, n.y, n.z);
    gt::gtVertex(p.x, p.y, p.z);
  }
  gt::gtEndShape();
}

/// The textured case through the surface shaders: the llvmpipe case's texture, unlit (the texel is the color, as
/// GL_REPLACE), trilinear.
struct TexturedDraw {
  Texture2D texture;
  raster3d::SurfaceUniforms uniforms;
  raster3d::Framebuffer framebuffer;

  TexturedDraw(int width, int height)
      : texture(texture_image(*textured_gl_state().texture), Sampler{.filter = Filter::trilinear}),
        framebuffer(width, height) {
    uniforms.lighting = raster3d::PreparedLighting(raster3d::unlit_lighting());
    uniforms.maps.texture = &texture;
  }

  /// The GL texture (rows bottom first) as an 8-bit image (rows top first): the format llvmpipe samples (GL_RGBA8).
  static ImageRGBA8 texture_image(const reference::GlTexture& gl) {
    ImageRGBA8 image(gl.width, gl.height);
    for (int j = 0; j < gl.height; ++j)
      for (int i = 0; i < gl.width; ++i) {
        const uint8_t* t = &gl.rgba[(size_t(j) * gl.width + i) * 4];
        image(i, gl.height - 1 - j) = glm::u8vec4(t[0], t[1], t[2], 255);
      }
    return image;
  }
};

std::map<int, Rates> g_unpipelined;  // immediate mode drawn batch by batch, by thread count (tessera fields only)

void BM_Tessera(benchmark::State& state, Case c, int threads, bool unpipelined) {
  const Workload& w = workload(c);
  const raster3d::VertexArrays arrays = raster3d::VertexArrays::from_mesh(w.mesh);
  raster3d::Context ctx(w.width, w.height);
  set_tessera_state(ctx, c);
  gt::gtMakeCurrent(&ctx);
  const ThreadLimit limit(threads);
  const Vec3f background = gl_state(c).background;
  std::optional<TexturedDraw> textured;
  if (c == Case::textured) textured.emplace(w.width, w.height);
  const auto frame = [&] {
    if (textured) {
      textured->framebuffer.clear(background);
      raster3d::draw_surface(textured->framebuffer, raster3d::RasterState{}, arrays, textured->uniforms);
      benchmark::DoNotOptimize(textured->framebuffer.color().pixels().data());
      return;
    }
    ctx.clear(background);
    if (c == Case::immediate)
      draw_immediate(arrays, unpipelined);
    else
      ctx.draw(arrays);
    benchmark::DoNotOptimize(ctx.framebuffer().color().pixels().data());  // framebuffer() draws what is pending
  };
  frame();  // warm-up: the binning memory is allocated once
  Timing best;
  ThreadSplit best_split;  // of the fastest frame
  for (auto _ : state) {
    for (int i = 0; i < kFrames; ++i) {
      const auto before = thread_cpu_seconds();
      const Stopwatch watch;
      frame();
      const Timing t = watch.elapsed();
      if (t.wall < best.wall) best_split = thread_split(before, thread_cpu_seconds());
      best.keep_best(t);
    }
    state.SetIterationTime(best.wall);
  }
  gt::gtMakeCurrent(nullptr);
  // The fastest frame's CPU time on the calling thread (gt calls, vertex stage, its share of the setup) and on the
  // others (the raster thread, oneTBB's workers): which side is the critical path, and whether a thread spins.
  state.counters["caller_cpu_ms"] = 1e3 * best_split.caller;
  state.counters["others_cpu_ms"] = 1e3 * best_split.others;
  if (unpipelined) {
    state.counters["tris_per_s"] = rate_of(c, best.wall);
    state.counters["cpu_ms"] = 1e3 * best.cpu;
    Rates& u = g_unpipelined[threads];
    u.tessera = std::max(u.tessera, rate_of(c, best.wall));
    u.tessera_cpu = std::max(u.tessera_cpu, rate_of(c, best.cpu));
    return;
  }
  const Rates& r = record(state, c, threads, best, false);
  if (r.llvmpipe > 0) state.counters["x_llvmpipe"] = rate_of(c, best.wall) / r.llvmpipe;
  if (r.llvmpipe_cpu > 0) state.counters["x_llvmpipe_cpu"] = r.tessera_cpu / r.llvmpipe_cpu;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--llvmpipe-child=", 17) == 0) {
      const std::string spec = argv[i] + 17;
      const size_t comma = spec.find(',');
      const std::string name = spec.substr(0, comma);
      const Case c = name == "immediate" ? Case::immediate
                     : name == "batched" ? Case::batched
                     : name == "fill"    ? Case::fill
                                         : Case::textured;
      return llvmpipe_child(c, std::atoi(spec.c_str() + comma + 1));
    }
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  g_self = n > 0 ? std::string(self, size_t(n)) : std::string(argv[0]);

  for (int threads : {1, 2})
    for (const bool triad : {false, true})
      benchmark::RegisterBenchmark(fmt::format("bandwidth/{}/threads:{}", triad ? "triad" : "copy", threads).c_str(),
                                   BM_Bandwidth, triad, threads)
          ->UseManualTime()
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
  for (Case c : {Case::immediate, Case::batched, Case::fill, Case::textured})
    for (int threads : {1, 2}) {
      // The peer first, so that the Tessera run can report the ratio.
      benchmark::RegisterBenchmark(fmt::format("{}/llvmpipe/threads:{}", case_name(c), threads).c_str(), BM_Llvmpipe, c,
                                   threads)
          ->UseManualTime()
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
      for (const bool unpipelined : {false, true}) {
        if (unpipelined && c != Case::immediate) continue;
        benchmark::RegisterBenchmark(
            fmt::format("{}/tessera{}/threads:{}", case_name(c), unpipelined ? "_unpipelined" : "", threads).c_str(),
            BM_Tessera, c, threads, unpipelined)
            ->UseManualTime()
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
      }
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const double load_before = load_average();
  benchmark::RunSpecifiedBenchmarks();
  std::printf(
      "\nbest rates (frames of clear + draw + finish; load average %.1f before, %.1f after; bandwidth %.1f GB/s "
      "on 1 thread, %.1f GB/s on 2)\n",
      load_before, load_average(), g_bandwidth[1] / 1e9, g_bandwidth[2] / 1e9);
  std::printf("%-14s %12s %12s %7s %14s %14s %7s %9s\n", "case/threads", "llvmpipe/s", "tessera/s", "ratio",
              "llvmpipe/cpu-s", "tessera/cpu-s", "ratio", "bw_share");
  for (const auto& [name, r] : g_rates) {
    const bool fill = name.rfind("fill", 0) == 0;
    const double bandwidth = g_bandwidth[std::atoi(name.c_str() + name.find('/') + 1)];
    std::printf("%-14s %12.4g %12.4g %7.2f %14.4g %14.4g %7.2f %9s\n", name.c_str(), r.llvmpipe, r.tessera,
                r.llvmpipe > 0 ? r.tessera / r.llvmpipe : 0.0, r.llvmpipe_cpu, r.tessera_cpu,
                r.llvmpipe_cpu > 0 ? r.tessera_cpu / r.llvmpipe_cpu : 0.0,
                fill && bandwidth > 0 ? fmt::format("{:.0f}%", 100 * r.tessera * 12 / bandwidth).c_str() : "");
  }
  for (const auto& [threads, u] : g_unpipelined) {
    const Rates& r = g_rates[key(Case::immediate, threads)];
    std::printf(
        "immediate/%d unpipelined (flush after every batch): %.4g tris/s, %.4g per cpu-s; pipelining gains "
        "%.2fx wall, %.2fx per cpu-s\n",
        threads, u.tessera, u.tessera_cpu, u.tessera > 0 ? r.tessera / u.tessera : 0.0,
        u.tessera_cpu > 0 ? r.tessera_cpu / u.tessera_cpu : 0.0);
  }
  benchmark::Shutdown();
  return 0;
}
