// tessera trace MESH -o IMG: a quick ray-cast of a mesh through a BVH (headlight diffuse shading, smooth normals when
// the mesh has them), or a picture of the normals or of the traversal cost.
#include <fmt/format.h>

#include <algorithm>
#include <memory>

#include "camera_options.hpp"
#include "command.hpp"
#include "tessera/accel/mesh_accel.hpp"
#include "tessera/color/colormap.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/raytrace/sampling.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera::cli {
namespace {

struct TraceArgs {
  std::string mesh, output, shade = "diffuse", color = "0.85,0.8,0.7", background = "0.1,0.1,0.12";
  int samples = 1;
  CameraOptions camera;
};

/// What one eye ray shows: the headlit surface, its normal, or (cost) the BVH nodes and triangles it tested.
Vec3f shade_ray(const TraceArgs& a, const MeshAccel& accel, const TriMesh& mesh, Ray ray, const Vec3f& surface,
                const Vec3f& background) {
  Hit hit;
  TraversalStats stats;
  const bool h = accel.intersect(ray, hit, &stats);
  if (a.shade == "cost") return Vec3f(float(stats.nodes + stats.prims));
  if (!h) return background;
  const Vec3f n = shading_normal(mesh, hit);
  if (a.shade == "normal") return 0.5f * n + 0.5f;
  // A headlight: the light is at the eye, so N.L is the cosine with the ray (either side of the surface).
  const float lambert = std::abs(glm::dot(n, glm::normalize(ray.dir)));
  return surface * (0.15f + 0.85f * lambert);
}

void run_trace(const TraceArgs& a, const CommonOptions& common) {
  // Plain ints, not a structured binding: the lambdas below capture them, which clang-tidy's clang 14 cannot parse.
  const Size2 size = a.camera.image_size();
  const int width = size.width, height = size.height;
  // Per pixel: the float image, the depth image and the 8-bit copy (22 bytes measured).
  MemoryBudget::check(saturating_product({uint64_t(width), uint64_t(height), 24}),
                      fmt::format("tracing {}x{} pixels", width, height));
  const Rgb color = parse_color(a.color, "--color"), background = parse_color(a.background, "--background");
  PhaseTimer timer;
  const PolyMesh poly = timer.time("read_s", [&] { return read_mesh_with_progress(a.mesh); });
  const TriMesh mesh = to_tri_mesh(poly);
  if (mesh.triangle_count() == 0) throw InvalidInput(fmt::format("{}: the mesh has no faces to trace", a.mesh));
  const Bounds3 b = bounding_box(poly);
  const Camera camera = a.camera.camera(b.lo, b.hi);

  const Vec3f surface(color.r, color.g, color.b), bg(background.r, background.g, background.b);
  ImageRGB image(width, height, bg);
  timer.time("compute_s", [&] {
    const MeshAccel accel(mesh);
    const EyeRays eye(camera, width, height);
    // Each pixel averages its --samples rays (stratified, a pattern of its own), or (cost) their traversal costs.
    Progress progress("trace", int64_t(width) * height);
    parallel_tiles(width, height, 16, [&](const Tile& tile) {
      for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
          Vec3f sum(0);
          const uint32_t pattern = hash_u32(uint64_t(x), uint64_t(y));
          for (int s = 0; s < a.samples; ++s) {
            const Vec2 offset = pixel_sample(s, a.samples, pattern);
            sum += shade_ray(a, accel, mesh, eye.ray(x, y, offset.x, offset.y), surface, bg);
          }
          image(x, y) = sum / float(a.samples);
        }
      progress.advance(int64_t(tile.x1 - tile.x0) * (tile.y1 - tile.y0));
    });
    progress.done();
    if (a.shade == "cost") {
      float most = 0;
      for (const Vec3f& c : image.pixels()) most = std::max(most, c.x);
      for (Vec3f& c : image.pixels()) c = heat_color(most > 0 ? c.x / most : 0.0f);
    }
  });
  timer.time("write_s", [&] { write_image(a.output, image, common.write_options()); });
  if (common.stats) {
    StatRows rows = {{"triangles", stat_value(double(mesh.triangle_count()))},
                     {"pixels", stat_value(double(width) * height)},
                     {"width", stat_value(width)},
                     {"height", stat_value(height)},
                     {"samples", stat_value(a.samples)},
                     {"seconds", stat_value(timer.seconds("compute_s"))}};
    for (auto& row : timer.rows()) rows.push_back(row);
    print_stats(rows);
  }
}

}  // namespace

void setup_trace(CLI::App& cmd, CommonOptions& common) {
  auto a = std::make_shared<TraceArgs>();
  cmd.add_option("mesh", a->mesh, "Mesh file (.obj, .ply, .off, .stl)")->required();
  cmd.add_option("-o,--output", a->output, "Output image (.png, .ppm, .pfm, .hdr, .jpg, ...)")->required();
  a->camera.clip_planes = false;
  a->camera.add(cmd);
  cmd.add_option("--shade", a->shade,
                 "diffuse (headlight, smooth normals when the mesh has them) | normal (n/2 + 1/2) | cost (BVH nodes + "
                 "triangles tested per pixel, blue to red)")
      ->check(CLI::IsMember({"diffuse", "normal", "cost"}))
      ->capture_default_str();
  cmd.add_option("--color", a->color, "Surface color: a name, #rrggbb or r,g,b in [0,1]")
      ->check(color_format())
      ->capture_default_str();
  cmd.add_option("--background", a->background, "Background color: a name, #rrggbb or r,g,b")
      ->check(color_format())
      ->capture_default_str();
  add_samples_option(cmd, a->samples);
  add_srgb_option(cmd, common);
  cmd.callback([a, &common, &cmd] {
    // Options that would change nothing are refused rather than ignored.
    if (cmd.count("--color") > 0 && a->shade != "diffuse")
      throw InvalidInput(fmt::format("--color: --shade {} does not use the surface color", a->shade));
    if (cmd.count("--background") > 0 && a->shade == "cost")
      throw InvalidInput("--background: --shade cost colors every pixel by its cost");
    run_trace(*a, common);
  });
}

}  // namespace tessera::cli
