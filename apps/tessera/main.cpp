// tessera: the command-line front end. The table below lists every command; each lives in commands/<name>.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "command.hpp"
#include "tessera/core/cpu.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/version.hpp"

namespace tessera::cli {
using tessera::Progress;
void setup_bench(CLI::App&, CommonOptions&);
void setup_assemble(CLI::App&, CommonOptions&);
void setup_canvas(CLI::App&, CommonOptions&);
void setup_color(CLI::App&, CommonOptions&);
void setup_curve(CLI::App&, CommonOptions&);
void setup_demo(CLI::App&, CommonOptions&);
void setup_farm(CLI::App&, CommonOptions&);
void setup_fractal(CLI::App&, CommonOptions&);
void setup_gallery(CLI::App&, CommonOptions&);
void setup_mesh(CLI::App&, CommonOptions&);
void setup_patch(CLI::App&, CommonOptions&);
void setup_raster(CLI::App&, CommonOptions&);
void setup_render(CLI::App&, CommonOptions&);
void setup_sketch(CLI::App&, CommonOptions&);
void setup_trace(CLI::App&, CommonOptions&);
void setup_view(CLI::App&, CommonOptions&);
void setup_volume(CLI::App&, CommonOptions&);

namespace {
const Command kCommands[] = {
    {"demo", "Render the built-in demo pictures into a folder (default out/)", setup_demo},
    {"gallery", "Render every example and algorithm as a picture, with an index.html", setup_gallery},
    {"canvas", "2D canvas: rasterize an SVG drawing", setup_canvas},
    {"color", "Color-model conversions", setup_color},
    {"mesh", "Mesh processing: info, convert, normals, smooth, subdivide, triangulate, weld", setup_mesh},
    {"curve", "Bezier curves: draw curves, control polygons and subdivision steps", setup_curve},
    {"patch", "Bezier patches (.bpt) tessellated into a mesh", setup_patch},
    {"fractal", "Fractals: mandelbrot, julia, koch, cantor, sierpinski, hilbert, peano, terrain, dimension",
     setup_fractal},
    {"volume", "Volume data: info, slice, contour (marching squares), isosurface (marching cubes), render",
     setup_volume},
    {"raster", "Z-buffered 3D rasterization of a mesh (flat, Gouraud or Phong shading)", setup_raster},
    {"render", "Render a scene file or a built-in scene (ray tracing or rasterization); frames, tiles, movies",
     setup_render},
    {"assemble", "Stitch the tiles of rendered frames into the frames; optionally encode them as a movie",
     setup_assemble},
    {"farm", "Render an animation on a Slurm cluster (job arrays) and follow its progress", setup_farm},
    {"trace", "Ray-cast a mesh into a shaded image", setup_trace},
    {"sketch", "Run a Processing sketch of the notes, in a window or headless (--list shows them)", setup_sketch},
    {"view", "View a mesh, scene, volume or Bezier patches: orbit, pan, zoom, shading keys; --headless --orbit N",
     setup_view},
    {"bench", "Measure hot paths: bench raycast MESH (rays per second)", setup_bench},
};

/// Edit distance between two words (for "did you mean").
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// The message for a word that names no command of `parent`: "unknown command 'x'", with the nearest command when
/// one is close enough to be a typo (or has the word as its prefix).
std::string unknown_command(const CLI::App& parent, const std::string& word) {
  std::string best;
  size_t best_distance = 3;
  for (const CLI::App* sub : parent.get_subcommands([](const CLI::App*) { return true; })) {
    const std::string& name = sub->get_name();
    const size_t d = name.rfind(word, 0) == 0 ? 0 : edit_distance(word, name);
    if (d < best_distance) best_distance = d, best = name;
  }
  const std::string prefix = parent.get_parent() ? parent.get_name() + " " : "";
  std::string message = fmt::format("unknown command '{}{}'", prefix, word);
  if (!best.empty()) message += fmt::format(" (did you mean '{}{}'?)", prefix, best);
  return message + fmt::format("; 'tessera {}--help' lists the commands", prefix);
}

/// "'tessera fractal' needs a subcommand: mandelbrot, julia, …" (CLI11 says only "A subcommand is required").
std::string missing_subcommand(const CLI::App& parent) {
  std::string names;
  for (const CLI::App* sub : parent.get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return fmt::format("'tessera {}' needs a subcommand: {}; 'tessera {} SUBCOMMAND --help' for its options",
                     parent.get_name(), names, parent.get_name());
}

/// Checks the command words of argv against the command tree before CLI11 sees them (CLI11 would call an unknown
/// word an extra positional argument). Returns the error message, or "" when every command word is known.
std::string check_command_words(const CLI::App& app, int argc, char** argv) {
  const CLI::App* parent = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word == "--help" || word == "-h" || word == "--version") break;
    if (parent->get_subcommands([](const CLI::App*) { return true; }).empty()) break;
    if (word.empty() || word[0] == '-') return parent == &app ? "" : missing_subcommand(*parent);
    // CLI11 2.1 has no get_subcommand_no_throw: look the word up among the subcommands' names.
    const auto named = parent->get_subcommands([&](const CLI::App* sub) { return sub->check_name(word); });
    if (named.empty()) return unknown_command(*parent, word);
    parent = named.front();
  }
  const bool needs_subcommand =
      parent != &app && !parent->get_subcommands([](const CLI::App*) { return true; }).empty();
  const bool asks_help = argc > 1 && (std::string(argv[argc - 1]) == "--help" || std::string(argv[argc - 1]) == "-h");
  return needs_subcommand && !asks_help ? missing_subcommand(*parent) : "";
}

/// The list of commands, for a bare `tessera`.
void print_command_list(const CLI::App& app) {
  fmt::print(stderr,
             "usage: tessera <command> [options]   ('tessera <command> --help' for its options)\n\ncommands:\n");
  for (const Command& c : kCommands) fmt::print(stderr, "  {:<9} {}\n", c.name, c.summary);
  fmt::print(stderr, "\n{}\n", app.get_footer());
}

/// The command words that were parsed, e.g. "mesh subdivide" (for messages that name what was running).
std::string command_path(const CLI::App& app) {
  std::string path;
  for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
    sub = sub->get_subcommands().front();
    path += (path.empty() ? "" : " ") + sub->get_name();
  }
  return path;
}

