// tessera sketch NAME|--list [--frames N | --seconds S] [--fps F] [-o out.gif|out.mp4|dir/|pic.png] [--size WxH]
// [--window|--headless] [--input script.txt] [--demo] [--seed N] [--srgb]: runs a built-in Processing sketch
// (libs/sketch's registry) in a window or headless (docs/sketch.md). The flags are the runner's, as sketch_main's.
#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/sketch/runner.hpp"

namespace tessera::cli {

void setup_sketch(CLI::App& cmd, CommonOptions& common) {
  struct Options {
    std::string name, output, size, input;
    bool list = false, window = false, headless = false, demo = false;
    int frames = 0;
    double seconds = 0, fps = 0;
    uint64_t seed = 0;
  };
  auto opt = std::make_shared<Options>();
  std::vector<std::string> names;
  for (const SketchInfo& info : builtin_sketches()) names.emplace_back(info.name);
  cmd.add_option("name", opt->name, "The built-in sketch (--list shows them)")->check(CLI::IsMember(names));
  cmd.add_flag("--list", opt->list, "List the built-in sketches with a line each");
  auto* frames = cmd.add_option("--frames", opt->frames,
                                "Stop after N frames (headless default: the sketch's demo "
                                "length)")
                     ->check(CLI::Range(1, 1 << 30));
  cmd.add_option("--seconds", opt->seconds, "Stop after S seconds (headless: S x fps frames; window: wall time)")
      ->check(positive())
      ->excludes(frames);
  cmd.add_option("--fps", opt->fps, "Frame rate, replacing the sketch's (default 60)")->check(CLI::Range(1e-6, 1000.0));
  cmd.add_option("-o,--output", opt->output,
                 "Write every frame to out.gif, out.mp4|.webm|.mov|.mkv (ffmpeg), dir/ or frame-####.png; any other "
                 "image name gets the last frame");
  cmd.add_option("--size", opt->size, "WxH, replacing the sketch's size()")->check(size_format());
  auto* window = cmd.add_flag("--window", opt->window, "Open a window (the default without -o)");
  cmd.add_flag("--headless", opt->headless, "No window: a fixed frame rate, deterministic (the default with -o)")
      ->excludes(window);
  cmd.add_option("--input", opt->input, "An input script: one event per line, 'FRAME EVENT ARGS' (docs/sketch.md)")
      ->check(CLI::ExistingFile);
  cmd.add_flag("--demo", opt->demo, "Play the sketch's demo input (the mouse and keys of its gallery animation)");
  cmd.add_option("--seed", opt->seed, "Seed of the sketch's random() and noise()")->capture_default_str();
  add_srgb_option(cmd, common);
  cmd.callback([opt, &common] {
    if (opt->list) {
      for (const SketchInfo& info : builtin_sketches()) fmt::print("{:<16} {}\n", info.name, info.description);
      if (common.stats) print_stats({{"sketches", stat_value(double(builtin_sketches().size()))}});
      return;
    }
    if (opt->name.empty()) throw CLI::RequiredError("a sketch NAME (or --list)");
    const SketchInfo& info = *find_sketch(opt->name);
    RunOptions options;
    options.mode = run_mode(opt->window, opt->headless, opt->output);
    if (opt->frames > 0) options.frames = opt->frames;
    if (opt->seconds > 0) options.seconds = opt->seconds;
    if (!options.frames && !options.seconds && options.mode == RunMode::headless) options.frames = info.demo_frames;
    if (opt->fps > 0) options.fps = opt->fps;
    if (!opt->size.empty()) {
      const Size2 size = parse_size(opt->size, "--size");
      options.size = std::pair{size.width, size.height};
    }
    options.output = opt->output;
    options.input = opt->input;
    if (opt->demo) options.events = parse_input_script(info.demo_input, info.name);
    options.threads = common.threads;
    options.seed = opt->seed;
    options.srgb = common.srgb;
    options.title = fmt::format("tessera sketch {}", info.name);
    const std::unique_ptr<Sketch> sketch = info.make();
    const RunResult r = run_sketch(*sketch, options);
    if (!common.stats) return;
    print_stats({{"width", stat_value(r.width)},
                 {"height", stat_value(r.height)},
                 {"pixels", stat_value(double(r.width) * r.height)},
                 {"frames", stat_value(r.frames)},
                 {"draws", stat_value(r.draws)},
                 {"compute_s", stat_value(r.draw_seconds)},
                 {"write_s", stat_value(r.write_seconds)}});
  });
}

}  // namespace tessera::cli
