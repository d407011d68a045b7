// tessera raster MESH -o IMG: z-buffered rasterization of a mesh file through raster3d's fixed-function pipeline.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "camera_options.hpp"
#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/shadow_map.hpp"
#include "tessera/raster3d/shadow_volume.hpp"
#include "tessera/raster3d/surface_shader.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera::cli {
namespace {

struct RasterArgs {
  std::string mesh, output, color = "0.8,0.8,0.8", background = "0,0,0", light_dir, light_pos, depth_out;
  raster3d::ShadingModel shading = raster3d::ShadingModel::gouraud;
  raster3d::CullMode cull = raster3d::CullMode::none;
  bool wireframe = false;
  int repeat = 1, samples = 1;
  raster3d::HiddenSurface hidden_surface = raster3d::HiddenSurface::zbuffer;
  CameraOptions camera;
  // The maps (drawn per pixel by raster3d's surface shaders).
  std::string texture, bump, env;
  Filter filter = Filter::trilinear;
  ShadowMethod shadow_method = ShadowMethod::map;
  double bump_scale = 0.01, reflect = 0.6, opacity = 1;
  bool shadows = false, floor = false, env_cube = false, shading_given = false;
  int shadow_size = 2048;

  bool maps() const { return !texture.empty() || !bump.empty() || !env.empty() || shadows || floor || env_cube; }
};

template <class T>
using Names = std::vector<std::pair<std::string, T>>;

const Names<raster3d::ShadingModel> kShadings = {{"unlit", raster3d::ShadingModel::unlit},
                                                 {"flat", raster3d::ShadingModel::flat},
                                                 {"gouraud", raster3d::ShadingModel::gouraud},
                                                 {"phong", raster3d::ShadingModel::phong}};
const Names<ShadowMethod> kShadowMethods = {
    {"map", ShadowMethod::map}, {"zpass", ShadowMethod::zpass}, {"zfail", ShadowMethod::zfail}};

/// The option name of an enum value (for messages).
template <class T>
const std::string& name_of(const Names<T>& names, T value) {
  return std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.second == value; })->first;
}

/// Whether the faces wind inward (an inside-out mesh: lit from behind, black but for the ambient term, and culled
/// whole by --cull back): a closed, consistently oriented mesh with a negative volume. Open meshes are left as they
/// are: their volume depends on the origin.
bool winds_inward(const PolyMesh& mesh) {
  if (signed_volume(mesh) >= 0) return false;
  const EdgeTable edges = build_edge_table(mesh);
  for (size_t e = 0; e < edges.size(); ++e)
    if (edges.valence(e) != 2) return false;
  return is_consistently_oriented(mesh, edges);
}

/// Reverses every face's winding, with its corner attributes.
void reverse_faces(PolyMesh& mesh) {
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const uint32_t begin = mesh.face_offsets[f], end = mesh.face_offsets[f + 1];
    std::reverse(mesh.face_vertices.begin() + begin, mesh.face_vertices.begin() + end);
    if (!mesh.corner_uvs.empty()) std::reverse(mesh.corner_uvs.begin() + begin, mesh.corner_uvs.begin() + end);
  }
}

Vec3 parse_vec3(const std::string& text, const char* what) {
  const auto v = parse_doubles(text, 3, what);
  return {v[0], v[1], v[2]};
}

/// The --samples pattern (one for every pixel: the jittered frames move the whole picture).
constexpr uint32_t kSamplePattern = 0x5eed;

/// A floor under the box [lo, hi] along the model's up axis k (--up-axis): a square at lo[k], three times the box's
/// larger horizontal size.
raster3d::VertexArrays floor_under(const Bounds3& box, int k) {
  // Corners in the horizontal axes (a, b), e_a x e_b = -e_k: (x, z) for y up.
  const int a = (k + 2) % 3, b = (k + 1) % 3;
  const Vec3 mid = 0.5 * (box.lo + box.hi);
  const float half = float(1.5 * std::max({box.hi[a] - box.lo[a], box.hi[b] - box.lo[b], 1e-6}));
  const auto corner = [&](float da, float db) {
    Vec3f p;
    p[k] = float(box.lo[k]);
    p[a] = float(mid[a]) + da;
    p[b] = float(mid[b]) + db;
    return p;
  };
  raster3d::VertexArrays arrays;
  arrays.positions = {corner(-half, -half), corner(half, -half), corner(half, half), corner(-half, half)};
  Vec3f up(0);
  up[k] = 1;
  arrays.normals.assign(4, up);
  arrays.indices = {0, 2, 1, 0, 3, 2};  // counterclockwise seen from above
  return arrays;
}