Progress::Mode progress_mode(const CommonOptions& common) {
  if (common.quiet || common.progress == "none") return Progress::Mode::none;
  if (common.progress == "plain") return Progress::Mode::plain;
  if (common.progress == "bar") return Progress::Mode::bar;
  return Progress::Mode::automatic;
}

}  // namespace
}  // namespace tessera::cli

int main(int argc, char** argv) {
  using namespace tessera::cli;
  start_command_clock();
  CLI::App app{"Tessera: a computer-graphics toolkit (rasterization, ray tracing, meshes, curves, volumes)", "tessera"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fmt::format("tessera {} (git {}, {})", tessera::kVersion, tessera::kGitHash,
                                                tessera::simd_level_name(tessera::simd_level())));
  app.footer(
      "Every command accepts --threads N, --quiet, --progress MODE, --stats and --max-memory SIZE; docs/cli.md has the "
      "contract.");
  CommonOptions common;
  for (const Command& c : kCommands) {
    CLI::App* sub = app.add_subcommand(c.name, c.summary);
    sub->fallthrough();  // options of `tessera X` also work after a nested `tessera X Y`
    c.setup(*sub, common);
    add_common_options(*sub, common);
  }
  if (argc < 2) {
    print_command_list(app);
    return 2;
  }
  if (const std::string error = check_command_words(app, argc, argv); !error.empty()) {
    fmt::print(stderr, "tessera: error: {}\n", error);
    return 2;
  }
  // Apply --threads, --quiet and --progress before any callback runs (CLI11 runs callbacks after parsing all options).
  std::unique_ptr<tessera::ThreadLimit> limit;
  app.parse_complete_callback([&] {
    tessera::Progress::set_mode(progress_mode(common));
    limit = std::make_unique<tessera::ThreadLimit>(common.threads);
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print and exit 0; every usage error says what was wrong and exits 2.
    if (e.get_exit_code() == 0) return app.exit(e);
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    fmt::print(stderr, "run with --help for the options\n");
    return 2;
  } catch (const std::bad_alloc&) {
    // A request that the budget's estimates missed: say what ran out instead of a bare "std::bad_alloc".
    fmt::print(stderr,
               "tessera: error: out of memory while running 'tessera {}' (the memory budget is {}; --max-memory SIZE "
               "sets it)\n",
               command_path(app), tessera::format_bytes(tessera::MemoryBudget::bytes()));
    return 1;
  } catch (const std::length_error&) {
    // A container asked for more elements than it can hold: the same condition, as std::vector reports it.
    fmt::print(stderr, "tessera: error: out of memory while running 'tessera {}' (a request larger than any memory)\n",
               command_path(app));
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
