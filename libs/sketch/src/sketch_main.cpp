// sketch_main: the runner's flags for a user's sketch program (tessera_add_sketch), parsed with CLI11.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/sketch/runner.hpp"

namespace tessera {

int sketch_main(int argc, char** argv, const SketchFactory& factory) {
  const auto start = std::chrono::steady_clock::now();
  const std::string program = argc > 0 ? std::filesystem::path(argv[0]).filename().string() : "sketch";
  CLI::App app{"A Tessera sketch: runs in a window, or headless with -o (docs/sketch.md)", program};
  RunOptions options;
  int frames = 0;
  double seconds = 0, fps = 0;
  std::string size, output, input;
  bool window = false, headless = false, stats = false;
  app.add_option("--frames", frames, "Stop after N frames")->check(CLI::Range(1, 1 << 30));
  app.add_option("--seconds", seconds, "Stop after S seconds (headless: S x fps frames)")->check(CLI::Range(1e-6, 1e9));
  app.add_option("--fps", fps, "Frame rate, replacing the sketch's frame_rate()")->check(CLI::Range(1e-6, 1000.0));
  app.add_option("-o,--output", output, "Write out.gif, out.mp4|.webm, dir/, frame-####.png, or picture.png");
  app.add_option("--size", size, "WxH, replacing the size() of the sketch");
  auto* w = app.add_flag("--window", window, "Open a window (the default without -o)");
  app.add_flag("--headless", headless, "No window: a fixed frame rate, deterministic (the default with -o)")
      ->excludes(w);
  app.add_option("--input", input, "An input script: one event per line, 'FRAME EVENT ARGS'")->check(CLI::ExistingFile);
  app.add_option("--threads", options.threads, "Worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  app.add_option("--seed", options.seed, "Seed of random() and noise()");
  app.add_flag("--srgb", options.srgb, "Encode 8-bit frames with the sRGB curve");
  app.add_flag("--stats", stats, "Print width, height, pixels, frames, draws and timings as key=value lines");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    fmt::print(stderr, "{}: error: {}\nrun with --help for the options\n", program, e.what());
    return 2;
  }
  try {
    if (frames > 0) options.frames = frames;
    if (seconds > 0) options.seconds = seconds;
    if (fps > 0) options.fps = fps;
    if (!size.empty()) {
      const Size2 s = parse_size(size, "--size");
      options.size = {s.width, s.height};
    }
    options.output = output;
    options.input = input;
    options.mode = run_mode(window, headless, options.output);
    const std::unique_ptr<Sketch> sketch = factory();
    const RunResult r = run_sketch(*sketch, options);
    // The keys of `tessera sketch --stats` (docs/cli.md's vocabulary).
    if (stats)
      fmt::print(
          "width={}\nheight={}\npixels={}\nframes={}\ndraws={}\ncompute_s={:.6f}\nwrite_s={:.6f}\ntotal_s={:.6f}\n",
          r.width, r.height, int64_t(r.width) * r.height, r.frames, r.draws, r.draw_seconds, r.write_seconds,
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}: error: {}\n", program, e.what());
    return 1;
  }
  return 0;
}

}  // namespace tessera