/// The model's up axis as a coordinate index.
int up_index(UpAxis axis) { return axis == UpAxis::x ? 0 : axis == UpAxis::y ? 1 : 2; }

/// The pictures of a pixel's samples averaged (the accumulation buffer's anti-aliasing, one jittered frame a sample),
/// the nearest of their depths, and the pixels any sample covered.
class SampleResolve {
 public:
  SampleResolve(int width, int height) : sum_(width, height, Vec3f(0)), depth_(width, height, raster3d::kDepthMax) {}

  /// Adds one sample's frame; `painter`: coverage from the stencil buffer (the painter's algorithm keeps no depth).
  void add(const raster3d::Framebuffer& fb, bool painter) {
    const ImageRGB color = fb.color_rgb();
    for (size_t i = 0; i < color.pixels().size(); ++i) {
      sum_.pixels()[i] += color.pixels()[i];
      depth_.pixels()[i] =
          std::min(depth_.pixels()[i], painter && fb.stencil().pixels()[i] ? 0u : fb.depth().pixels()[i]);
    }
    ++count_;
  }
  /// The average color.
  ImageRGB color() const {
    ImageRGB out = sum_;
    for (Vec3f& c : out.pixels()) c /= float(count_);
    return out;
  }
  /// The depth buffer's nearest values as window z in [0, 1].
  DepthImage depth() const {
    DepthImage out(depth_.width(), depth_.height(), 1.0f);
    for (size_t i = 0; i < out.pixels().size(); ++i)
      out.pixels()[i] = float(double(depth_.pixels()[i]) / raster3d::kDepthMax);
    return out;
  }
  /// Pixels that some sample covered.
  size_t covered() const {
    return size_t(std::count_if(depth_.pixels().begin(), depth_.pixels().end(),
                                [](uint32_t d) { return d < raster3d::kDepthMax; }));
  }

 private:
  ImageRGB sum_;
  Image<uint32_t> depth_;
  int count_ = 0;
};

