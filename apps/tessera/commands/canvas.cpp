// tessera canvas render IN.svg -o OUT.png [--size WxH] [--no-antialias] [--background COLOR] [--srgb]: rasterizes an
// SVG drawing (the subset of docs/svg.md) with the 2D canvas's path fill and strokes.
#include <fmt/format.h>

#include <cstdio>
#include <memory>

#include "command.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera::cli {
namespace {

void setup_render(CLI::App& cmd, CommonOptions& common) {
  struct Options {
    std::string input, output, size, background;
    bool no_antialias = false;
    double tolerance = 0.1;
  };
  auto opt = std::make_shared<Options>();
  cmd.add_option("input", opt->input, "The SVG file")->required();
  cmd.add_option("-o,--output", opt->output, "The image to write (PNG keeps alpha; the extension picks the format)")
      ->required();
  cmd.add_option("--size", opt->size, "Output size WxH in pixels (default: the SVG's width and height)")
      ->check(size_format());
  cmd.add_flag("--no-antialias", opt->no_antialias, "Fill pixels whose center is inside instead of area coverage");
  cmd.add_option("--background", opt->background,
                 "Opaque background: a color name as SVG's (white), #rrggbb or r,g,b in [0,1] (default: transparent)")
      ->check(color_format());
  cmd.add_option("--tolerance", opt->tolerance, "Curve flattening tolerance in pixels")
      ->check(CLI::Range(1e-6, 1e6))
      ->capture_default_str();
  add_srgb_option(cmd, common);
  cmd.callback([opt, &common] {
    // Every option and the whole document are checked before anything is written; write_image is atomic.
    SvgRenderOptions options;
    if (!opt->size.empty()) {
      const Size2 size = parse_size(opt->size, "--size");
      options.width = size.width;
      options.height = size.height;
    }
    if (!opt->background.empty()) {
      const Rgb c = parse_color(opt->background, "--background");
      options.background = Vec4f(c.r, c.g, c.b, 1);
    }
    options.antialias = !opt->no_antialias;
    options.tolerance = opt->tolerance;
    PhaseTimer timer;
    const SvgDocument document = timer.time("read_s", [&] { return load_svg(opt->input); });
    for (const std::string& warning : document.warnings) fmt::print(stderr, "tessera: warning: {}\n", warning);
    const ImageRGBA image = timer.time("compute_s", [&] { return render_svg(document, options); });
    timer.time("write_s", [&] { write_image(opt->output, image, common.write_options()); });
    if (!common.stats) return;
    StatRows rows{{"width", stat_value(image.width())},
                  {"height", stat_value(image.height())},
                  {"pixels", stat_value(double(image.width()) * image.height())},
                  {"shapes", stat_value(double(document.shapes.size()))},
                  {"warnings", stat_value(double(document.warnings.size()))},
                  // Deprecated alias: reading and rendering, as before read_s and compute_s.
                  {"seconds", stat_value(timer.seconds("read_s") + timer.seconds("compute_s"))}};
    for (const auto& row : timer.rows()) rows.push_back(row);
    print_stats(rows);
  });
}

}  // namespace

void setup_canvas(CLI::App& canvas, CommonOptions& common) {
  canvas.require_subcommand(1);
  setup_render(*canvas.add_subcommand("render", "Rasterize an SVG drawing into an image"), common);
}

}  // namespace tessera::cli
