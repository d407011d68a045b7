// tessera fractal mandelbrot|julia|cantor|sierpinski|koch|hilbert|peano|terrain -o OUT [options] [--srgb] [--stats]
// and tessera fractal dimension IMAGE [--stats] (docs/fractal.md). Malformed values, unknown choices and depths past a
// figure's limit are usage errors (exit 2) found while parsing, before anything is computed or written.
#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <string>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
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

/// --size, refused when the picture is over the memory budget: per pixel the float RGBA picture (16 bytes), the 8-bit
/// copy a writer makes (4) and a float of working data (4).
Size2 picture_size(const std::string& text) {
  const Size2 size = parse_size(text, "--size");
  MemoryBudget::check(saturating_product({uint64_t(size.width), uint64_t(size.height), 24}),
                      fmt::format("drawing {}x{} pixels", size.width, size.height));
  return size;
}

enum class SierpinskiShape { carpet, triangle };
enum class KochShape { snowflake, curve };
enum class TerrainMethod { midpoint, triangles, diamond_square };

struct FractalOptions {
  std::string output, size;
  // mandelbrot, julia
  std::string center, c = "-0.8,0.156";
  double scale = 3;
  int iterations = 1000;
  Palette palette = Palette::classic;
  SimdPath simd = SimdPath::automatic;
  // the self-similar figures
  int depth = 0;
  double margin = 0, line_width = 1;
  bool dust = false;
  SierpinskiShape sierpinski = SierpinskiShape::carpet;
  KochShape koch = KochShape::snowflake;
  // terrain
  TerrainMethod method = TerrainMethod::diamond_square;
  double roughness = 0.5, height_scale = 0.5;
  int seed = 1;
  // dimension
  std::string image;
  double threshold = 0.5, min_box = 1, max_box = 0, factor = 2;
  bool invert = false;
};

/// Checks that a number option is above `lo` (or at least `lo` when `inclusive`), and below `hi` when hi > lo.
CLI::Validator number_range(double lo, double hi, bool inclusive = false) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v)) return "expected a number, got '" + text + "'";
        const bool above = inclusive ? v >= lo : v > lo;
        if (above && (hi <= lo || v < hi)) return "";
        if (hi > lo) return fmt::format("expected a number in {}{}, {}), got {}", inclusive ? "[" : "(", lo, hi, text);
        return fmt::format("expected a number {} {}, got {}", inclusive ? ">=" : ">", lo, text);
      },
      "");
}

/// A depth past the limit of the figure the other options chose: a usage error, like a depth past --depth's range.
void check_depth(int depth, int max_depth, const std::string& which) {
  if (depth > max_depth)
    throw CLI::ValidationError("--depth", fmt::format("{} goes up to depth {}, got {}", which, max_depth, depth));
}

CLI::Option* add_size(CLI::App& sub, FractalOptions& o, const char* size, const char* help = "Picture size WxH") {
  o.size = size;
  return sub.add_option("--size", o.size, help)->check(size_format())->capture_default_str();
}

/// Writes a picture (with --srgb's encoding) under write_s and returns the stats rows that describe it.
template <class Picture>
StatRows write_picture(const std::string& path, const Picture& picture, const CommonOptions& common,
                       PhaseTimer& timer) {
  timer.time("write_s", [&] { write_image(path, picture, common.write_options()); });
  return {{"width", stat_value(picture.width())},
          {"height", stat_value(picture.height())},
          {"pixels", stat_value(double(picture.width()) * picture.height())}};
}

/// Prints rows, then the picture's rows and the timed phases.
void print_all(StatRows rows, const StatRows& picture, const PhaseTimer& timer) {
  rows.insert(rows.end(), picture.begin(), picture.end());
  for (const auto& row : timer.rows()) rows.push_back(row);
  print_stats(rows);
}

ComplexView complex_view(const FractalOptions& o) {
  const Size2 size = picture_size(o.size);
  const auto center = parse_doubles(o.center, 2, "--center");
  return ComplexView{{center[0], center[1]}, o.scale, size.width, size.height};
}

