// tessera raster MESH -o IMG: a mesh file drawn by the library's one mesh renderer (scene's MeshView, mesh_view.hpp):
// the command parses and checks the options, reads the mesh and the maps, and writes the pictures.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <utility>

#include "camera_options.hpp"
#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/glsl/program.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/raster3d/shadow_map.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera::cli {
namespace {

struct RasterArgs {
  std::string mesh, output, color = "0.8,0.8,0.8", background = "0,0,0", light_dir, light_pos, depth_out;
  MeshShading shading = MeshShading::gouraud;
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
  // A GLSL program (libs/glsl) instead of the shading, its uniforms ("name=v1,v2,...") and textures ("N=IMG").
  std::string vertex_shader, fragment_shader, texture0, texture1;
  std::vector<std::string> uniforms, texture_units, cube_maps;

  bool program() const { return !vertex_shader.empty() || !fragment_shader.empty(); }
  bool program_inputs() const {
    return !uniforms.empty() || !texture_units.empty() || !cube_maps.empty() || !texture0.empty() || !texture1.empty();
  }

  bool maps() const { return !texture.empty() || !bump.empty() || !env.empty() || shadows || floor || env_cube; }
};

template <class T>
using Names = std::vector<std::pair<std::string, T>>;

const Names<MeshShading> kShadings = {{"unlit", MeshShading::unlit},
                                      {"flat", MeshShading::flat},
                                      {"gouraud", MeshShading::gouraud},
                                      {"phong", MeshShading::phong}};
const Names<ShadowMethod> kShadowMethods = {
    {"map", ShadowMethod::map}, {"zpass", ShadowMethod::zpass}, {"zfail", ShadowMethod::zfail}};

/// The option name of an enum value (for messages).
template <class T>
const std::string& name_of(const Names<T>& names, T value) {
  return std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.second == value; })->first;
}

/// The model's up axis as a coordinate index.
int up_index(UpAxis axis) { return axis == UpAxis::x ? 0 : axis == UpAxis::y ? 1 : 2; }

/// Splits "key=value" (the --texture-unit and --cube-map forms). Throws InvalidInput naming the option.
std::pair<std::string, std::string> key_value(const std::string& text, const char* option, const char* form) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InvalidInput(fmt::format("{}: expected {}, got '{}'", option, form, printable(text)));
  return {text.substr(0, eq), text.substr(eq + 1)};
}

/// A texture unit number of --texture-unit or --cube-map.
int unit_number(const std::string& text, const char* option) {
  const long long unit = parse_int(text, option);
  if (unit < 0 || unit >= 16) throw InvalidInput(fmt::format("{}: texture unit {} is not in [0, 16)", option, unit));
  return int(unit);
}

/// The GLSL program of --vertex-shader and --fragment-shader, with its uniforms and textures bound.
std::shared_ptr<glsl::Program> load_program(const RasterArgs& a) {
  auto program = std::make_shared<glsl::Program>(
      glsl::Program::compile(glsl::read_shader(a.vertex_shader), glsl::read_shader(a.fragment_shader)));
  for (const std::string& u : a.uniforms) program->set_uniform_assignment(u);
  std::vector<std::pair<int, std::string>> textures;
  if (!a.texture0.empty()) textures.emplace_back(0, a.texture0);
  if (!a.texture1.empty()) textures.emplace_back(1, a.texture1);
  for (const std::string& t : a.texture_units) {
    const auto [unit, path] = key_value(t, "--texture-unit", "N=IMAGE");
    textures.emplace_back(unit_number(unit, "--texture-unit"), path);
  }
  for (const auto& [unit, path] : textures)
    program->bind_texture(unit, std::make_shared<Texture2D>(load_texture(path, Sampler{.filter = a.filter})));
  for (const std::string& c : a.cube_maps) {
    const auto [unit, path] = key_value(c, "--cube-map", "N=IMAGE");
    const EnvironmentMap env = load_environment_map(path);
    // The lat-long image resampled onto six faces of half its height (at most 1024).
    const int size = std::clamp(env.texture().height() / 2, 1, 1024);
    program->bind_cube_map(unit_number(unit, "--cube-map"),
                           std::make_shared<CubeMap>(CubeMap::from_function(
                               size, [&](const glm::vec3& d) { return env.lookup(d); }, Filter::bilinear)));
  }
  return program;
}

