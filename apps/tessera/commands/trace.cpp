// tessera trace MESH -o IMG: a quick ray-cast of a mesh through a BVH (headlight diffuse shading, smooth normals when
// the mesh has them), or a picture of the normals or of the traversal cost.
#include <algorithm>
#include <chrono>
#include <memory>

#include <fmt/format.h>

#include "camera_options.hpp"
#include "command.hpp"
#include "tessera/accel/mesh_accel.hpp"
#include "tessera/color/colormap.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera::cli {
namespace {

struct TraceArgs {
  std::string mesh, output, shade = "diffuse", color = "0.85,0.8,0.7", background = "0.1,0.1,0.12";
  CameraOptions camera;
};

void run_trace(const TraceArgs& a, const CommonOptions& common) {
  const auto [width, height] = a.camera.image_size();
  const Rgb color = parse_color(a.color, "--color"), background = parse_color(a.background, "--background");
  const PolyMesh poly = read_mesh(a.mesh);
  const TriMesh mesh = to_tri_mesh(poly);
  if (mesh.triangle_count() == 0) throw InvalidInput(fmt::format("{}: the mesh has no faces to trace", a.mesh));
  const Bounds3 b = bounding_box(poly);
  const Camera camera = a.camera.camera(b.lo, b.hi);

  const auto start = std::chrono::steady_clock::now();
  const MeshAccel accel(mesh);
  const EyeRays eye(camera, width, height);
  const Vec3f surface(color.r, color.g, color.b), bg(background.r, background.g, background.b);
  ImageRGB image(width, height, bg);
  Image<float> cost(a.shade == "cost" ? width : 1, a.shade == "cost" ? height : 1, 0.0f);
  parallel_tiles(width, height, 16, [&](const Tile& tile) {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        Ray ray = eye.ray(x, y);
        Hit hit;
        TraversalStats stats;
        const bool h = accel.intersect(ray, hit, &stats);
        if (a.shade == "cost") {
          cost(x, y) = float(stats.nodes + stats.prims);
          continue;
        }
        if (!h) continue;
        const Vec3f n = shading_normal(mesh, hit);
        if (a.shade == "normal") {
          image(x, y) = 0.5f * n + 0.5f;
        } else {
          // A headlight: the light is at the eye, so N.L is the cosine with the ray (either side of the surface).
          const float lambert = std::abs(glm::dot(n, glm::normalize(ray.dir)));
          image(x, y) = surface * (0.15f + 0.85f * lambert);
        }
      }
  });
  if (a.shade == "cost") {
    const float most = *std::max_element(cost.pixels().begin(), cost.pixels().end());
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) image(x, y) = heat_color(most > 0 ? cost(x, y) / most : 0.0f);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_image(a.output, image);
  if (common.stats)
    print_stats({{"triangles", stat_value(double(mesh.triangle_count()))},
                 {"pixels", stat_value(double(width) * height)},
                 {"seconds", stat_value(seconds)}});
}

}  // namespace

void setup_trace(CLI::App& cmd, CommonOptions& common) {
  auto a = std::make_shared<TraceArgs>();
  cmd.add_option("mesh", a->mesh, "Mesh file (.obj, .ply, .off, .stl)")->required();
  cmd.add_option("-o,--output", a->output, "Output image (.png, .ppm, .pfm, .hdr, .jpg, ...)")->required();
  a->camera.add(cmd);
  cmd.add_option("--shade", a->shade,
                 "diffuse (headlight, smooth normals when the mesh has them) | normal (n/2 + 1/2) | cost (BVH nodes + "
                 "triangles tested per pixel, blue to red)")
      ->check(CLI::IsMember({"diffuse", "normal", "cost"}))
      ->capture_default_str();
  cmd.add_option("--color", a->color, "Surface color r,g,b in [0,1] or #rrggbb")->capture_default_str();
  cmd.add_option("--background", a->background, "Background color r,g,b or #rrggbb")->capture_default_str();
  cmd.callback([a, &common] { run_trace(*a, common); });
}

}  // namespace tessera::cli
