// tessera render SCENE.json|BUILTIN -o IMG: render a scene file (or a built-in scene by name) with the ray tracer or
// the rasterizer.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/scene/raster.hpp"
#include "tessera/scene/trace.hpp"

namespace tessera::cli {
namespace {

enum class Backend { raytrace, raster };

struct RenderArgs {
  std::string scene, output, size;
  Backend backend = Backend::raytrace;
  RasterShadows shadow_method = RasterShadows::map;
  bool shadow_method_given = false;
  std::optional<int> spp, depth;
  uint64_t seed = 0;
};

std::string builtin_list() {
  std::string list;
  for (const auto& name : builtin_scene_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

// Refuses an image over the memory budget. Per pixel: the float image, the depth image and the 8-bit copy (25 bytes
// measured with either backend).
void check_render_memory(Size2 size) {
  MemoryBudget::check(saturating_product({uint64_t(size.width), uint64_t(size.height), 28}),
                      fmt::format("rendering {}x{} pixels", size.width, size.height));
}

void run_render(const RenderArgs& a, const CommonOptions& common) {
  // Every option and the output format are checked before the scene is built or anything is written.
  Size2 size{0, 0};
  if (!a.size.empty()) size = parse_size(a.size, "--size");
  check_render_memory(size);
  if (a.spp && (*a.spp < 1 || *a.spp > SceneImage::kMaxSamples))
    throw InvalidInput(
        fmt::format("--spp: expected a number of samples in [1, {}], got {}", SceneImage::kMaxSamples, *a.spp));
  if (a.depth && (*a.depth < 1 || *a.depth > RenderSettings::kMaxDepth))
    throw InvalidInput(
        fmt::format("--depth: expected a recursion depth in [1, {}], got {}", RenderSettings::kMaxDepth, *a.depth));
  const std::string ext = std::filesystem::path(a.output).extension().string();
  static const std::set<std::string> kFormats = {".png", ".ppm", ".pfm", ".hdr", ".jpg", ".jpeg", ".bmp", ".tga"};
  std::string lower(ext.size(), ' ');
  std::transform(ext.begin(), ext.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (!kFormats.count(lower))
    throw InvalidInput(
        fmt::format("-o {}: expected an image file (.png, .hdr, .pfm, .ppm, .jpg, .bmp, .tga)", a.output));
  if (a.shadow_method_given && a.backend != Backend::raster)
    throw InvalidInput("--shadow-method: only the raster backend has shadow methods; add --backend raster");
  PhaseTimer timer;
  const Scene scene = timer.time("read_s", [&] { return load_scene_or_builtin(a.scene); });
  RenderSettings settings = render_settings(scene);
  if (size.width > 0) settings.width = size.width, settings.height = size.height;
  check_render_memory({settings.width, settings.height});  // a scene file's own size
  if (a.spp) settings.samples = *a.spp;
  if (a.depth) settings.max_depth = *a.depth;
  settings.seed = a.seed;
  settings.progress = !common.quiet;
  // The raster backend shades one sample per pixel, locally: the scene's samples and depth do not apply.
  const int samples = a.backend == Backend::raster ? 1 : settings.samples;
  StatRows figures = {{"width", stat_value(settings.width)},
                      {"height", stat_value(settings.height)},
                      {"pixels", stat_value(double(settings.width) * settings.height)},
                      {"samples", stat_value(samples)},
                      {"objects", stat_value(double(scene.objects.size()))},
                      {"lights", stat_value(double(scene.lights.size()))}};
  ImageRGB image;
  double seconds = 0;  // the rendering's own time: the deprecated `seconds` scripts read
  if (a.backend == Backend::raster) {
    image = timer.time("compute_s",
                       [&] { return rasterize_scene(scene, settings.width, settings.height, a.shadow_method); });
    seconds = timer.seconds("compute_s");
  } else {
    RenderStats stats;
    image = timer.time("compute_s", [&] { return render(to_ray_scene(scene), settings, &stats); });
    seconds = stats.seconds;
    figures.insert(figures.end(), {{"eye_rays", stat_value(double(stats.eye_rays))},
                                   {"rays", stat_value(double(stats.rays))},
                                   {"rays_per_s", stat_value(double(stats.rays) / std::max(stats.seconds, 1e-9))}});
  }
  timer.time("write_s", [&] { write_image(a.output, image, common.write_options()); });
  figures.emplace_back("seconds", stat_value(seconds));
  const StatRows phases = timer.rows();
  figures.insert(figures.end(), phases.begin(), phases.end());
  if (common.stats) print_stats(figures);
}

}  // namespace

void setup_render(CLI::App& cmd, CommonOptions& common) {
  auto a = std::make_shared<RenderArgs>();
  cmd.add_option("scene", a->scene, "Scene file (.json, docs/scene-format.md) or a built-in scene: " + builtin_list())
      ->required();
  cmd.add_option("-o,--output", a->output, "Output image (.png, .hdr, .pfm, .ppm, .jpg)")->required();
  cmd.add_option("--spp", a->spp, "Samples per pixel (default: the scene's)");
  cmd.add_option("--size", a->size, "Image size WxH (default: the scene's)")->check(size_format());
  cmd.add_option("--depth", a->depth, "Recursion depth, 1 = eye rays only (default: the scene's)");
  cmd.add_option("--seed", a->seed, "Seed of the sampling patterns (same seed, same picture)");
  add_choice(
      cmd, "--backend", a->backend, {{"raytrace", Backend::raytrace}, {"raster", Backend::raster}},
      "Renderer: raytrace (everything) or raster (z-buffer, local shading, one bounce of reflection by cube maps, "
      "glass blended without refraction; docs/raytrace.md)");
  CLI::Option* shadows = add_choice(cmd, "--shadow-method", a->shadow_method,
                                    {{"map", RasterShadows::map}, {"volumes", RasterShadows::volumes}},
                                    "Raster shadows of every light: map (a shadow map per light) or volumes (stencil "
                                    "shadow volumes)");
  add_srgb_option(cmd, common);
  cmd.callback([a, shadows, &common] {
    a->shadow_method_given = shadows->count() > 0;
    run_render(*a, common);
  });
}

}  // namespace tessera::cli