void add_escape_options(CLI::App& sub, FractalOptions& o, const char* center, double scale) {
  o.center = center, o.scale = scale;
  sub.add_option("-o,--output", o.output, "Output picture")->required();
  sub.add_option("--center", o.center, "Middle of the view in the complex plane, re,im")
      ->check(numbers_format(2))
      ->capture_default_str();
  sub.add_option("--scale", o.scale, "Width of the view in the complex plane")
      ->check(number_range(0, 0))
      ->capture_default_str();
  add_size(sub, o, "800x600");
  sub.add_option("--iterations", o.iterations, "Iteration cap")->check(CLI::Range(1, 100000000))->capture_default_str();
  add_choice(
      sub, "--palette", o.palette,
      {{"classic", Palette::classic}, {"fire", Palette::fire}, {"ocean", Palette::ocean}, {"gray", Palette::gray}},
      "Color ramp of the escape times");
  add_choice(sub, "--simd", o.simd,
             {{"auto", SimdPath::automatic},
              {"scalar", SimdPath::scalar},
              {"avx2", SimdPath::avx2},
              {"avx512", SimdPath::avx512}},
             "Instruction set of the escape loop");
}

/// Colors escape times and writes the picture, timed; returns the picture's rows.
StatRows color_and_write(const FractalOptions& o, const CommonOptions& common, PhaseTimer& timer,
                         const EscapeImage& image) {
  ColorOptions colors;
  colors.palette = o.palette;
  const ImageRGB picture = timer.time("compute_s", [&] { return colorize(image, colors); });
  return write_picture(o.output, picture, common, timer);
}

void setup_mandelbrot(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = fractal.add_subcommand("mandelbrot", "The Mandelbrot set (z0 = 0, c from the pixel)");
  add_escape_options(*sub, *o, "-0.5,0", 3);
  add_srgb_option(*sub, common);
  sub->callback([o, &common] {
    const ComplexView view = complex_view(*o);
    EscapeOptions options;
    options.max_iterations = o->iterations;
    options.simd = o->simd;
    PhaseTimer timer;
    const EscapeImage image = timer.time("compute_s", [&] { return mandelbrot(view, options); });
    const double seconds = timer.seconds("compute_s");  // the escape loop alone: `seconds` keeps its meaning
    const StatRows picture = color_and_write(*o, common, timer, image);
    if (!common.stats) return;
    size_t inside = 0;
    for (uint32_t n : image.iterations.pixels()) inside += n >= uint32_t(options.max_iterations);
    print_all({{"area", stat_value(double(inside) * view.pixel_size() * view.pixel_size())},
               {"seconds", stat_value(seconds)},
               {"iterations", stat_value(double(iteration_count(image)))},
               {"simd", std::string(simd_name(options.simd == SimdPath::automatic ? best_simd_path() : options.simd))}},
              picture, timer);
  });
}

void setup_julia(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = fractal.add_subcommand("julia", "The Julia set of one c (z0 from the pixel)");
  sub->add_option("--c", o->c, "The constant c, re,im")->check(numbers_format(2))->capture_default_str();
  add_escape_options(*sub, *o, "0,0", 3.2);
  add_srgb_option(*sub, common);
  sub->callback([o, &common] {
    const ComplexView view = complex_view(*o);
    const auto c = parse_doubles(o->c, 2, "--c");
    EscapeOptions options;
    options.max_iterations = o->iterations;
    options.simd = o->simd;
    PhaseTimer timer;
    const EscapeImage image = timer.time("compute_s", [&] { return julia({c[0], c[1]}, view, options); });
    const double seconds = timer.seconds("compute_s");
    const StatRows picture = color_and_write(*o, common, timer, image);
    if (common.stats)
      print_all({{"connected", julia_is_connected({c[0], c[1]}) ? "1" : "0"},
                 {"seconds", stat_value(seconds)},
                 {"iterations", stat_value(double(iteration_count(image)))}},
                picture, timer);
  });
}

/// A self-similar picture's subcommand: -o, --depth (0..max_depth), --size, --margin, --srgb.
CLI::App* add_figure(CLI::App& fractal, CommonOptions& common, const char* name, const char* help, FractalOptions& o,
                     int depth, int max_depth, const char* size, double margin) {
  CLI::App* sub = fractal.add_subcommand(name, help);
  o.depth = depth, o.margin = margin;
  sub->add_option("-o,--output", o.output, "Output picture (PNG, PPM, JPG, ...)")->required();
  sub->add_option("--depth", o.depth, "Subdivision depth")->check(CLI::Range(0, max_depth))->capture_default_str();
  add_size(*sub, o, size);
  sub->add_option("--margin", o.margin, "Free border in pixels")->check(non_negative())->capture_default_str();
  add_srgb_option(*sub, common);
  return sub;
}