/// The library's options from the command's (the maps read from their files here: the library takes them loaded).
MeshViewOptions view_options(const RasterArgs& a, const Rgb& color, const Rgb& background) {
  MeshViewOptions o;
  o.shading = a.shading;
  o.color = Vec3f(color.r, color.g, color.b);
  o.background = Vec3f(background.r, background.g, background.b);
  if (!a.light_dir.empty()) o.light = {MeshLightKind::directional, parse_vec3(a.light_dir, "--light-dir")};
  if (!a.light_pos.empty()) o.light = {MeshLightKind::point, parse_vec3(a.light_pos, "--light-pos")};
  o.wireframe = a.wireframe ? MeshWireframe::over : MeshWireframe::none;
  o.cull = a.cull;
  o.hidden_surface = a.hidden_surface;
  o.opacity = a.opacity;
  o.samples = a.samples;
  if (!a.texture.empty()) o.texture = std::make_shared<Texture2D>(load_texture(a.texture, Sampler{.filter = a.filter}));
  if (!a.bump.empty()) o.bump = std::make_shared<Texture2D>(load_texture(a.bump));
  if (!a.env.empty()) o.environment = std::make_shared<EnvironmentMap>(load_environment_map(a.env));
  o.bump_scale = a.bump_scale;
  o.reflect = a.reflect;
  o.env_cube = a.env_cube;
  o.shadows = a.shadows;
  o.shadow_method = a.shadow_method;
  o.shadow_size = a.shadow_size;
  o.floor = a.floor;
  o.up_axis = up_index(a.camera.up_axis);
  if (a.program()) o.program = load_program(a);
  return o;
}

/// Writes the image and, with --depth-out, the depth buffer: both or neither.
void write_outputs(const RasterArgs& a, const MeshPicture& picture, const WriteOptions& options) {
  write_image(a.output, picture.color, options);
  if (!a.depth_out.empty()) {
    try {
      write_pfm(a.depth_out, picture.depth);
    } catch (...) {
      std::filesystem::remove(a.output);
      throw;
    }
  }
}

/// The --stats lines (docs/cli.md): triangles (and the older `tris`) and pixels per frame (pixels: those the mesh
/// covers), the image's size and samples, `seconds` for all `repeat` frames' drawing, and the command's phases.
void print_raster_stats(const RasterArgs& a, const MeshPicture& picture, size_t triangles, double seconds,
                        const PhaseTimer& timer) {
  const double tris = double(triangles);
  const auto [width, height] = a.camera.image_size();
  StatRows rows = {{"triangles", stat_value(tris)},
                   {"tris", stat_value(tris)},
                   {"pixels", stat_value(double(picture.covered))},
                   {"width", stat_value(width)},
                   {"height", stat_value(height)},
                   {"samples", stat_value(a.samples)},
                   {"seconds", stat_value(seconds)},
                   {"tris_per_s", stat_value(seconds > 0 ? tris * a.repeat * a.samples / seconds : 0)}};
  for (auto& row : timer.rows()) rows.push_back(row);
  print_stats(rows);
}

