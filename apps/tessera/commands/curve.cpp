// tessera curve --points x,y,x,y,... -o OUT.png|OUT.svg [--steps N] [--t T] [--split] [--size WxH] [--srgb]: draws a
// Bezier curve of any degree with its control polygon, convex hull and de Casteljau construction at t (docs/curves.md).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>

#include "command.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/curves/figure.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera::cli {
namespace {

struct CurveOptions {
  std::string points, output, size = "400x400";
  int steps = 0;
  double t = 0.5;
  bool split = false;
};

Bezier2 parse_curve(const std::string& text) {
  const std::vector<double> v = parse_doubles(text, 0, "--points");
  if (v.size() % 2 != 0 || v.size() < 4 || v.size() > 2000)
    throw InvalidInput(fmt::format("--points: expected 2 to 1000 x,y pairs, got {} numbers", v.size()));
  Bezier2 curve;
  for (size_t i = 0; i < v.size(); i += 2) curve.points.emplace_back(v[i], v[i + 1]);
  return curve;
}

void run_curve(const CurveOptions& opt, const CommonOptions& common) {
  const Size2 size = parse_size(opt.size, "--size");
  // Per pixel: the float RGBA picture (16 bytes) and the 8-bit copy a writer makes (4), with a float to spare.
  MemoryBudget::check(saturating_product({uint64_t(size.width), uint64_t(size.height), 24}),
                      fmt::format("drawing {}x{} pixels", size.width, size.height));
  CurveFigure figure{.width = size.width, .height = size.height, .curves = {parse_curve(opt.points)}};
  figure.construction = opt.t;
  figure.show_split = opt.split;
  figure.steps = opt.steps;
  PhaseTimer timer;
  const std::string svg = timer.time("compute_s", [&] { return curve_figure_svg(figure); });
  std::string ext = std::filesystem::path(opt.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".svg") {
    timer.time("write_s", [&] { write_file_atomic(opt.output, svg); });
  } else {
    // Pixels through raster2d's SVG renderer: the same picture as the SVG, antialiased.
    const ImageRGBA image =
        timer.time("compute_s", [&] { return render_svg(parse_svg(svg, "curve figure"), SvgRenderOptions{}); });
    timer.time("write_s", [&] { write_image(opt.output, image, common.write_options()); });
  }
  if (common.stats) {
    const Bezier2& curve = figure.curves.front();
    std::vector<Vec2> polyline{curve.front()};
    flatten(curve, 1e-3, polyline);
    double length = 0;
    for (size_t i = 1; i < polyline.size(); ++i) length += glm::length(polyline[i] - polyline[i - 1]);
    StatRows rows{{"degree", stat_value(curve.degree())},
                  {"length", stat_value(length)},
                  {"width", stat_value(size.width)},
                  {"height", stat_value(size.height)},
                  {"pixels", stat_value(double(size.width) * size.height)}};
    for (const auto& row : timer.rows()) rows.push_back(row);
    print_stats(rows);
  }
}

}  // namespace

void setup_curve(CLI::App& curve, CommonOptions& common) {
  auto opt = std::make_shared<CurveOptions>();
  curve.add_option("--points", opt->points, "Control points x,y,x,y,... in pixels (2 or more; y down)")
      ->required()
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              parse_curve(text);
              return std::string();
            } catch (const InvalidInput& e) {
              const std::string message = e.what();  // CLI11 names the option itself
              return message.rfind("--points: ", 0) == 0 ? message.substr(10) : message;
            }
          },
          "X,Y,..."));
  curve.add_option("-o,--output", opt->output, "Output picture: .svg, or an image (.png, .ppm, .jpg)")->required();
  curve.add_option("--steps", opt->steps, "Draw the curve as N segments by forward differences (0: adaptive)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  curve.add_option("--t", opt->t, "Parameter of the de Casteljau construction")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  curve.add_flag("--split", opt->split, "Also draw the control polygons of the two halves split at --t");
  curve.add_option("--size", opt->size, "Picture size WxH")->check(size_format())->capture_default_str();
  add_srgb_option(curve, common);
  curve.footer(
      "Stats (--stats): degree length width height pixels compute_s write_s total_s.\n"
      "Example: tessera curve --points 40,360,80,40,320,40,360,360 --t 0.75 --split -o curve.png");
  curve.callback([opt, &common] { run_curve(*opt, common); });
}

}  // namespace tessera::cli