/// The mesh drawn per pixel with the maps of the options (texture, bump, environment, shadows, floor), each of the
/// --samples frames into `resolve`; `seconds` gets the time of all --repeat frames.
void render_with_maps(const RasterArgs& a, const TriMesh& mesh, const Bounds3& box, Camera camera, const Vec3f& surface,
                      const Vec3f& background, SampleResolve& resolve, double& seconds) {
  const bool textured = !a.texture.empty() || !a.bump.empty();
  if (textured && mesh.uvs.empty())
    throw InvalidInput(fmt::format("{}: --texture and --bump need texture coordinates, and the mesh has none", a.mesh));
  // Everything is read before drawing.
  std::optional<Texture2D> texture, bump;
  std::optional<EnvironmentMap> environment;
  if (!a.texture.empty()) texture.emplace(load_texture(a.texture, Sampler{.filter = a.filter}));
  if (!a.bump.empty()) bump.emplace(load_texture(a.bump));
  if (!a.env.empty()) environment.emplace(load_environment_map(a.env));

  const auto [width, height] = a.camera.image_size();
  Bounds3 scene = box;
  raster3d::VertexArrays floor;
  if (a.floor) {
    floor = floor_under(box, up_index(a.camera.up_axis));
    for (const Vec3f& p : floor.positions) {
      scene.lo = glm::min(scene.lo, Vec3(p));
      scene.hi = glm::max(scene.hi, Vec3(p));
    }
    // The framing is the mesh's; the far plane must reach the floor's far corners.
    if (a.camera.far == 0)
      camera.far = std::max(camera.far, 2 * glm::length(scene.hi - scene.lo) + glm::length(camera.eye - camera.center));
  }
  if (a.env_cube && !environment && !a.floor)
    throw InvalidInput("--env-cube: nothing around the mesh to reflect; add --env or --floor");
  // z-fail shadow volumes need the far cap at infinity inside the view volume: a far plane at infinity.
  const bool volumes = a.shadows && a.shadow_method != ShadowMethod::map;
  if (volumes && a.shadow_method == ShadowMethod::zfail && camera.orthographic)
    throw InvalidInput(
        "--shadow-method zfail needs a perspective camera (its far plane at infinity); with --ortho "
        "use zpass or map");
  const Mat4 view = camera.view(), projection = volumes && a.shadow_method == ShadowMethod::zfail
                                                    ? infinite_perspective(camera.fovy, camera.aspect, camera.near)
                                                    : camera.projection();
  // The light, as in the fixed-function path: a direction or a point in world space, else over the viewer's
  // upper-left shoulder (fixed in eye space). `lighting_under(v)` places it in the eye space of view v.
  const bool point_light = !a.light_pos.empty();
  const Vec3 light = point_light           ? parse_vec3(a.light_pos, "--light-pos")
                     : a.light_dir.empty() ? glm::transpose(Mat3(view)) * glm::normalize(Vec3(-0.4, 0.6, 1.0))
                                           : glm::normalize(parse_vec3(a.light_dir, "--light-dir"));
  const auto lighting_under = [&](const Mat4& v) {
    raster3d::Lighting lighting;
    lighting.material = raster3d::Material::plastic(surface, 32, 0.4f);
    lighting.color_material = true;  // the (textured) surface color is C_r
    lighting.lights[0].position =
        point_light ? Vec4f(Vec3f(v * glm::dvec4(light, 1)), 1) : Vec4f(Vec3f(Mat3(v) * light), 0);
    return raster3d::PreparedLighting(lighting);
  };
  // The map is fitted to the mesh, the only caster: the floor beyond it is shadowed all the same.
  std::optional<raster3d::ShadowMap> shadow;
  if (a.shadows && !volumes)
    shadow.emplace(point_light
                       ? raster3d::ShadowMap::point(a.shadow_size, light, box.lo, box.hi)
                       : raster3d::ShadowMap(a.shadow_size, raster3d::ShadowMap::directional(light, box.lo, box.hi)));

  raster3d::SurfaceUniforms u;
  u.lighting = lighting_under(view);
  u.color = surface;
  u.maps.shadows[0] = shadow ? &*shadow : nullptr;
  raster3d::SurfaceUniforms floor_uniforms = u;  // the floor: light gray, shadows only (set_camera: per sample)
  floor_uniforms.color = Vec3f(0.85f);
  u.maps.texture = texture ? &*texture : nullptr;
  u.maps.bump = bump ? &*bump : nullptr;
  u.maps.bump_scale = float(a.bump_scale * glm::length(box.hi - box.lo));
  u.maps.environment = environment ? &*environment : nullptr;
  u.maps.reflectivity = float(a.reflect);

  const raster3d::VertexArrays arrays = raster3d::VertexArrays::from_mesh(mesh);
  // Shadow volumes: the mesh's own, the only caster (the floor only receives).
  std::vector<raster3d::ShadowVolume> shadow_volumes;
  if (volumes)
    shadow_volumes.push_back(
        raster3d::shadow_volume(arrays.positions, arrays.indices, Vec4f(Vec3f(light), point_light ? 1.0f : 0.0f)));
  const raster3d::UvTangents tangents =
      bump ? raster3d::uv_tangents(arrays.positions, arrays.uvs, arrays.indices) : raster3d::UvTangents{};
  raster3d::RasterState state;
  state.cull = a.cull;
  // --env-cube: what surrounds the mesh (the floor, the environment) seen from its center, the notes' "render scene
  // 6 times, eye at center of cube".
  const auto draw_surroundings = [&](raster3d::Framebuffer& face, const Mat4& p, const Mat4& v) {
    if (a.floor) {
      raster3d::SurfaceUniforms f = floor_uniforms;
      f.set_camera(p, v);
      f.lighting = lighting_under(v);
      raster3d::draw_surface(face, raster3d::RasterState{}, floor, f);
    }
    if (environment) raster3d::fill_background(face, *environment, p * v);
  };
  std::optional<CubeMap> cube;
  raster3d::Framebuffer fb(width, height);
  Progress progress("raster", int64_t(a.repeat) * a.samples);
  const auto start = std::chrono::steady_clock::now();
  for (int frame = 0; frame < a.repeat; ++frame) {
    if (shadow) {
      shadow->clear();
      shadow->draw(arrays);
    }
    if (a.env_cube) {
      const Vec3 center = 0.5 * (box.lo + box.hi);
      cube.emplace(
          raster3d::render_cube_map(center, 256, draw_surroundings, 1e-3 * glm::length(box.hi - box.lo), camera.far));
      u.maps.cube = &*cube;
    }
    for (int sample = 0; sample < a.samples; ++sample) {
      const Mat4 jittered =
          jittered_projection(projection, pixel_sample(sample, a.samples, kSamplePattern), width, height);
      u.set_camera(jittered, view);
      floor_uniforms.set_camera(jittered, view);
      fb.clear(background);
      // Light 0 off (0) or on (1), as the shadow volumes' passes ask; without them, on.
      const auto draw_scene = [&](const raster3d::RasterState& pass, float light0) {
        raster3d::RasterState mesh_state = pass;
        mesh_state.cull = state.cull;
        raster3d::SurfaceUniforms mesh_uniforms = u, f = floor_uniforms;
        mesh_uniforms.light0 = f.light0 = light0;
        raster3d::draw_surface(fb, mesh_state, arrays, mesh_uniforms, bump ? &tangents : nullptr);
        if (a.floor) raster3d::draw_surface(fb, pass, floor, f);
      };
      if (volumes)
        raster3d::draw_with_shadow_volumes(
            fb, shadow_volumes, Mat4f(jittered * view),
            a.shadow_method == ShadowMethod::zfail ? raster3d::ShadowCount::zfail : raster3d::ShadowCount::zpass,
            draw_scene);
      else
        draw_scene(raster3d::RasterState{}, 1.0f);
      progress.advance();
      if (frame + 1 < a.repeat) continue;
      if (environment) raster3d::fill_background(fb, *environment, jittered * view);
      resolve.add(fb, false);
    }
  }
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Writes the image and, with --depth-out, the depth buffer: both or neither.
void write_outputs(const RasterArgs& a, const SampleResolve& resolve, const WriteOptions& options) {
  write_image(a.output, resolve.color(), options);
  if (!a.depth_out.empty()) {
    try {
      write_pfm(a.depth_out, resolve.depth());
    } catch (...) {
      std::filesystem::remove(a.output);
      throw;
    }
  }
}

/// The --stats lines (docs/cli.md): triangles (and the older `tris`) and pixels per frame (pixels: those the mesh
/// covers), the image's size and samples, `seconds` for all `repeat` frames' drawing, and the command's phases.
void print_raster_stats(const RasterArgs& a, const SampleResolve& resolve, const TriMesh& mesh, double seconds,
                        const PhaseTimer& timer) {
  const double tris = double(mesh.triangle_count());
  const auto [width, height] = a.camera.image_size();
  StatRows rows = {{"triangles", stat_value(tris)},
                   {"tris", stat_value(tris)},
                   {"pixels", stat_value(double(resolve.covered()))},
                   {"width", stat_value(width)},
                   {"height", stat_value(height)},
                   {"samples", stat_value(a.samples)},
                   {"seconds", stat_value(seconds)},
                   {"tris_per_s", stat_value(seconds > 0 ? tris * a.repeat * a.samples / seconds : 0)}};
  for (auto& row : timer.rows()) rows.push_back(row);
  print_stats(rows);
}

/// The mesh drawn by the fixed-function pipeline (--shading, --wireframe, --opacity, --hidden-surface), each of the
/// --samples frames into `resolve`; `seconds` gets the time of all --repeat frames.
void render_fixed_function(const RasterArgs& a, const PolyMesh& poly, const TriMesh& mesh, const Camera& camera,
                           const Vec3f& surface, const Vec3f& bg, SampleResolve& resolve, double& seconds) {
  const auto [width, height] = a.camera.image_size();
  const bool painter = a.hidden_surface == raster3d::HiddenSurface::painter;
  const Vec3 light_dir = a.light_dir.empty() ? Vec3(0) : parse_vec3(a.light_dir, "--light-dir");
  const Vec3 light_pos = a.light_pos.empty() ? Vec3(0) : parse_vec3(a.light_pos, "--light-pos");
  raster3d::Context ctx(width, height);
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  // The light: a direction or a point in world space (set under the view matrix, as glLight), else a light over
  // the viewer's upper-left shoulder in eye space.
  if (a.light_dir.empty() && a.light_pos.empty())
    ctx.light(0, {.position = Vec4f(glm::normalize(Vec3f(-0.4f, 0.6f, 1.0f)), 0)});
  ctx.look_at(camera.eye, camera.center, camera.up);
  if (!a.light_dir.empty()) ctx.light(0, {.position = Vec4f(Vec3f(glm::normalize(light_dir)), 0)});
  if (!a.light_pos.empty()) ctx.light(0, {.position = Vec4f(Vec3f(light_pos), 1)});
  ctx.material(raster3d::Material::plastic(surface, 32, 0.4f));
  ctx.color(surface);
  ctx.shading(a.shading);
  ctx.cull(a.cull);
  ctx.hidden_surface(a.hidden_surface);
  if (painter) {
    // The painter's algorithm keeps no depth: the stencil buffer records which pixels the mesh covers.
    ctx.stencil_test(true);
    const raster3d::StencilFace mark{.ref = 1, .zpass = raster3d::StencilOp::replace};
    ctx.stencil(mark, mark);
  }
  raster3d::VertexArrays arrays = raster3d::VertexArrays::from_mesh(mesh);
  if (a.opacity < 1) {
    // Transparency: "over" blending of the triangles sorted far to near, the z-buffer still on (for --depth-out and
    // the pixel count) and passing them in that order.
    raster3d::sort_back_to_front(arrays, look_at(camera.eye, camera.center, camera.up));
    ctx.alpha(float(a.opacity));
    ctx.blend(true);
    ctx.blend_function({raster3d::BlendFactor::src_alpha, raster3d::BlendFactor::one_minus_src_alpha});
    ctx.depth_func(raster3d::DepthFunc::lequal);
  }
  const auto edges = a.wireframe ? polygon_edges(poly) : std::vector<std::pair<uint32_t, uint32_t>>{};
  // Edges dark on a light background, light on a dark one.
  const Vec3f wire_color = (bg.x + bg.y + bg.z) > 1.5f ? Vec3f(0.1f, 0.1f, 0.15f) : Vec3f(0.9f, 0.9f, 0.8f);

  Progress progress("raster", int64_t(a.repeat) * a.samples);
  const auto start = std::chrono::steady_clock::now();
  for (int frame = 0; frame < a.repeat; ++frame)
    for (int sample = 0; sample < a.samples; ++sample) {
      ctx.matrix_mode(raster3d::MatrixMode::projection);
      ctx.load_matrix(
          jittered_projection(camera.projection(), pixel_sample(sample, a.samples, kSamplePattern), width, height));
      ctx.matrix_mode(raster3d::MatrixMode::model_view);
      ctx.clear(bg);
      if (painter) ctx.clear_stencil(0);
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
        ctx.alpha(1);
        ctx.begin(raster3d::Primitive::lines);
        for (const auto& [u, v] : edges) {
          ctx.vertex(poly.positions[u].x, poly.positions[u].y, poly.positions[u].z);
          ctx.vertex(poly.positions[v].x, poly.positions[v].y, poly.positions[v].z);
        }
        ctx.end();
        ctx.shading(saved);
        ctx.color(surface);
        ctx.alpha(float(a.opacity));
        ctx.matrix_mode(raster3d::MatrixMode::projection);
        ctx.pop_matrix();
        ctx.matrix_mode(raster3d::MatrixMode::model_view);
      }
      ctx.flush();
      progress.advance();
      if (frame + 1 == a.repeat) resolve.add(ctx.framebuffer(), painter);
    }
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void run_raster(const RasterArgs& a, const CommonOptions& common) {
  // Every option is checked before the mesh is read or anything is drawn.
  const auto [width, height] = a.camera.image_size();
  // Per pixel: the framebuffer (color and depth), the samples' sum and depth, the 8-bit copy (42 bytes measured). A
  // shadow map: 4 bytes a texel, 1.5 times size^2 texels for a point light among the casters (six faces of size/2).
  const bool shadow_map = a.shadows && a.shadow_method == ShadowMethod::map;
  MemoryBudget::check(saturating_product({uint64_t(width), uint64_t(height), 44}) +
                          (shadow_map ? saturating_product({uint64_t(a.shadow_size), uint64_t(a.shadow_size), 6}) : 0),
                      shadow_map ? fmt::format("rasterizing {}x{} pixels with a {}x{} shadow map", width, height,
                                               a.shadow_size, a.shadow_size)
                                 : fmt::format("rasterizing {}x{} pixels", width, height));
  const Rgb color = parse_color(a.color, "--color"), background = parse_color(a.background, "--background");
  if (!a.light_dir.empty() && !a.light_pos.empty())
    throw InvalidInput("--light-dir and --light-pos: give one light, not both");
  const Vec3 light_dir = a.light_dir.empty() ? Vec3(0) : parse_vec3(a.light_dir, "--light-dir");
  if (!a.light_dir.empty() && glm::length(light_dir) == 0) throw InvalidInput("--light-dir: expected a nonzero vector");
  if (!a.depth_out.empty() && std::filesystem::path(a.depth_out).extension() != ".pfm")
    throw InvalidInput(fmt::format("--depth-out: expected a .pfm file, got '{}'", a.depth_out));
  const raster3d::ShadingModel shading = a.shading;
  if (a.maps() && a.shading_given && shading != raster3d::ShadingModel::phong)
    throw InvalidInput(
        fmt::format("--shading {}: texture, bump, environment and shadow mapping are per pixel "
                    "(--shading phong, the default with them)",
                    name_of(kShadings, a.shading)));
  if (a.shadow_method != ShadowMethod::map && !a.shadows)
    throw InvalidInput(
        fmt::format("--shadow-method {}: shadows are off; add --shadows", name_of(kShadowMethods, a.shadow_method)));
  if (a.maps() && a.wireframe)
    throw InvalidInput("--wireframe does not combine with --texture, --bump, --env, --env-cube, --shadows or --floor");
  if (a.maps() && a.opacity < 1)
    throw InvalidInput("--opacity does not combine with --texture, --bump, --env, --env-cube, --shadows or --floor");
  const bool painter = a.hidden_surface == raster3d::HiddenSurface::painter;
  if (painter && a.maps())
    throw InvalidInput(
        "--hidden-surface painter: the maps and shadows (--texture, --bump, --env, --env-cube, "
        "--shadows, --floor) draw with the z-buffer");
  if (painter && a.wireframe)
    throw InvalidInput("--hidden-surface painter: --wireframe needs the z-buffer to hide the edges behind the surface");
  if (painter && !a.depth_out.empty())
    throw InvalidInput("--hidden-surface painter keeps no depth buffer to write with --depth-out");

  PhaseTimer timer;
  PolyMesh poly = timer.time("read_s", [&] { return read_mesh_with_progress(a.mesh); });
  if (poly.face_count() == 0) throw InvalidInput(fmt::format("{}: the mesh has no faces to draw", a.mesh));
  double seconds = 0;
  SampleResolve resolve(width, height);
  TriMesh mesh;
  timer.time("compute_s", [&] {
    // Normals come from the winding when the file has none: an inside-out mesh is drawn turned outward.
    const bool own_normals = !poly.normals.empty() || !poly.corner_normals.empty();
    if (!own_normals && winds_inward(poly)) {
      reverse_faces(poly);
      if (!common.quiet)
        fmt::print(stderr, "tessera: note: {}: the faces wind inward (a negative volume); drawn turned outward\n",
                   a.mesh);
    }
    if (shading != raster3d::ShadingModel::unlit && poly.normals.empty() && poly.corner_normals.empty())
      compute_vertex_normals(poly);
    mesh = to_tri_mesh(poly);
    if (shading == raster3d::ShadingModel::flat) mesh = split_faceted(mesh);
    const Bounds3 box = bounding_box(poly);
    const Camera camera = a.camera.camera(box.lo, box.hi);
    const Vec3f surface(color.r, color.g, color.b);
    const Vec3f bg(background.r, background.g, background.b);
    if (a.maps())
      render_with_maps(a, mesh, box, camera, surface, bg, resolve, seconds);
    else
      render_fixed_function(a, poly, mesh, camera, surface, bg, resolve, seconds);
  });
  timer.time("write_s", [&] { write_outputs(a, resolve, common.write_options()); });
  if (common.stats) print_raster_stats(a, resolve, mesh, seconds, timer);
}

}  // namespace