void run_raster(const RasterArgs& a, const CommonOptions& common) {
  // Every option is checked before the mesh is read or anything is drawn. (Plain ints, not a structured binding: the
  // lambdas below capture them, which clang-tidy's clang 14 cannot parse.)
  const Size2 size = a.camera.image_size();
  const int width = size.width, height = size.height;
  MeshViewOptions planned;  // what the memory estimate reads
  planned.shadows = a.shadows;
  planned.shadow_method = a.shadow_method;
  planned.shadow_size = a.shadow_size;
  check_mesh_view_memory(width, height, planned);
  const Rgb color = parse_color(a.color, "--color"), background = parse_color(a.background, "--background");
  if (!a.light_dir.empty() && !a.light_pos.empty())
    throw InvalidInput("--light-dir and --light-pos: give one light, not both");
  const Vec3 light_dir = a.light_dir.empty() ? Vec3(0) : parse_vec3(a.light_dir, "--light-dir");
  if (!a.light_dir.empty() && glm::length(light_dir) == 0) throw InvalidInput("--light-dir: expected a nonzero vector");
  if (!a.depth_out.empty() && std::filesystem::path(a.depth_out).extension() != ".pfm")
    throw InvalidInput(fmt::format("--depth-out: expected a .pfm file, got '{}'", a.depth_out));
  if (a.maps() && a.shading_given && a.shading != MeshShading::phong)
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
  if (a.program() && a.maps())
    throw InvalidInput(
        "--vertex-shader/--fragment-shader: the program draws the surface; --texture, --bump, --env, --env-cube, "
        "--shadows and --floor do not combine with it (bind textures with --texture0)");
  if (a.program() && a.shading_given) throw InvalidInput("--shading: the program does the shading");
  const bool painter = a.hidden_surface == raster3d::HiddenSurface::painter;
  if (painter && a.maps())
    throw InvalidInput(
        "--hidden-surface painter: the maps and shadows (--texture, --bump, --env, --env-cube, "
        "--shadows, --floor) draw with the z-buffer");
  if (painter && a.wireframe)
    throw InvalidInput("--hidden-surface painter: --wireframe needs the z-buffer to hide the edges behind the surface");
  if (painter && !a.depth_out.empty())
    throw InvalidInput("--hidden-surface painter keeps no depth buffer to write with --depth-out");
  if (a.env_cube && a.env.empty() && !a.floor)
    throw InvalidInput("--env-cube: nothing around the mesh to reflect; add --env or --floor");
  if (a.shadows && a.shadow_method == ShadowMethod::zfail && a.camera.ortho)
    throw InvalidInput(
        "--shadow-method zfail needs a perspective camera (its far plane at infinity); with --ortho "
        "use zpass or map");

  PhaseTimer timer;
  PolyMesh poly = timer.time("read_s", [&] { return read_mesh_with_progress(a.mesh); });
  if (poly.face_count() == 0) throw InvalidInput(fmt::format("{}: the mesh has no faces to draw", a.mesh));
  if ((!a.texture.empty() || !a.bump.empty()) && poly.uvs.empty() && poly.corner_uvs.empty())
    throw InvalidInput(fmt::format("{}: --texture and --bump need texture coordinates, and the mesh has none", a.mesh));
  double seconds = 0;
  MeshPicture picture;
  size_t triangles = 0;
  timer.time("compute_s", [&] {
    // Everything is read and prepared before drawing.
    MeshViewOptions options = view_options(a, color, background);
    const MeshView view(std::move(poly), std::move(options));
    if (view.turned_outward() && !common.quiet)
      fmt::print(stderr, "tessera: note: {}: the faces wind inward (a negative volume); drawn turned outward\n",
                 a.mesh);
    triangles = view.triangle_count();
    Camera camera = a.camera.camera(view.bounds().lo, view.bounds().hi);
    if (a.floor && a.camera.far == 0) {
      // The framing is the mesh's; the far plane must reach the floor's far corners.
      const Bounds3 scene = view.scene_bounds();
      camera.far = std::max(camera.far, 2 * glm::length(scene.hi - scene.lo) + glm::length(camera.eye - camera.center));
    }
    Progress progress("raster", int64_t(a.repeat) * a.samples);
    const auto start = std::chrono::steady_clock::now();
    for (int frame = 0; frame < a.repeat; ++frame) picture = view.render(camera, width, height, &progress);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
  timer.time("write_s", [&] { write_outputs(a, picture, common.write_options()); });
  if (common.stats) print_raster_stats(a, picture, triangles, seconds, timer);
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
  cmd.add_option("--texture", a->texture, "Texture image colouring the surface (needs the mesh's uvs)");
  add_choice(cmd, "--filter", a->filter,
             {{"nearest", Filter::nearest}, {"bilinear", Filter::bilinear}, {"trilinear", Filter::trilinear}},
             "Texture filter of --texture and of a program's textures: nearest | bilinear | trilinear (MIPmaps)");
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
  cmd.add_option("--vertex-shader", a->vertex_shader,
                 "GLSL vertex shader file (the notes' GLSL 1.10 with gl_Vertex, ftransform(), ... or GLSL 3.30+): "
                 "with --fragment-shader, the program draws the surface (docs/shaders.md)");
  cmd.add_option("--fragment-shader", a->fragment_shader, "GLSL fragment shader file (with --vertex-shader)");
  cmd.add_option("--uniform", a->uniforms,
                 "A program's uniform: name=v1,v2,... (floats, ints for int, bool and sampler uniforms: a sampler's "
                 "texture unit); repeat for more");
  cmd.add_option("--texture0", a->texture0,
                 "Image bound to texture unit 0 of the program (samplers read unit 0 "
                 "unless --uniform sets them)");
  cmd.add_option("--texture1", a->texture1, "Image bound to texture unit 1 of the program");
  cmd.add_option("--texture-unit", a->texture_units, "Image bound to a texture unit of the program: N=IMAGE");
  cmd.add_option("--cube-map", a->cube_maps,
                 "A lat-long (equirectangular) image bound to texture unit N as a cube map (samplerCube): N=IMAGE");
  add_samples_option(cmd, a->samples);
  add_srgb_option(cmd, common);
  cmd.callback([a, &common, &cmd] {
    a->shading_given = cmd.count("--shading") > 0;
    // Usage errors (exit 2), as CLI11's own.
    if (cmd.count("--filter") > 0 && a->texture.empty() && a->texture0.empty() && a->texture1.empty() &&
        a->texture_units.empty())
      throw CLI::ValidationError("--filter", "no texture to filter; add --texture (or a program's --texture0)");
    if (a->program() && (a->vertex_shader.empty() || a->fragment_shader.empty()))
      throw CLI::ValidationError("--vertex-shader and --fragment-shader", "a program needs both");
    if (a->program_inputs() && !a->program())
      throw CLI::ValidationError("--uniform, --texture0, --texture1, --texture-unit, --cube-map",
                                 "they set a program's inputs; add --vertex-shader and --fragment-shader");
    // Options that would change nothing are refused rather than ignored.
    if (cmd.count("--reflect") > 0 && a->env.empty() && !a->env_cube)
      throw InvalidInput("--reflect: nothing to reflect; add --env or --env-cube");
    if (a->shading == MeshShading::unlit && (!a->light_dir.empty() || !a->light_pos.empty()))
      throw InvalidInput("--shading unlit draws without lights; --light-dir and --light-pos need a lit shading");
    run_raster(*a, common);
  });
}

}  // namespace tessera::cli