void add_line_width(CLI::App& sub, FractalOptions& o) {
  sub.add_option("--line-width", o.line_width, "Line width in pixels")
      ->check(number_range(0, 0))
      ->capture_default_str();
}

PictureFrame square_frame(const FractalOptions& o) {
  const Size2 size = picture_size(o.size);
  return PictureFrame{size.width, size.height, o.margin, {0, 0, 1, 1}};
}

/// Draws a figure under compute_s, writes it and prints the figure's stats. A margin that leaves no room is a usage
/// error, like a malformed --margin.
void finish_figure(const FractalOptions& o, const CommonOptions& common, const std::function<ImageRGBA()>& draw,
                   size_t elements, double measure, const char* measure_name, double dimension) {
  const Size2 size = picture_size(o.size);
  if (2 * o.margin >= std::min(size.width, size.height))
    throw CLI::ValidationError("--margin", fmt::format("a margin of {} pixels leaves nothing of a {}x{} picture",
                                                       o.margin, size.width, size.height));
  PhaseTimer timer;
  const ImageRGBA picture = timer.time("compute_s", draw);
  const StatRows rows = write_picture(o.output, picture, common, timer);
  if (common.stats)
    print_all({{"elements", stat_value(double(elements))},
               {measure_name, stat_value(measure)},
               {"dimension", stat_value(dimension)}},
              rows, timer);
}

void setup_cantor(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = add_figure(fractal, common, "cantor", "Cantor set levels 0..depth stacked, or --dust: 2D Cantor dust",
                             *o, 5, 20, "729x729", 0);
  sub->add_flag("--dust", o->dust, "Draw the 2D Cantor dust (Cantor set x Cantor set) at --depth (up to 10)");
  sub->callback([o, &common] {
    if (o->dust) check_depth(o->depth, 10, "--dust");
    const int depth = o->depth;
    std::vector<Rect> rects;
    if (o->dust) {
      rects = cantor_dust(depth);
    } else {
      // The notes' figure: level k as a bar in row k, bars half as tall as the gaps between rows.
      const double row = 1.0 / (depth + 1);
      for (int k = 0; k <= depth; ++k)
        for (const Interval& i : cantor_set(k)) rects.push_back({i.a, 1.0 - (k + 0.75) * row, i.b - i.a, 0.5 * row});
    }
    finish_figure(
        *o, common, [&] { return draw_polygons(as_polygons(rects), square_frame(*o)); },
        o->dust ? rects.size() : size_t(1) << depth,
        o->dust ? cantor_measure(depth) * cantor_measure(depth) : cantor_measure(depth), o->dust ? "area" : "length",
        similarity_dimension(o->dust ? 4 : 2, 3));
  });
}

void setup_sierpinski(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = add_figure(fractal, common, "sierpinski", "Sierpinski carpet (depth up to 7) or triangle (up to 12)",
                             *o, 5, 12, "729x729", 0);
  add_choice(*sub, "--shape", o->sierpinski,
             {{"carpet", SierpinskiShape::carpet}, {"triangle", SierpinskiShape::triangle}}, "Which figure");
  sub->callback([o, &common] {
    if (o->sierpinski == SierpinskiShape::carpet) {
      check_depth(o->depth, 7, "the carpet");
      const auto rects = sierpinski_carpet(o->depth);
      finish_figure(
          *o, common, [&] { return draw_polygons(as_polygons(rects), square_frame(*o)); }, rects.size(),
          carpet_area(o->depth), "area", similarity_dimension(8, 3));
    } else {
      const auto triangles = sierpinski_triangle(o->depth);
      finish_figure(
          *o, common, [&] { return draw_polygons(as_polygons(triangles), square_frame(*o)); }, triangles.size(),
          sierpinski_triangle_fraction(o->depth), "area", similarity_dimension(3, 2));
    }
  });
}

