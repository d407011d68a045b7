// Rendering: meshes through the rasterizer (scene's MeshView, as `tessera raster`), scenes through the ray tracer
// or the rasterizer (as `tessera render`), and ray casting numpy ray batches against a mesh's BVH.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>

#include "bindings.hpp"
#include "convert.hpp"
#include "tessera/accel/mesh_accel.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/glsl/program.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/raytrace/render.hpp"
#include "tessera/scene/mesh_view.hpp"
#include "tessera/scene/raster.hpp"
#include "tessera/scene/scene.hpp"
#include "tessera/scene/trace.hpp"

namespace tessera::python {
namespace {

/// An image option: a file path (8-bit files stay 8-bit) or an image array.
Texture2D texture(const py::object& value, const Sampler& sampler, const std::string& what) {
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))
    return load_texture(py::str(value).cast<std::string>(), sampler);
  return Texture2D(image_rgba(value, what), sampler);
}

/// A shader option: source text (it has a newline) or a file path.
glsl::ShaderSource shader(const py::object& value, const char* what) {
  const std::string text = py::str(value);
  if (text.find('\n') != std::string::npos) return {text, what};
  return glsl::read_shader(text);
}

/// The GLSL program of the options vertex_shader and fragment_shader, its uniforms ({name: number or sequence}) and
/// textures ({unit: path or image}) bound; null without shaders.
std::shared_ptr<glsl::Program> program(Options& options, const Sampler& sampler) {
  const py::object vs = options.take("vertex_shader"), fs = options.take("fragment_shader");
  const py::object uniforms = options.take("uniforms"), textures = options.take("textures"),
                   cube_maps = options.take("cube_maps");
  if (vs.is_none() && fs.is_none()) {
    if (!uniforms.is_none() || !textures.is_none() || !cube_maps.is_none())
      throw InvalidInput(
          "uniforms, textures and cube_maps: they are a program's; give vertex_shader and fragment_shader");
    return nullptr;
  }
  if (vs.is_none() || fs.is_none()) throw InvalidInput("vertex_shader and fragment_shader: give both");
  auto p = std::make_shared<glsl::Program>(
      glsl::Program::compile(shader(vs, "vertex shader"), shader(fs, "fragment shader")));
  if (!uniforms.is_none())
    for (const auto& [name, value] : uniforms.cast<py::dict>()) {
      const py::array a = py::array::ensure(value);
      std::string text;
      for (const py::handle v : a.attr("ravel")())
        text += (text.empty() ? "" : ",") + std::string(py::repr(v.attr("item")()));
      p->set_uniform_text(std::string(py::str(name)), text);
    }
  if (!textures.is_none())
    for (const auto& [unit, value] : textures.cast<py::dict>())
      p->bind_texture(unit.cast<int>(), std::make_shared<Texture2D>(
                                            texture(py::reinterpret_borrow<py::object>(value), sampler, "textures")));
  if (!cube_maps.is_none())
    for (const auto& [unit, value] : cube_maps.cast<py::dict>()) {
      const py::object v = py::reinterpret_borrow<py::object>(value);
      const EnvironmentMap env = py::isinstance<py::str>(v) ? load_environment_map(v.cast<std::string>())
                                                            : EnvironmentMap(image_rgba(v, "cube_maps"));
      // The lat-long image resampled onto six faces of half its height (at most 1024), as `tessera raster`.
      const int size = std::clamp(env.texture().height() / 2, 1, 1024);
      p->bind_cube_map(unit.cast<int>(),
                       std::make_shared<CubeMap>(CubeMap::from_function(
                           size, [&](const glm::vec3& d) { return env.lookup(d); }, Filter::bilinear)));
    }
  return p;
}

