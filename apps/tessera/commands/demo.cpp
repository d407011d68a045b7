// tessera demo [-o DIR]: the embedded default, renders the built-in scenes (quickly: half size, few samples) and the
// gallery into DIR.
#include <fmt/format.h>

#include "command.hpp"
#include "gallery.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/scene/trace.hpp"

namespace tessera::cli {
namespace {

/// Renders every built-in scene to DIR/scene_<name>.png at half its size with at most 4 samples per pixel.
size_t render_builtin_scenes(const std::filesystem::path& dir, bool quiet) {
  std::filesystem::create_directories(dir);
  size_t count = 0;
  for (const auto& name : builtin_scene_names()) {
    const Scene scene = builtin_scene(name);
    RenderSettings s = render_settings(scene);
    s.width = std::max(1, s.width / 2);
    s.height = std::max(1, s.height / 2);
    s.samples = std::min(s.samples, 4);
    s.progress = !quiet;
    write_image(dir / ("scene_" + name + ".png"), render(to_ray_scene(scene), s));
    ++count;
  }
  return count;
}

}  // namespace

void setup_demo(CLI::App& cmd, CommonOptions& common) {
  auto output = std::make_shared<std::string>("out");
  cmd.add_option("-o,--output", *output, "Folder for the pictures")->capture_default_str();
  cmd.callback([output, &common] {
    const ThreadLimit limit(common.threads);
    const size_t scenes = render_builtin_scenes(*output, common.quiet);
    const size_t n = examples::run_examples(*output) + scenes;
    if (common.stats)
      print_stats({{"pictures", stat_value(double(n))}, {"scenes", stat_value(double(scenes))}});
    else
      fmt::print("{} pictures ({} built-in scenes) written to {}/ (open {}/index.html)\n", n, scenes, *output, *output);
  });
}

}  // namespace tessera::cli
