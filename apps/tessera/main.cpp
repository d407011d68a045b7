// tessera: the command-line front end. The table below lists every command; each lives in commands/<name>.cpp.
#include <cstdio>
#include <exception>

#include <fmt/format.h>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"

namespace tessera::cli {
void setup_bench(CLI::App&, CommonOptions&);
void setup_canvas(CLI::App&, CommonOptions&);
void setup_color(CLI::App&, CommonOptions&);
void setup_curve(CLI::App&, CommonOptions&);
void setup_demo(CLI::App&, CommonOptions&);
void setup_fractal(CLI::App&, CommonOptions&);
void setup_gallery(CLI::App&, CommonOptions&);
void setup_mesh(CLI::App&, CommonOptions&);
void setup_patch(CLI::App&, CommonOptions&);
void setup_raster(CLI::App&, CommonOptions&);
void setup_render(CLI::App&, CommonOptions&);
void setup_trace(CLI::App&, CommonOptions&);
void setup_volume(CLI::App&, CommonOptions&);

namespace {
const Command kCommands[] = {
    {"demo", "Render the built-in demo pictures into a folder (default out/)", setup_demo},
    {"gallery", "Render every example and algorithm as a picture, with an index.html", setup_gallery},
    {"canvas", "2D canvas: rasterize an SVG drawing", setup_canvas},
    {"color", "Color-model conversions", setup_color},
    {"mesh", "Mesh processing: info, convert, normals, smooth, subdivide, triangulate", setup_mesh},
    {"curve", "Bezier curves: draw curves, control polygons and subdivision steps", setup_curve},
    {"patch", "Bezier patches (.bpt) tessellated into a mesh", setup_patch},
    {"fractal", "Fractals: mandelbrot, julia, koch, cantor, sierpinski, hilbert, peano, terrain, dimension", setup_fractal},
    {"volume", "Volume data: info, slice, contour (marching squares), isosurface (marching cubes), render", setup_volume},
    {"raster", "Z-buffered 3D rasterization of a mesh (flat, Gouraud or Phong shading)", setup_raster},
    {"render", "Render a scene file or a built-in scene (ray tracing or rasterization)", setup_render},
    {"trace", "Ray-cast a mesh into a shaded image", setup_trace},
    {"bench", "Measure hot paths: bench raycast MESH (rays per second)", setup_bench},
};
}  // namespace
}  // namespace tessera::cli

int main(int argc, char** argv) {
  using namespace tessera::cli;
  CLI::App app{"Tessera: a computer-graphics toolkit (rasterization, ray tracing, meshes, curves, volumes)", "tessera"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tessera 0.1.0");
  CommonOptions common;
  for (const Command& c : kCommands) {
    CLI::App* sub = app.add_subcommand(c.name, c.summary);
    sub->fallthrough();  // options of `tessera X` also work after a nested `tessera X Y`
    c.setup(*sub, common);
    add_common_options(*sub, common);
  }
  // Apply --threads/--quiet before any callback runs (CLI11 runs callbacks after parsing all options).
  std::unique_ptr<tessera::ThreadLimit> limit;
  app.parse_complete_callback([&] {
    tessera::Progress::set_quiet(common.quiet);
    limit = std::make_unique<tessera::ThreadLimit>(common.threads);
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every usage error prints CLI11's message and exits 2.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const tessera::Error& e) {
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "tessera: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