MeshViewOptions view_options(Options& options) {
  MeshViewOptions o;
  o.shading = choice<MeshShading>(options.get<std::string>("shading", "gouraud"),
                                  {{"unlit", MeshShading::unlit},
                                   {"flat", MeshShading::flat},
                                   {"gouraud", MeshShading::gouraud},
                                   {"phong", MeshShading::phong},
                                   {"normals", MeshShading::normals}},
                                  "shading");
  o.color = color(options.get<py::object>("color", py::make_tuple(0.8, 0.8, 0.8)), "color");
  o.background = color(options.get<py::object>("background", py::make_tuple(0, 0, 0)), "background");
  const py::object light_dir = options.take("light_dir"), light_pos = options.take("light_pos");
  if (!light_dir.is_none() && !light_pos.is_none()) throw InvalidInput("light_dir and light_pos: give one light");
  if (!light_dir.is_none()) o.light = {MeshLightKind::directional, vec3(light_dir, "light_dir")};
  if (!light_pos.is_none()) o.light = {MeshLightKind::point, vec3(light_pos, "light_pos")};
  o.wireframe = options.get("wireframe", false) ? MeshWireframe::over : MeshWireframe::none;
  o.cull = choice<raster3d::CullMode>(options.get<std::string>("cull", "none"),
                                      {{"none", raster3d::CullMode::none}, {"back", raster3d::CullMode::back}}, "cull");
  o.hidden_surface = choice<raster3d::HiddenSurface>(
      options.get<std::string>("hidden_surface", "zbuffer"),
      {{"zbuffer", raster3d::HiddenSurface::zbuffer}, {"painter", raster3d::HiddenSurface::painter}}, "hidden_surface");
  o.opacity = options.get("opacity", 1.0);
  o.samples = options.get("samples", 1);
  const Sampler sampler{
      .filter = choice<Filter>(
          options.get<std::string>("filter", "trilinear"),
          {{"nearest", Filter::nearest}, {"bilinear", Filter::bilinear}, {"trilinear", Filter::trilinear}}, "filter")};
  if (const py::object t = options.take("texture"); !t.is_none())
    o.texture = std::make_shared<Texture2D>(texture(t, sampler, "texture"));
  if (const py::object b = options.take("bump"); !b.is_none())
    o.bump = std::make_shared<Texture2D>(texture(b, Sampler{}, "bump"));
  if (const py::object e = options.take("env"); !e.is_none())
    o.environment =
        std::make_shared<EnvironmentMap>(py::isinstance<py::str>(e) ? load_environment_map(e.cast<std::string>())
                                                                    : EnvironmentMap(image_rgba(e, "env")));
  o.bump_scale = options.get("bump_scale", o.bump_scale);
  o.reflect = options.get("reflect", o.reflect);
  o.env_cube = options.get("env_cube", false);
  o.shadows = options.get("shadows", false);
  o.shadow_method = choice<ShadowMethod>(
      options.get<std::string>("shadow_method", "map"),
      {{"map", ShadowMethod::map}, {"zpass", ShadowMethod::zpass}, {"zfail", ShadowMethod::zfail}}, "shadow_method");
  o.shadow_size = options.get("shadow_size", o.shadow_size);
  o.floor = options.get("floor", false);
  o.program = program(options, sampler);
  return o;
}

py::tuple render_mesh_picture(py::handle value, int width, int height, py::dict kwargs) {
  Options options(std::move(kwargs));
  PolyMesh polys = mesh(value, "mesh");
  if (polys.face_count() == 0) throw InvalidInput("mesh: the mesh has no faces to draw");
  MeshViewOptions o = view_options(options);
  const Framing f = framing(options, 45);
  o.up_axis = int(f.up_axis);
  options.finish("render_mesh");
  if ((o.texture || o.bump) && polys.uvs.empty() && polys.corner_uvs.empty())
    throw InvalidInput("mesh: texture and bump need texture coordinates (uvs), and the mesh has none");
  if (o.maps() && o.wireframe != MeshWireframe::none)
    throw InvalidInput("wireframe does not combine with texture, bump, env, env_cube, shadows or floor");
  if (o.maps() && o.program) throw InvalidInput("a program draws the surface: no texture, bump, env, shadows or floor");
  MeshPicture picture;
  {
    py::gil_scoped_release release;
    const MeshView view(std::move(polys), std::move(o));
    Camera camera = frame_camera(f, view.bounds().lo, view.bounds().hi, double(width) / double(height));
    if (view.options().floor && f.far == 0) {
      // The framing is the mesh's; the far plane must reach the floor's far corners (as `tessera raster`).
      const Bounds3 scene = view.scene_bounds();
      camera.far = std::max(camera.far, 2 * glm::length(scene.hi - scene.lo) + glm::length(camera.eye - camera.center));
    }
    picture = view.render(camera, width, height);
  }
  const size_t covered = picture.covered;
  return py::make_tuple(to_python(std::move(picture.color)), to_python(std::move(picture.depth)), covered);
}

AnimatedScene animated_scene(const std::string& source, bool is_text, const std::string& base_dir) {
  return is_text ? AnimatedScene(source, "scene", base_dir) : load_animated_scene(source);
}

py::object render_scene(const std::string& source, bool is_text, const std::string& base_dir, std::optional<int> width,
                        std::optional<int> height, std::optional<int> samples, std::optional<int> depth, uint64_t seed,
                        const std::string& backend, std::optional<int> frame) {
  const bool raster = choice<bool>(backend, {{"raytrace", false}, {"raster", true}}, "backend");
  ImageRGB image;
  {
    py::gil_scoped_release release;
    const AnimatedScene animated = animated_scene(source, is_text, base_dir);
    const Scene scene = animated.at(frame.value_or(animated.animation().first));
    RenderSettings settings = render_settings(scene);
    if (width) settings.width = *width;
    if (height) settings.height = *height;
    if (samples) settings.samples = *samples;
    if (depth) settings.max_depth = *depth;
    settings.seed = seed;
    settings.progress = false;
    image = raster ? rasterize_scene(scene, settings.width, settings.height) : render(to_ray_scene(scene), settings);
  }
  return to_python(std::move(image));
}