void setup_koch(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = add_figure(fractal, common, "koch", "von Koch snowflake or curve", *o, 4, 10, "600x600", 10);
  add_choice(*sub, "--shape", o->koch, {{"snowflake", KochShape::snowflake}, {"curve", KochShape::curve}},
             "Which figure");
  add_line_width(*sub, *o);
  sub->callback([o, &common] {
    const bool closed = o->koch == KochShape::snowflake;
    const std::vector<Vec2> points = closed ? koch_snowflake(o->depth) : koch_curve(o->depth);
    const Size2 size = picture_size(o->size);
    DrawStyle style;
    style.line_width = o->line_width;
    style.antialias = true;
    finish_figure(
        *o, common,
        [&] { return draw_curve(points, closed, frame_around(points, size.width, size.height, o->margin), style); },
        points.size(), (closed ? 3 : 1) * koch_length(o->depth), "length", similarity_dimension(4, 3));
  });
}

void setup_space_filling(CLI::App& fractal, CommonOptions& common, const char* name, const char* help, int max_depth,
                         std::vector<Vec2> (*curve)(int), double copies, double scale) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = add_figure(fractal, common, name, help, *o, 4, max_depth, "512x512", 4);
  add_line_width(*sub, *o);
  sub->callback([o, &common, curve, copies, scale] {
    const auto points = curve(o->depth);
    DrawStyle style;
    style.line_width = o->line_width;
    style.antialias = true;
    finish_figure(
        *o, common, [&] { return draw_curve(points, false, square_frame(*o), style); }, points.size(),
        polyline_length(points), "length", similarity_dimension(copies, scale));
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
  o->depth = 7;
  sub->add_option("-o,--output", o->output, "Output: a mesh (.obj .ply .off .stl) or a picture (.png ...)")->required();
  add_choice(*sub, "--method", o->method,
             {{"midpoint", TerrainMethod::midpoint},
              {"triangles", TerrainMethod::triangles},
              {"diamond-square", TerrainMethod::diamond_square}},
             "midpoint (1D profile, a picture), triangles (a mesh) or diamond-square (a mesh or a height picture)");
  sub->add_option("--depth", o->depth,
                  fmt::format("Subdivision levels (midpoint up to {}, triangles {}, diamond-square {})",
                              kMaxTerrainDepth1D, kMaxTerrainDepthTriangles, kMaxTerrainDepthGrid))
      ->check(CLI::Range(0, kMaxTerrainDepth1D))
      ->capture_default_str();
  sub->add_option("--roughness", o->roughness, "Range factor per level in (0, 1); 0.5 halves (the notes)")
      ->check(number_range(0, 1))
      ->capture_default_str();
  sub->add_option("--seed", o->seed, "Random seed")->check(CLI::Range(0, 2147483647))->capture_default_str();
  sub->add_option("--height-scale", o->height_scale, "Grid meshes: height multiplier")->capture_default_str();
  add_size(*sub, *o, "800x400", "Profile picture size WxH (midpoint)");
  add_srgb_option(*sub, common);
  sub->callback([o, &common] {
    const bool mesh_out = is_mesh_path(o->output);
    if (o->method == TerrainMethod::midpoint && mesh_out)
      throw CLI::ValidationError("--method", "the 1D midpoint profile is a picture: give -o a .png");
    if (o->method == TerrainMethod::triangles && !mesh_out)
      throw CLI::ValidationError("--method", "the triangle mountain is a mesh: give -o a .obj, .ply, .off or .stl");
    if (o->method == TerrainMethod::midpoint) check_depth(o->depth, kMaxTerrainDepth1D, "the midpoint profile");
    if (o->method == TerrainMethod::triangles)
      check_depth(o->depth, kMaxTerrainDepthTriangles, "the triangle mountain");
    if (o->method == TerrainMethod::diamond_square) check_depth(o->depth, kMaxTerrainDepthGrid, "diamond-square");
    TerrainOptions options;
    options.depth = o->depth;
    options.roughness = o->roughness;
    options.seed = uint64_t(o->seed);
    PhaseTimer timer;
    StatRows rows, output;
    const auto save_mesh = [&](const PolyMesh& mesh) {
      timer.time("write_s", [&] { write_mesh(o->output, mesh); });
      rows = {{"vertices", stat_value(double(mesh.vertex_count()))}, {"faces", stat_value(double(mesh.face_count()))}};
    };
    if (o->method == TerrainMethod::midpoint) {
      const auto heights = timer.time("compute_s", [&] { return midpoint_displacement_1d(options); });
      // The profile as a filled mountain: the height polyline closed along the bottom.
      std::vector<Vec2> outline;
      for (size_t i = 0; i < heights.size(); ++i)
        outline.push_back({double(i) / double(heights.size() - 1), heights[i]});
      outline.push_back({1.0, -0.6}), outline.push_back({0.0, -0.6});
      const Size2 size = picture_size(o->size);
      DrawStyle style;
      style.ink = {0.35f, 0.3f, 0.25f}, style.paper = {0.85f, 0.92f, 1.0f}, style.antialias = true;
      const ImageRGBA picture = timer.time("compute_s", [&] {
        return draw_polygons({outline}, frame_around(outline, size.width, size.height, 0), style);
      });
      output = write_picture(o->output, picture, common, timer);
      rows = {{"vertices", stat_value(double(heights.size()))}};
    } else if (o->method == TerrainMethod::triangles) {
      save_mesh(timer.time("compute_s", [&] { return triangle_mountain(options); }));
    } else {
      const Image<float> heights = timer.time("compute_s", [&] { return diamond_square(options); });
      if (mesh_out) {
        save_mesh(timer.time("compute_s", [&] { return height_map_mesh(heights, o->height_scale); }));
      } else {
        output = write_picture(o->output, height_map_picture(heights), common, timer);
        rows = {{"vertices", stat_value(double(heights.pixels().size()))}};
      }
    }
    if (common.stats) print_all(rows, output, timer);
  });
}

void setup_dimension(CLI::App& fractal, CommonOptions& common) {
  auto o = std::make_shared<FractalOptions>();
  CLI::App* sub = fractal.add_subcommand("dimension", "Box-counting dimension of the dark pixels of a picture");
  sub->add_option("image", o->image, "Picture to measure (dark ink on light paper unless --invert)")->required();
  sub->add_option("--threshold", o->threshold, "Luminance below which a pixel is ink")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  sub->add_flag("--invert", o->invert, "Measure the light pixels instead");
  sub->add_option("--min-box", o->min_box, "Smallest box side in pixels (>= 1)")
      ->check(number_range(1, 0, true))
      ->capture_default_str();
  sub->add_option("--max-box", o->max_box,
                  "Largest box side in pixels (0: the set's extent, the longer side of its bounding box)")
      ->check(non_negative())
      ->capture_default_str();
  sub->add_option("--factor", o->factor, "Ratio between box sizes (> 1); 3 suits triadic sets")
      ->check(number_range(1, 0))
      ->capture_default_str();
  sub->callback([o, &common] {
    if (o->max_box > 0 && o->max_box < o->min_box)
      throw CLI::ValidationError("--max-box", fmt::format("{} is smaller than --min-box {}", o->max_box, o->min_box));
    PhaseTimer timer;
    const ImageRGBA picture = timer.time("read_s", [&] { return read_image(o->image); });
    const BoxCountResult r = timer.time("compute_s", [&] {
      return box_counting_dimension(ink_mask(picture, float(o->threshold), o->invert),
                                    BoxCountOptions{o->min_box, o->max_box, o->factor});
    });
    if (common.stats)
      print_all({{"dimension", stat_value(r.dimension)},
                 {"box_sizes", stat_value(double(r.sizes.size()))},
                 {"fitted_sizes", stat_value(double(r.fitted))},
                 {"extent", stat_value(r.extent)},
                 {"smallest_box", stat_value(r.sizes.back())},
                 {"smallest_box_count", stat_value(double(r.counts.back()))},
                 {"width", stat_value(picture.width())},
                 {"height", stat_value(picture.height())},
                 {"pixels", stat_value(double(picture.width()) * picture.height())}},
                {}, timer);
    else
      fmt::print("box-counting dimension {:.4f} (set extent {} pixels; boxes of {:.4g} to {:.4g} pixels, {} fitted)\n",
                 r.dimension, r.extent, r.sizes.back(), r.sizes.front(), r.fitted);
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
