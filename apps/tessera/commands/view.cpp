// tessera view FILE [--headless] [--orbit N] [-o turntable.gif|picture.png] [--size WxH] [--input script.txt]
// [--frames N] [--fps F] [--shading NAME] [--texture IMG] [--vertex-shader F --fragment-shader F [--uniform N=V]]
// [--samples N] [--no-status]: the interactive viewer
// (libs/view, docs/view.md), a 3D sketch run by the sketch runner in a window or headless.
#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/sketch/runner.hpp"
#include "tessera/view/viewer.hpp"

namespace tessera::cli {

void setup_view(CLI::App& cmd, CommonOptions& common) {
  struct Options {
    std::string file, output, size = "1280x720", input, texture, vertex_shader, fragment_shader;
    std::vector<std::string> uniforms;
    bool window = false, headless = false, no_status = false;
    int orbit = 0, frames = 0, samples = 2, up_axis = -1;
    double fps = 0;
    ViewShading shading = ViewShading::gouraud;
  };
  auto opt = std::make_shared<Options>();
  cmd.add_option("file", opt->file,
                 "A mesh (.obj .ply .off .stl), a scene (.json or a built-in name), a volume (.nrrd .nhdr .mhd or "
                 "sphere:N ...) or Bezier patches (.bpt)")
      ->required();
  auto* window = cmd.add_flag("--window", opt->window, "Open a window (the default without -o)");
  cmd.add_flag("--headless", opt->headless, "No window: render frames at a fixed rate (the default with -o)")
      ->excludes(window);
  cmd.add_option("--orbit", opt->orbit, "A turntable: N frames, one full turn about the vertical")
      ->check(CLI::Range(1, 100000));
  cmd.add_option("-o,--output", opt->output,
                 "Write every frame to out.gif, out.mp4|.webm (ffmpeg), dir/ or frame-####.png; any other image name "
                 "gets the last frame");
  cmd.add_option("--size", opt->size, "The picture's size WxH")->check(size_format())->capture_default_str();
  cmd.add_option("--input", opt->input, "An input script: one event per line, 'FRAME EVENT ARGS' (docs/sketch.md)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--frames", opt->frames, "Stop after N frames (headless default: the turntable's, else until idle)")
      ->check(CLI::Range(1, 1 << 30));
  cmd.add_option("--fps", opt->fps, "Frame rate (default 60; a turntable's GIF 30)")->check(CLI::Range(1e-6, 1000.0));
  std::vector<std::pair<std::string, ViewShading>> shadings;  // named as the status line names them
  for (int k = 0; k <= int(ViewShading::normals); ++k)
    shadings.emplace_back(shading_name(ViewShading(k)), ViewShading(k));
  add_choice(cmd, "--shading", opt->shading, shadings, "The first shading of a surface (keys 1-6 change it)");
  add_choice(cmd, "--up-axis", opt->up_axis, {{"y", 1}, {"z", 2}},
             "The model's up axis: the home view's vertical and the turntable's axis (default: z for .bpt patches, "
             "y otherwise)");
  cmd.add_option("--texture", opt->texture, "The image key t maps on surfaces with uvs (default: a checkerboard)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--vertex-shader", opt->vertex_shader,
                 "GLSL vertex shader drawing the surface (with --fragment-shader; in a window both files are compiled "
                 "again when they change on disk)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--fragment-shader", opt->fragment_shader, "GLSL fragment shader (with --vertex-shader)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--uniform", opt->uniforms, "A uniform of the program: name=v1,v2,...; repeat for more");
  cmd.add_option("--samples", opt->samples, "The progressive ray tracer's samples per pixel per frame")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd.add_flag("--no-status", opt->no_status, "No status line at the bottom of the picture");
  add_srgb_option(cmd, common);
  cmd.callback([opt, &common] {
    if (opt->vertex_shader.empty() != opt->fragment_shader.empty())
      throw CLI::ValidationError("--vertex-shader and --fragment-shader", "a program needs both");
    if (!opt->uniforms.empty() && opt->vertex_shader.empty())
      throw CLI::ValidationError("--uniform", "sets a program's uniform; add --vertex-shader and --fragment-shader");
    PhaseTimer timer;
    Viewable viewable = timer.time("read_s", [&] { return read_viewable(opt->file); });
    RunOptions run;
    run.mode = run_mode(opt->window, opt->headless, opt->output);
    const Size2 size = parse_size(opt->size, "--size");
    ViewerOptions options;
    options.width = size.width;
    options.height = size.height;
    options.orbit_frames = opt->orbit;
    options.shading = opt->shading;
    options.up_axis = opt->up_axis;
    options.texture = opt->texture;
    options.vertex_shader = opt->vertex_shader;
    options.fragment_shader = opt->fragment_shader;
    options.uniforms = opt->uniforms;
    options.watch_shaders = run.mode == RunMode::window && !opt->vertex_shader.empty();
    options.status_line = !opt->no_status;
    options.frame_time = run.mode == RunMode::window;
    options.trace_samples = opt->samples;
    if (opt->frames > 0)
      run.frames = opt->frames;
    else if (opt->orbit > 0 && run.mode == RunMode::headless)
      run.frames = opt->orbit;
    if (opt->fps > 0)
      run.fps = opt->fps;
    else if (opt->orbit > 0)
      run.fps = 30;
    run.output = opt->output;
    run.input = opt->input;
    run.threads = common.threads;
    run.srgb = common.srgb;
    run.title = fmt::format("tessera view {}", opt->file);
    Viewer viewer(std::move(viewable), options);
    const RunResult r = run_sketch(viewer, run);  // compute_s below is the runner's draw time
    if (!common.stats) return;
    const ViewerStats& s = viewer.stats();
    StatRows rows = {{"width", stat_value(r.width)},
                     {"height", stat_value(r.height)},
                     {"pixels", stat_value(double(r.width) * r.height)},
                     {"triangles", stat_value(double(s.triangles))},
                     {"frames", stat_value(r.frames)},
                     {"renders", stat_value(s.renders)},
                     {"render_s", stat_value(s.render_seconds)},
                     {"frames_per_s", stat_value(s.render_seconds > 0 ? s.renders / s.render_seconds : 0)},
                     {"read_s", stat_value(timer.seconds("read_s"))},
                     {"compute_s", stat_value(r.draw_seconds)},
                     {"write_s", stat_value(r.write_seconds)}};
    print_stats(rows);
  });
}

}  // namespace tessera::cli