void setup_raster(CLI::App& cmd, CommonOptions& common) {
  auto a = std::make_shared<RasterArgs>();
  cmd.add_option("mesh", a->mesh, "Mesh file (.obj, .ply, .off, .stl)")->required();
  cmd.add_option("-o,--output", a->output, "Output image (.png, .ppm, .pfm, .hdr, .jpg, ...)")->required();
  a->camera.add(cmd);
  add_choice(cmd, "--shading", a->shading, kShadings,
             "unlit | flat (per polygon) | gouraud (per vertex) | phong (per pixel; the default with maps)");
  cmd.add_option("--color", a->color, "Surface color: a name, #rrggbb or r,g,b in [0,1] (a plastic: white highlights)")
      ->check(color_format())
      ->capture_default_str();
  cmd.add_option("--background", a->background, "Background color: a name, #rrggbb or r,g,b")
      ->check(color_format())
      ->capture_default_str();
  cmd.add_option(
         "--light-dir", a->light_dir,
         "Directional light: world-space direction toward the light x,y,z (default: over the viewer's shoulder)")
      ->check(numbers_format(3));
  cmd.add_option("--light-pos", a->light_pos, "Point light at world-space x,y,z")->check(numbers_format(3));
  cmd.add_flag("--wireframe", a->wireframe, "Draw the polygon edges over the surface");
  add_choice(cmd, "--cull", a->cull, {{"back", raster3d::CullMode::back}, {"none", raster3d::CullMode::none}},
             "Back-face culling: back | none");
  cmd.add_option("--depth-out", a->depth_out, "Also write the depth buffer (window z in [0,1], 1 = background) as PFM");
  cmd.add_option("--repeat", a->repeat, "Render N frames (for timing with --stats)")
      ->check(positive())
      ->capture_default_str();
  CLI::Option* texture =
      cmd.add_option("--texture", a->texture, "Texture image colouring the surface (needs the mesh's uvs)");
  add_choice(cmd, "--filter", a->filter,
             {{"nearest", Filter::nearest}, {"bilinear", Filter::bilinear}, {"trilinear", Filter::trilinear}},
             "Texture filter: nearest | bilinear | trilinear (MIPmaps)")
      ->needs(texture);
  CLI::Option* bump =
      cmd.add_option("--bump", a->bump, "Bump map: height image (red channel), Blinn's bump mapping (needs uvs)");
  cmd.add_option("--bump-scale", a->bump_scale, "Height of a white bump texel, as a fraction of the mesh's size")
      ->check(non_negative())
      ->capture_default_str()
      ->needs(bump);
  cmd.add_option("--env", a->env, "Environment map: a lat-long (equirectangular) image the surface reflects");
  cmd.add_option("--reflect", a->reflect, "How much of the environment the surface reflects, in [0,1]")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd.add_flag("--env-cube", a->env_cube,
               "Reflect what surrounds the mesh (--floor, --env) through a cube map rendered from its center");
  CLI::Option* shadows =
      cmd.add_flag("--shadows", a->shadows, "Shadow mapping: the light's depth map (pass 1) shadows the surfaces");
  add_choice(cmd, "--shadow-method", a->shadow_method, kShadowMethods,
             "With --shadows: map (shadow mapping) | zpass | zfail (stencil shadow volumes, counted in front of or "
             "behind the surface; zfail is right with the eye in shadow)");
  cmd.add_option("--shadow-size", a->shadow_size, "Shadow map size in texels")
      ->check(CLI::Range(16, raster3d::ShadowMap::kMaxSize))
      ->capture_default_str()
      ->needs(shadows);
  cmd.add_option("--opacity", a->opacity,
                 "Surface opacity in [0,1]: below 1 the triangles are sorted far to near and blended over what lies "
                 "behind them (alpha blending)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd.add_flag("--floor", a->floor, "Add a light gray floor under the mesh (along --up-axis), to receive its shadow");
  add_choice(cmd, "--hidden-surface", a->hidden_surface,
             {{"zbuffer", raster3d::HiddenSurface::zbuffer}, {"painter", raster3d::HiddenSurface::painter}},
             "Hidden-surface removal: the z-buffer, or the painter's algorithm (triangles sorted by average depth, "
             "drawn far to near; wrong where triangles intersect or overlap cyclically)");
  add_samples_option(cmd, a->samples);
  add_srgb_option(cmd, common);
  cmd.callback([a, &common, &cmd] {
    a->shading_given = cmd.count("--shading") > 0;
    // Options that would change nothing are refused rather than ignored.
    if (cmd.count("--reflect") > 0 && a->env.empty() && !a->env_cube)
      throw InvalidInput("--reflect: nothing to reflect; add --env or --env-cube");
    if (a->shading == raster3d::ShadingModel::unlit && (!a->light_dir.empty() || !a->light_pos.empty()))
      throw InvalidInput("--shading unlit draws without lights; --light-dir and --light-pos need a lit shading");
    run_raster(*a, common);
  });
}

}  // namespace tessera::cli
