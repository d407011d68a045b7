// tessera demo [-o DIR] [--data DIR]: the embedded default, renders the built-in scenes (quickly: half size, few
// samples) and the gallery into DIR.
#include <fmt/format.h>

#include "command.hpp"
#include "data_option.hpp"
#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/scene/trace.hpp"

namespace tessera::cli {
namespace {

/// Renders every built-in scene to DIR/scene_<name>.png at half its size with at most 4 samples per pixel.
size_t render_builtin_scenes(const std::filesystem::path& dir, bool quiet, const WriteOptions& write) {
  std::filesystem::create_directories(dir);
  size_t count = 0;
  for (const auto& name : builtin_scene_names()) {
    const Scene scene = builtin_scene(name);
    RenderSettings s = render_settings(scene);
    s.width = std::max(1, s.width / 2);
    s.height = std::max(1, s.height / 2);
    s.samples = std::min(s.samples, 4);
    s.progress = !quiet;
    write_image(dir / ("scene_" + name + ".png"), render(to_ray_scene(scene), s), write);
    ++count;
  }
  return count;
}

}  // namespace

void setup_demo(CLI::App& cmd, CommonOptions& common) {
  struct Options {
    std::string output = "out";
    std::string data;
  };
  auto opt = std::make_shared<Options>();
  cmd.add_option("-o,--output", opt->output, "Folder for the pictures")->capture_default_str();
  add_data_option(cmd, opt->data);
  add_srgb_option(cmd, common);
  cmd.callback([opt, &common] {
    const examples::DataFolder data = examples::locate_shared_data(opt->data);
    const size_t scenes = render_builtin_scenes(opt->output, common.quiet, common.write_options());
    const examples::RunSummary run = examples::run_examples(opt->output, {{}, data, common.write_options()});
    const size_t n = run.pictures + scenes;
    if (common.stats) {
      print_stats({{"pictures", stat_value(double(n))},
                   {"scenes", stat_value(double(scenes))},
                   {"stand_ins", stat_value(double(run.stand_ins))}});
    } else {
      fmt::print("{} pictures ({} built-in scenes) written to {}/ (open {}/index.html){}\n", n, scenes, opt->output,
                 opt->output, stand_in_note(run, data));
    }
  });
}

}  // namespace tessera::cli
