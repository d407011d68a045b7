// tessera fractal mandelbrot|julia|cantor|sierpinski|koch|hilbert|peano|terrain -o OUT [options] [--stats] and
// tessera fractal dimension IMAGE [--stats] (docs/fractal.md). Numbers are parsed strictly: a bad number, size or
// depth is an error (exit 1) naming the option.
#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <string>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/fractal/coloring.hpp"
#include "tessera/fractal/dimension.hpp"
#include "tessera/fractal/draw.hpp"
#include "tessera/fractal/escape_time.hpp"
#include "tessera/fractal/self_similar.hpp"
#include "tessera/fractal/terrain.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera::cli {
namespace {

// Every option as text, parsed when the command runs (so that bad values are tessera errors, exit 1).
struct FractalOptions {
  std::string output;
  std::string size;
  std::string center, scale, iterations = "1000", palette = "classic", simd = "auto", c = "-0.8,0.156";
  std::string depth, shape, line_width = "1", margin;
  std::string method = "diamond-square", roughness = "0.5", seed = "1", height_scale = "0.5";
  std::string image, threshold = "0.5", min_box = "2", max_box = "0", factor = "2";
  bool invert = false;
};

int parse_bounded(const std::string& text, const char* what, long long lo, long long hi) {
  const long long v = parse_int(text, what);
  if (v < lo || v > hi) throw InvalidInput(fmt::format("{} must be in [{}, {}], got {}", what, lo, hi, v));
  return int(v);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void write_picture(const std::string& path, const ImageRGBA& picture) { write_image(path, picture); }

/// The escape-time view and options shared by mandelbrot and julia.
std::pair<ComplexView, EscapeOptions> escape_setup(const FractalOptions& o) {
  const Size2 size = parse_size(o.size, "--size");
  const auto center = parse_doubles(o.center, 2, "--center");
  ComplexView view{{center[0], center[1]}, parse_double(o.scale, "--scale"), size.width, size.height};
  EscapeOptions options;
  options.max_iterations = parse_bounded(o.iterations, "--iterations", 1, 100000000);
  options.simd = parse_simd_path(o.simd);
  return {view, options};
}

void add_escape_options(CLI::App& sub, FractalOptions& o, const char* center, const char* scale) {
  o.center = center, o.scale = scale, o.size = "800x600";
  sub.add_option("--center", o.center, "Middle of the view in the complex plane, re,im")->capture_default_str();
  sub.add_option("--scale", o.scale, "Width of the view in the complex plane")->capture_default_str();
  sub.add_option("--size", o.size, "Picture size WxH")->capture_default_str();
  sub.add_option("--iterations", o.iterations, "Iteration cap")->capture_default_str();
  sub.add_option("--palette", o.palette, "classic, fire, ocean or gray")->capture_default_str();
  sub.add_option("--simd", o.simd, "auto, scalar, avx2 or avx512")->capture_default_str();
}

/// A self-similar picture's subcommand: -o, --depth, --size, --margin, and a run function.
CLI::App* add_figure(CLI::App& fractal, const char* name, const char* help, const std::shared_ptr<FractalOptions>& o,
                     const char* depth, const char* size) {
  CLI::App* sub = fractal.add_subcommand(name, help);
  o->depth = depth, o->size = size, o->margin = "0";
  sub->add_option("-o,--output", o->output, "Output picture (PNG, PPM, JPG, ...)")->required();
  sub->add_option("--depth", o->depth, "Subdivision depth")->capture_default_str();
  sub->add_option("--size", o->size, "Picture size WxH")->capture_default_str();
  sub->add_option("--margin", o->margin, "Free border in pixels")->capture_default_str();
  return sub;
}

PictureFrame square_frame(const FractalOptions& o) {
  const Size2 size = parse_size(o.size, "--size");
  return PictureFrame{size.width, size.height, parse_double(o.margin, "--margin"), {0, 0, 1, 1}};
}

void print_figure_stats(const CommonOptions& common, size_t elements, double measure, const char* measure_name,
                        double dimension) {
  if (common.stats)
    print_stats({{"elements", stat_value(double(elements))},
                 {measure_name, stat_value(measure)},
                 {"dimension", stat_value(dimension)}});
}

void setup_mandelbrot(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = fractal.add_subcommand("mandelbrot", "The Mandelbrot set (z0 = 0, c from the pixel)");
  sub->add_option("-o,--output", o->output, "Output picture")->required();
  add_escape_options(*sub, *o, "-0.5,0", "3");
  sub->callback([o, &common] {
    const auto [view, options] = escape_setup(*o);
    const auto start = std::chrono::steady_clock::now();
    const EscapeImage image = mandelbrot(view, options);
    const double seconds = seconds_since(start);
    ColorOptions colors;
    colors.palette = parse_palette(o->palette);
    write_image(o->output, colorize(image, colors));
    if (!common.stats) return;
    size_t inside = 0;
    for (uint32_t n : image.iterations.pixels()) inside += n >= uint32_t(options.max_iterations);
    print_stats({{"area", stat_value(double(inside) * view.pixel_size() * view.pixel_size())},
                 {"seconds", stat_value(seconds)},
                 {"iterations", stat_value(double(iteration_count(image)))},
                 {"simd", std::string(simd_name(options.simd == SimdPath::Auto ? best_simd_path() : options.simd))}});
  });
}

void setup_julia(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = fractal.add_subcommand("julia", "The Julia set of one c (z0 from the pixel)");
  sub->add_option("-o,--output", o->output, "Output picture")->required();
  sub->add_option("--c", o->c, "The constant c, re,im")->capture_default_str();
  add_escape_options(*sub, *o, "0,0", "3.2");
  sub->callback([o, &common] {
    const auto [view, options] = escape_setup(*o);
    const auto c = parse_doubles(o->c, 2, "--c");
    const auto start = std::chrono::steady_clock::now();
    const EscapeImage image = julia({c[0], c[1]}, view, options);
    const double seconds = seconds_since(start);
    ColorOptions colors;
    colors.palette = parse_palette(o->palette);
    write_image(o->output, colorize(image, colors));
    if (common.stats)
      print_stats({{"connected", julia_is_connected({c[0], c[1]}) ? "1" : "0"},
                   {"seconds", stat_value(seconds)},
                   {"iterations", stat_value(double(iteration_count(image)))}});
  });
}

void setup_cantor(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub =
      add_figure(fractal, "cantor", "Cantor set levels 0..depth stacked, or --dust: 2D Cantor dust", o, "5", "729x729");
  auto dust = std::make_shared<bool>(false);
  sub->add_flag("--dust", *dust, "Draw the 2D Cantor dust (Cantor set x Cantor set) at --depth");
  sub->callback([o, dust, &common] {
    const int depth = parse_bounded(o->depth, "--depth", 0, *dust ? 10 : 20);
    const PictureFrame frame = square_frame(*o);
    std::vector<Rect> rects;
    if (*dust) {
      rects = cantor_dust(depth);
    } else {
      // The notes' figure: level k as a bar in row k, bars half as tall as the gaps between rows.
      const double row = 1.0 / (depth + 1);
      for (int k = 0; k <= depth; ++k)
        for (const Interval& i : cantor_set(k)) rects.push_back({i.a, 1.0 - (k + 0.75) * row, i.b - i.a, 0.5 * row});
    }
    write_picture(o->output, draw_polygons(as_polygons(rects), frame));
    print_figure_stats(common, *dust ? rects.size() : size_t(1) << depth,
                       *dust ? cantor_measure(depth) * cantor_measure(depth) : cantor_measure(depth),
                       *dust ? "area" : "length", similarity_dimension(*dust ? 4 : 2, 3));
  });
}

void setup_sierpinski(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = add_figure(fractal, "sierpinski", "Sierpinski carpet or triangle", o, "5", "729x729");
  o->shape = "carpet";
  sub->add_option("--shape", o->shape, "carpet or triangle")->capture_default_str();
  sub->callback([o, &common] {
    const PictureFrame frame = square_frame(*o);
    if (o->shape == "carpet") {
      const int depth = parse_bounded(o->depth, "--depth", 0, 7);
      const auto rects = sierpinski_carpet(depth);
      write_picture(o->output, draw_polygons(as_polygons(rects), frame));
      print_figure_stats(common, rects.size(), carpet_area(depth), "area", similarity_dimension(8, 3));
    } else if (o->shape == "triangle") {
      const int depth = parse_bounded(o->depth, "--depth", 0, 12);
      const auto triangles = sierpinski_triangle(depth);
      write_picture(o->output, draw_polygons(as_polygons(triangles), frame));
      print_figure_stats(common, triangles.size(), sierpinski_triangle_fraction(depth), "area",
                         similarity_dimension(3, 2));
    } else {
      throw InvalidInput(fmt::format("--shape must be carpet or triangle, got '{}'", o->shape));
    }
  });
}

void setup_koch(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = add_figure(fractal, "koch", "von Koch snowflake or curve", o, "4", "600x600");
  o->shape = "snowflake", o->margin = "10";
  sub->add_option("--shape", o->shape, "snowflake or curve")->capture_default_str();
  sub->add_option("--line-width", o->line_width, "Line width in pixels")->capture_default_str();
  sub->callback([o, &common] {
    const int depth = parse_bounded(o->depth, "--depth", 0, 10);
    const Size2 size = parse_size(o->size, "--size");
    const bool closed = o->shape == "snowflake";
    if (!closed && o->shape != "curve")
      throw InvalidInput(fmt::format("--shape must be snowflake or curve, got '{}'", o->shape));
    const std::vector<Vec2> points = closed ? koch_snowflake(depth) : koch_curve(depth);
    const PictureFrame frame = frame_around(points, size.width, size.height, parse_double(o->margin, "--margin"));
    DrawStyle style;
    style.line_width = parse_double(o->line_width, "--line-width");
    style.antialias = true;
    write_picture(o->output, draw_curve(points, closed, frame, style));
    print_figure_stats(common, points.size(), (closed ? 3 : 1) * koch_length(depth), "length",
                       similarity_dimension(4, 3));
  });
}

void setup_space_filling(CLI::App& fractal, CommonOptions& common, const char* name, const char* help, int max_depth,
                         std::vector<Vec2> (*curve)(int), double copies, double scale) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = add_figure(fractal, name, help, o, "4", "512x512");
  o->margin = "4";
  sub->add_option("--line-width", o->line_width, "Line width in pixels")->capture_default_str();
  sub->callback([o, &common, max_depth, curve, copies, scale] {
    const int depth = parse_bounded(o->depth, "--depth", 0, max_depth);
    const auto points = curve(depth);
    DrawStyle style;
    style.line_width = parse_double(o->line_width, "--line-width");
    style.antialias = true;
    write_picture(o->output, draw_curve(points, false, square_frame(*o), style));
    print_figure_stats(common, points.size(), polyline_length(points), "length", similarity_dimension(copies, scale));
  });
}

bool is_mesh_path(const std::string& path) {
  try {
    mesh_format_from_path(path);
    return true;
  } catch (const InvalidInput&) {
    return false;
  }
}

void setup_terrain(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = fractal.add_subcommand(
      "terrain", "Fractal mountains: 1D midpoint profile, 2D triangle subdivision or diamond-square grid");
  o->depth = "7", o->size = "800x400";
  sub->add_option("-o,--output", o->output, "Output: a mesh (.obj .ply .off .stl) or a picture (.png ...)")->required();
  sub->add_option("--method", o->method, "midpoint (1D profile), triangles or diamond-square")->capture_default_str();
  sub->add_option("--depth", o->depth, "Subdivision levels")->capture_default_str();
  sub->add_option("--roughness", o->roughness, "Range factor per level in (0, 1); 0.5 halves (the notes)")
      ->capture_default_str();
  sub->add_option("--seed", o->seed, "Random seed")->capture_default_str();
  sub->add_option("--height-scale", o->height_scale, "Grid meshes: height multiplier")->capture_default_str();
  sub->add_option("--size", o->size, "Profile picture size WxH (midpoint)")->capture_default_str();
  sub->callback([o, &common] {
    TerrainOptions options;
    options.depth = parse_bounded(o->depth, "--depth", 0, 24);
    options.roughness = parse_double(o->roughness, "--roughness");
    options.seed = uint64_t(parse_bounded(o->seed, "--seed", 0, 2147483647));
    const bool mesh_out = is_mesh_path(o->output);
    size_t vertices = 0;
    if (o->method == "midpoint") {
      if (mesh_out) throw InvalidInput("the 1D midpoint profile is a picture: give -o a .png");
      const auto heights = midpoint_displacement_1d(options);
      // The profile as a filled mountain: the height polyline closed along the bottom.
      std::vector<Vec2> outline;
      for (size_t i = 0; i < heights.size(); ++i)
        outline.push_back({double(i) / double(heights.size() - 1), heights[i]});
      outline.push_back({1.0, -0.6}), outline.push_back({0.0, -0.6});
      const Size2 size = parse_size(o->size, "--size");
      DrawStyle style;
      style.ink = {0.35f, 0.3f, 0.25f}, style.paper = {0.85f, 0.92f, 1.0f}, style.antialias = true;
      write_picture(o->output, draw_polygons({outline}, frame_around(outline, size.width, size.height, 0), style));
      vertices = heights.size();
    } else if (o->method == "triangles") {
      if (!mesh_out) throw InvalidInput("the triangle mountain is a mesh: give -o a .obj, .ply, .off or .stl");
      const PolyMesh mesh = triangle_mountain(options);
      write_mesh(o->output, mesh);
      vertices = mesh.vertex_count();
    } else if (o->method == "diamond-square") {
      const Image<float> heights = diamond_square(options);
      if (mesh_out)
        write_mesh(o->output, height_map_mesh(heights, parse_double(o->height_scale, "--height-scale")));
      else
        write_image(o->output, height_map_picture(heights));
      vertices = heights.pixels().size();
    } else {
      throw InvalidInput(fmt::format("--method must be midpoint, triangles or diamond-square, got '{}'", o->method));
    }
    if (common.stats) print_stats({{"vertices", stat_value(double(vertices))}});
  });
}

void setup_dimension(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = fractal.add_subcommand("dimension", "Box-counting dimension of the dark pixels of a picture");
  sub->add_option("image", o->image, "Picture to measure (dark ink on light paper unless --invert)")->required();
  sub->add_option("--threshold", o->threshold, "Luminance below which a pixel is ink")->capture_default_str();
  sub->add_flag("--invert", o->invert, "Measure the light pixels instead");
  sub->add_option("--min-box", o->min_box, "Smallest box side in pixels")->capture_default_str();
  sub->add_option("--max-box", o->max_box, "Largest box side (0: a quarter of the shorter side)")
      ->capture_default_str();
  sub->add_option("--factor", o->factor, "Ratio between box sizes")->capture_default_str();
  sub->callback([o, &common] {
    const ImageRGBA picture = read_image(o->image);
    BoxCountOptions options;
    options.min_box = parse_bounded(o->min_box, "--min-box", 1, 65536);
    options.max_box = parse_bounded(o->max_box, "--max-box", 0, 65536);
    options.factor = parse_double(o->factor, "--factor");
    const BoxCountResult r =
        box_counting_dimension(ink_mask(picture, float(parse_double(o->threshold, "--threshold")), o->invert), options);
    if (common.stats)
      print_stats({{"dimension", stat_value(r.dimension)},
                   {"box_sizes", stat_value(double(r.sizes.size()))},
                   {"smallest_box_count", stat_value(double(r.counts.front()))}});
    else
      fmt::print("box-counting dimension {:.4f} (boxes of {} to {} pixels)\n", r.dimension, r.sizes.front(),
                 r.sizes.back());
  });
}

}  // namespace

void setup_fractal(CLI::App& fractal, CommonOptions& common) {
  fractal.require_subcommand(1);
  setup_mandelbrot(fractal, common);
  setup_julia(fractal, common);
  setup_cantor(fractal, common);
  setup_sierpinski(fractal, common);
  setup_koch(fractal, common);
  setup_space_filling(fractal, common, "hilbert", "Hilbert space-filling curve", 10, hilbert_curve, 4, 2);
  setup_space_filling(fractal, common, "peano", "Peano space-filling curve", 7, peano_curve, 9, 3);
  setup_terrain(fractal, common);
  setup_dimension(fractal, common);
}

}  // namespace tessera::cli