/// A mesh's BVH for casting ray batches (MeshAccel over the triangulated mesh).
struct RayCaster {
  explicit RayCaster(const PolyMesh& polys) : mesh(to_tri_mesh(polys)), accel(mesh) {}
  TriMesh mesh;
  MeshAccel accel;
};

py::tuple cast_rays(const RayCaster& caster, py::handle origins, py::handle directions, float tmin, float tmax) {
  const auto o = rows(origins, 3, "origins"), d = rows(directions, 3, "directions");
  if (o.shape(0) != d.shape(0))
    throw InvalidInput(
        fmt::format("origins and directions: expected the same number of rays, got {} and {}", o.shape(0), d.shape(0)));
  const auto n = size_t(o.shape(0));
  std::vector<Ray> rays(n);
  for (size_t i = 0; i < n; ++i) {
    const double* a = o.data() + 3 * i;
    const double* b = d.data() + 3 * i;
    rays[i].origin = Vec3f(float(a[0]), float(a[1]), float(a[2]));
    rays[i].dir = Vec3f(float(b[0]), float(b[1]), float(b[2]));
    rays[i].tmin = tmin;
    rays[i].tmax = tmax;
  }
  py::array_t<float> t{py::ssize_t(n)};
  py::array_t<int32_t> prim{py::ssize_t(n)};
  py::array_t<float> uv({py::ssize_t(n), py::ssize_t(2)});
  float* tp = t.mutable_data();
  int32_t* pp = prim.mutable_data();
  float* uvp = uv.mutable_data();
  {
    py::gil_scoped_release release;
    std::vector<Hit> hits(n);
    // Chunks of rays in parallel; the batched walk inside each chunk overlaps their cache misses.
    parallel_for(0, int64_t(n), 4096, [&](int64_t begin, int64_t end) {
      caster.accel.intersect(std::span(rays).subspan(size_t(begin), size_t(end - begin)),
                             std::span(hits).subspan(size_t(begin), size_t(end - begin)));
      for (auto i = size_t(begin); i < size_t(end); ++i) {  // into numpy's arrays while the chunk is in cache
        tp[i] = hits[i].t;
        pp[i] = hits[i].prim;
        uvp[2 * i] = hits[i].uv.x;
        uvp[2 * i + 1] = hits[i].uv.y;
      }
    });
  }
  return py::make_tuple(t, prim, uv);
}

}  // namespace

void bind_rendering(py::module_& m) {
  m.def("_render_mesh", &render_mesh_picture, py::arg("mesh"), py::arg("width"), py::arg("height"), py::arg("options"));
  m.def("_render_scene", &render_scene, py::arg("source"), py::arg("is_text"), py::arg("base_dir"), py::arg("width"),
        py::arg("height"), py::arg("samples"), py::arg("depth"), py::arg("seed"), py::arg("backend"), py::arg("frame"));
  m.def(
      "_scene_animation",
      [](const std::string& source, bool is_text, const std::string& base_dir) {
        const AnimatedScene animated = animated_scene(source, is_text, base_dir);
        const SceneAnimation& a = animated.animation();
        return py::make_tuple(a.first, a.last, a.fps, a.shutter, animated.keyed());
      },
      py::arg("source"), py::arg("is_text"), py::arg("base_dir"));
  m.attr("builtin_scenes") = builtin_scene_names();
  py::class_<RayCaster, std::shared_ptr<RayCaster>>(m, "RayCaster",
                                                    R"(A mesh's bounding volume hierarchy for casting rays.

Built once (SAH binary BVH collapsed to 4- or 8-wide nodes, SIMD triangle tests, as the ray tracer's), then cast with
batches of rays: cast(origins (N, 3), directions (N, 3)) returns the hit distances t (N,) (inf for a miss), the
triangle ids (N,) (-1 for a miss; ids of the triangulated mesh, whose triangles follow the faces in order) and the
barycentrics (N, 2) of the triangle's vertices 1 and 2. Directions need not be unit length: t is in their units.)")
      .def(py::init([](py::handle value) {
             PolyMesh polys = mesh(value, "mesh");
             py::gil_scoped_release release;
             return std::make_shared<RayCaster>(polys);
           }),
           py::arg("mesh"), "Builds the BVH of a mesh (triangulated), the GIL released while it builds.")
      .def("cast", &cast_rays, py::arg("origins"), py::arg("directions"), py::kw_only(), py::arg("tmin") = 0.0f,
           py::arg("tmax") = std::numeric_limits<float>::infinity(),
           "Nearest hits of the rays origin + t direction, t in [tmin, tmax]: (t, triangle ids, barycentrics).")
      .def_property_readonly(
          "triangle_count", [](const RayCaster& c) { return c.accel.triangle_count(); },
          "The number of triangles cast against.");
}

}  // namespace tessera::python
