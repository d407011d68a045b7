// tessera raster MESH -o IMG: z-buffered rasterization of a mesh file through raster3d's fixed-function pipeline.
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/raster3d/context.hpp"

namespace tessera::cli {
namespace {

struct RasterArgs {
  std::string mesh, output, shading = "gouraud", color = "0.8,0.8,0.8", background = "0,0,0", light_dir, light_pos,
                            cull = "none", depth_out;
  bool wireframe = false;
  int repeat = 1;
  CameraOptions camera;
};

const std::map<std::string, raster3d::ShadingModel> kShadings = {{"unlit", raster3d::ShadingModel::unlit},
                                                                 {"flat", raster3d::ShadingModel::flat},
                                                                 {"gouraud", raster3d::ShadingModel::gouraud},
                                                                 {"phong", raster3d::ShadingModel::phong}};

/// Every triangle with its own three vertices and its face normal: flat shading shows facets whatever the file's
/// normals (OpenGL's flat model would light each triangle at its last vertex's normal).
TriMesh faceted(const TriMesh& mesh) {
  TriMesh out;
  out.positions.reserve(mesh.indices.size());
  out.normals.reserve(mesh.indices.size());
  out.indices.reserve(mesh.indices.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* v = &mesh.indices[3 * t];
    const Vec3 a = mesh.positions[v[0]], b = mesh.positions[v[1]], c = mesh.positions[v[2]];
    const Vec3 cross = glm::cross(b - a, c - a);
    const double length = glm::length(cross);
    const Vec3 n = length > 0 ? cross / length : Vec3(0, 0, 1);
    for (int k = 0; k < 3; ++k) {
      out.indices.push_back(uint32_t(out.positions.size()));
      out.positions.push_back(mesh.positions[v[k]]);
      out.normals.push_back(n);
      if (!mesh.colors.empty()) out.colors.push_back(mesh.colors[v[k]]);
    }
  }
  return out;
}

/// The polygon edges (not the triangulation's diagonals), each once, as vertex pairs.
std::vector<std::pair<uint32_t, uint32_t>> polygon_edges(const PolyMesh& mesh) {
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (size_t i = 0; i < face.size(); ++i) {
      const uint32_t a = face[i], b = face[(i + 1) % face.size()];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return {edges.begin(), edges.end()};
}

Vec3 parse_vec3(const std::string& text, const char* what) {
  const auto v = parse_doubles(text, 3, what);
  return {v[0], v[1], v[2]};
}

void run_raster(const RasterArgs& a, const CommonOptions& common) {
  // Every option is checked before the mesh is read or anything is drawn.
  const auto [width, height] = a.camera.image_size();
  const Rgb color = parse_color(a.color, "--color"), background = parse_color(a.background, "--background");
  if (!a.light_dir.empty() && !a.light_pos.empty())
    throw InvalidInput("--light-dir and --light-pos: give one light, not both");
  const Vec3 light_dir = a.light_dir.empty() ? Vec3(0) : parse_vec3(a.light_dir, "--light-dir");
  if (!a.light_dir.empty() && glm::length(light_dir) == 0) throw InvalidInput("--light-dir: expected a nonzero vector");
  const Vec3 light_pos = a.light_pos.empty() ? Vec3(0) : parse_vec3(a.light_pos, "--light-pos");
  if (!a.depth_out.empty() && std::filesystem::path(a.depth_out).extension() != ".pfm")
    throw InvalidInput(fmt::format("--depth-out: expected a .pfm file, got '{}'", a.depth_out));
  const raster3d::ShadingModel shading = kShadings.at(a.shading);

  PolyMesh poly = read_mesh(a.mesh);
  if (poly.face_count() == 0) throw InvalidInput(fmt::format("{}: the mesh has no faces to draw", a.mesh));
  if (shading != raster3d::ShadingModel::unlit && poly.normals.empty() && poly.corner_normals.empty())
    compute_vertex_normals(poly);
  TriMesh mesh = to_tri_mesh(poly);
  if (shading == raster3d::ShadingModel::flat) mesh = faceted(mesh);

  const Bounds3 box = bounding_box(poly);
  const Camera camera = a.camera.camera(box.lo, box.hi);

  raster3d::Context ctx(width, height);
  ctx.perspective(camera.fovy, camera.near, camera.far, camera.aspect);
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  // The light: a direction or a point in world space (set under the view matrix, as glLight), else a light over
  // the viewer's upper-left shoulder in eye space.
  if (a.light_dir.empty() && a.light_pos.empty()) ctx.light(0, {.position = Vec4f(glm::normalize(Vec3f(-0.4f, 0.6f, 1.0f)), 0)});
  ctx.look_at(camera.eye, camera.center, camera.up);
  if (!a.light_dir.empty()) ctx.light(0, {.position = Vec4f(Vec3f(glm::normalize(light_dir)), 0)});
  if (!a.light_pos.empty()) ctx.light(0, {.position = Vec4f(Vec3f(light_pos), 1)});
  const Vec3f surface(color.r, color.g, color.b);
  ctx.material(raster3d::Material::plastic(surface, 32, 0.4f));
  ctx.color(surface);
  ctx.shading(shading);
  ctx.cull(a.cull == "back" ? raster3d::CullMode::back : raster3d::CullMode::none);
  const raster3d::VertexArrays arrays = raster3d::VertexArrays::from_mesh(mesh);
  const auto edges = a.wireframe ? polygon_edges(poly) : std::vector<std::pair<uint32_t, uint32_t>>{};
  const Vec3f bg(background.r, background.g, background.b);
  // Edges dark on a light background, light on a dark one.
  const Vec3f wire_color = (bg.x + bg.y + bg.z) > 1.5f ? Vec3f(0.1f, 0.1f, 0.15f) : Vec3f(0.9f, 0.9f, 0.8f);

  const auto start = std::chrono::steady_clock::now();
  for (int frame = 0; frame < a.repeat; ++frame) {
    ctx.clear(bg);
    ctx.draw(arrays);
    if (a.wireframe) {
      // Edges pulled toward the eye by a tiny depth offset (z_clip -= 2^-14 w, like glPolygonOffset) so that the
      // surface under them does not hide them.
      ctx.matrix_mode(raster3d::MatrixMode::projection);
      ctx.push_matrix();
      ctx.load_matrix(translate(0, 0, -0x1p-14) * ctx.projection());
      ctx.matrix_mode(raster3d::MatrixMode::model_view);
      const raster3d::ShadingModel saved = ctx.shading();
      ctx.shading(raster3d::ShadingModel::unlit);
      ctx.color(wire_color);
      ctx.begin(raster3d::Primitive::lines);
      for (const auto& [u, v] : edges) {
        ctx.vertex(poly.positions[u].x, poly.positions[u].y, poly.positions[u].z);
        ctx.vertex(poly.positions[v].x, poly.positions[v].y, poly.positions[v].z);
      }
      ctx.end();
      ctx.shading(saved);
      ctx.color(surface);
      ctx.matrix_mode(raster3d::MatrixMode::projection);
      ctx.pop_matrix();
      ctx.matrix_mode(raster3d::MatrixMode::model_view);
    }
    ctx.flush();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const raster3d::Framebuffer& fb = ctx.framebuffer();
  write_image(a.output, fb.color_rgb());
  if (!a.depth_out.empty()) {
    try {
      write_pfm(a.depth_out, fb.depth_image());
    } catch (...) {
      std::filesystem::remove(a.output);  // both outputs or neither
      throw;
    }
  }
  if (common.stats) {
    size_t covered = 0;
    for (const uint32_t d : fb.depth().pixels()) covered += d < raster3d::kDepthMax ? 1 : 0;
    // tris and pixels per frame (pixels: those the mesh covers); seconds for all --repeat frames.
    const double tris = double(mesh.triangle_count());
    print_stats({{"tris", stat_value(tris)},
                 {"pixels", stat_value(double(covered))},
                 {"seconds", stat_value(seconds)},
                 {"tris_per_s", stat_value(seconds > 0 ? tris * a.repeat / seconds : 0)}});
  }
}

}  // namespace

void setup_raster(CLI::App& cmd, CommonOptions& common) {
  auto a = std::make_shared<RasterArgs>();
  cmd.add_option("mesh", a->mesh, "Mesh file (.obj, .ply, .off, .stl)")->required();
  cmd.add_option("-o,--output", a->output, "Output image (.png, .ppm, .pfm, .hdr, .jpg, ...)")->required();
  a->camera.add(cmd);
  cmd.add_option("--shading", a->shading, "unlit | flat (per polygon) | gouraud (per vertex) | phong (per pixel)")
      ->check(CLI::IsMember({"unlit", "flat", "gouraud", "phong"}))
      ->capture_default_str();
  cmd.add_option("--color", a->color, "Surface color r,g,b in [0,1] or #rrggbb (a plastic: white highlights)")
      ->capture_default_str();
  cmd.add_option("--background", a->background, "Background color r,g,b or #rrggbb")->capture_default_str();
  cmd.add_option("--light-dir", a->light_dir,
                 "Directional light: world-space direction toward the light x,y,z (default: over the viewer's shoulder)");
  cmd.add_option("--light-pos", a->light_pos, "Point light at world-space x,y,z");
  cmd.add_flag("--wireframe", a->wireframe, "Draw the polygon edges over the surface");
  cmd.add_option("--cull", a->cull, "Back-face culling: back | none")
      ->check(CLI::IsMember({"back", "none"}))
      ->capture_default_str();
  cmd.add_option("--depth-out", a->depth_out, "Also write the depth buffer (window z in [0,1], 1 = background) as PFM");
  cmd.add_option("--repeat", a->repeat, "Render N frames (for timing with --stats)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.callback([a, &common] { run_raster(*a, common); });
}

}  // namespace tessera::cli
