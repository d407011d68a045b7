// GLSL programs: Tessera's executor on the quad stage against Mesa's llvmpipe (OSMesa, a compatibility context) in the
// same run, on the same programs and scenes, at 1280 x 720 with 1 and 2 threads: the notes' texture program (a
// 512 x 512 texture repeated 4 times over a screen-filling quad in perspective, trilinear MIPmaps) and the per-pixel
// Phong program (examples/shaders/phong.*, a sphere filling the screen). llvmpipe reads LP_NUM_THREADS once per
// process, so each llvmpipe measurement runs in a child process (this program, --llvmpipe-child=CASE,THREADS). The
// counter x_llvmpipe is Tessera's frame rate over llvmpipe's (best frame of each); a table at the end repeats them.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>

#include "bench_util.hpp"
#include "osmesa_glsl.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/glsl/program.hpp"
#include "tessera/math/transform.hpp"

namespace {

using namespace tessera;

constexpr int kWidth = 1280, kHeight = 720, kFrames = 16;
enum class Case { texture, phong };
const char* case_name(Case c) { return c == Case::texture ? "notes_texture" : "phong"; }

/// The scene of a case, as the reference's draw (Tessera's is built from it).
reference::GlslDraw scene(Case c) {
  reference::GlslDraw d;
  const std::string dir = std::string(TESSERA_SOURCE_DIR) + "/examples/shaders/";
  d.vertex_source = read_file(dir + case_name(c) + ".vert");
  d.fragment_source = read_file(dir + case_name(c) + ".frag");
  d.projection = Mat4f(perspective(glm::radians(50.0), double(kWidth) / kHeight, 0.5, 50.0));
  if (c == Case::texture) {
    // A quad tilted away from the viewer, filling the screen: magnified near, minified far.
    d.positions = {{-2.4f, -1.4f, -1.6f}, {2.4f, -1.4f, -1.6f}, {2.4f, 1.6f, -4.2f}, {-2.4f, 1.6f, -4.2f}};
    d.uvs = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    d.indices = {0, 1, 2, 0, 2, 3};
    reference::GlslTexture t;
    t.width = t.height = 512;
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 512; ++x)
        t.rgba.insert(t.rgba.end(),
                      {uint8_t(x ^ y), uint8_t((x * 3) & 255), uint8_t(((x / 32 + y / 32) & 1) * 200), 255});
    t.filter = reference::GlFilter::linear_mipmap_linear;
    d.textures.emplace_back(0, t);
    d.uniforms.push_back({"myTexture", {}, {0}});
  } else {
    const int rings = 96, segments = 192;
    for (int r = 0; r <= rings; ++r)
      for (int s = 0; s <= segments; ++s) {
        const float theta = float(M_PI) * float(r) / rings, phi = 2 * float(M_PI) * float(s) / segments;
        const Vec3f n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
        d.positions.push_back(n * 1.4f + Vec3f(0, 0, -3));
        d.normals.push_back(n);
      }
    for (int r = 0; r < rings; ++r)
      for (int s = 0; s < segments; ++s) {
        const auto a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments) + 1;
        d.indices.insert(d.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
      }
    d.lights.push_back({Vec4f(2, 3, 4, 1), Vec4f(0.1f, 0.1f, 0.1f, 1), Vec4f(0.9f, 0.85f, 0.8f, 1), Vec4f(1)});
    d.material = {Vec4f(0.2f, 0.2f, 0.25f, 1), Vec4f(0.8f, 0.5f, 0.3f, 1), Vec4f(0.6f, 0.6f, 0.6f, 1),
                  Vec4f(0, 0, 0, 1), 40};
  }
  return d;
}

/// The same scene as a Tessera program and its inputs.
struct TesseraScene {
  reference::GlslDraw d;
  glsl::Program program;
  glsl::ProgramInputs inputs;
};

std::unique_ptr<TesseraScene> tessera_scene(Case c) {
  reference::GlslDraw d = scene(c);
  glsl::Program p = glsl::Program::compile({d.vertex_source, "v"}, {d.fragment_source, "f"});
  glsl::FixedFunctionState state;
  state.projection = d.projection;
  if (!d.lights.empty()) {
    state.lights[0] = {d.lights[0].ambient, d.lights[0].diffuse, d.lights[0].specular, d.lights[0].position};
    state.front_material = {d.material.ambient, d.material.diffuse, d.material.specular, d.material.emission,
                            d.material.shininess};
  }
  p.set_fixed_function(state);
  for (const auto& u : d.uniforms) p.set_uniform(u.name, u.ints);
  for (const auto& [unit, t] : d.textures) {
    ImageRGBA8 image(t.width, t.height);
    for (int y = 0; y < t.height; ++y)  // GL rows bottom first
      std::memcpy(&image(0, t.height - 1 - y), &t.rgba[size_t(y) * size_t(t.width) * 4], size_t(t.width) * 4);
    p.bind_texture(unit, std::make_shared<Texture2D>(image, Sampler{.filter = Filter::trilinear}));
  }
  auto s = std::unique_ptr<TesseraScene>(new TesseraScene{std::move(d), std::move(p), {}});
  s->inputs.positions = s->d.positions;
  s->inputs.normals = s->d.normals;
  s->inputs.uvs = s->d.uvs;
  return s;
}

std::string g_self;
std::map<std::string, double> g_llvmpipe, g_tessera;  // best frame seconds by "case/threads"

int llvmpipe_child(Case c) {
  reference::GlslRenderer renderer(scene(c), kWidth, kHeight);
  double best = 1e30;
  for (int frame = 0; frame < kFrames; ++frame) best = std::min(best, renderer.time_draws(1) / 1000);
  std::printf("llvmpipe seconds=%.9g\n", best);
  return 0;
}

void BM_Llvmpipe(benchmark::State& state, Case c, int threads) {
  for (auto _ : state) {
    std::string output;
    const int status = bench::run_command(
        fmt::format("LP_NUM_THREADS={} '{}' --llvmpipe-child={} 2>&1", threads, g_self, int(c)), output);
    const size_t at = output.find("llvmpipe seconds=");
    if (status != 0 || at == std::string::npos) {
      state.SkipWithError(("llvmpipe child failed: " + output.substr(0, 200)).c_str());
      return;
    }
    const double seconds = std::strtod(output.c_str() + at + std::strlen("llvmpipe seconds="), nullptr);
    state.SetIterationTime(seconds);
    g_llvmpipe[fmt::format("{}/{}", case_name(c), threads)] = seconds;
  }
  state.counters["pixels"] = kWidth * kHeight;
}

void BM_Tessera(benchmark::State& state, Case c, int threads) {
  const auto s = tessera_scene(c);
  ThreadLimit limit(threads);
  raster3d::Framebuffer fb(kWidth, kHeight);
  double best = 1e30;
  for (auto _ : state) {
    for (int frame = 0; frame < kFrames; ++frame) {
      const auto t0 = std::chrono::steady_clock::now();
      fb.clear(Vec3f(0));
      s->program.draw_triangles(fb, raster3d::RasterState{}, s->inputs, s->d.indices);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (frame > 0) best = std::min(best, seconds);  // frame 0 warms up
    }
    state.SetIterationTime(best);
  }
  const std::string key = fmt::format("{}/{}", case_name(c), threads);
  g_tessera[key] = best;
  if (g_llvmpipe.count(key)) state.counters["x_llvmpipe"] = g_llvmpipe[key] / best;
}

}  // namespace

int main(int argc, char** argv) {
  g_self = argv[0];
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--llvmpipe-child=", 17) == 0) return llvmpipe_child(Case(std::atoi(argv[i] + 17)));
  for (const Case c : {Case::texture, Case::phong})
    for (const int threads : {1, 2}) {
      benchmark::RegisterBenchmark(fmt::format("{}/llvmpipe/threads:{}", case_name(c), threads).c_str(), BM_Llvmpipe, c,
                                   threads)
          ->UseManualTime()
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(fmt::format("{}/tessera/threads:{}", case_name(c), threads).c_str(), BM_Tessera, c,
                                   threads)
          ->UseManualTime()
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  std::printf("\n%-18s %12s %12s %8s   (best frame, 1280x720; load average %.2f)\n", "case/threads", "llvmpipe ms",
              "tessera ms", "ratio", bench::load_average());
  for (const auto& [key, seconds] : g_tessera)
    if (g_llvmpipe.count(key))
      std::printf("%-18s %12.2f %12.2f %7.2fx\n", key.c_str(), 1e3 * g_llvmpipe[key], 1e3 * seconds,
                  g_llvmpipe[key] / seconds);
  return 0;
}
