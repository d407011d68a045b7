// A scene through the rasterizer: shapes tessellated, materials and lights in OpenGL's terms.
#include "tessera/scene/raster.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <string>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/frame.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/shadow_map.hpp"
#include "tessera/raster3d/shadow_volume.hpp"
#include "tessera/raster3d/surface_shader.hpp"
#include "tessera/raytrace/render.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera {
namespace {

/// Every triangle with its own three vertices (split_faceted): its face normal (sharp edges on flat-faced shapes), or
/// with `face_normals` false the mesh's own normals; the mesh's uvs, or where it has none the triangle's barycentric
/// coordinates (0, 0), (1, 0), (0, 1), the ray tracer's texture coordinates on a mesh without uvs. No vertex colors:
/// the materials color the surface.
TriMesh unwelded(const TriMesh& mesh, bool face_normals = true) {
  static const Vec2 kBarycentric[3] = {{0, 0}, {1, 0}, {0, 1}};
  TriMesh out = split_faceted(mesh);
  out.colors.clear();
  for (size_t i = 0; i < out.positions.size(); ++i) {
    if (!face_normals) out.normals[i] = mesh.normals[mesh.indices[i]];
    if (mesh.uvs.empty()) out.uvs.push_back(kBarycentric[i % 3]);
  }
  return out;
}

/// The mesh with every position mapped by m (normals by its inverse transpose).
TriMesh transformed(TriMesh mesh, const Mat4& m) {
  for (auto& p : mesh.positions) p = transform_point(m, p);
  const Mat3 nm = glm::transpose(glm::inverse(Mat3(m)));
  for (auto& n : mesh.normals) n = glm::normalize(nm * n);
  return mesh;
}

/// A convex fan of `points` (in order) as triangles.
TriMesh fan(const std::vector<Vec3>& points) {
  PolyMesh poly;
  poly.positions = points;
  std::vector<uint32_t> face(points.size());
  for (size_t i = 0; i < face.size(); ++i) face[i] = uint32_t(i);
  poly.add_face(face);
  return unwelded(to_tri_mesh(poly));
}

/// `n` points on the circle of radius r about c in the plane with unit normal `normal`, counterclockwise about it.
std::vector<Vec3> circle(const Vec3& c, const Vec3& normal, double r, int n) {
  const Frame f = Frame::from_normal(Vec3f(normal));
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    points.push_back(c + r * (std::cos(a) * Vec3(f.s) + std::sin(a) * Vec3(f.t)));
  }
  return points;
}

}  // namespace

TriMesh tessellate(const Shape& shape, int segments, double plane_size) {
  const int stacks = std::max(2, segments / 2);
  TriMesh mesh = std::visit(
      [&](const auto& s) -> TriMesh {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          return transformed(to_tri_mesh(make_uv_sphere(segments, stacks)),
                             translate(s.center.x, s.center.y, s.center.z) * scale(s.radius, s.radius, s.radius));
        } else if constexpr (std::is_same_v<T, Ellipsoid>) {
          return transformed(to_tri_mesh(make_uv_sphere(segments, stacks)),
                             translate(s.center.x, s.center.y, s.center.z) * scale(s.radii.x, s.radii.y, s.radii.z));
        } else if constexpr (std::is_same_v<T, Plane>) {
          auto square = circle(Vec3(s.point), glm::normalize(Vec3(s.normal)), plane_size / std::sqrt(2.0), 4);
          return fan(square);
        } else if constexpr (std::is_same_v<T, Triangle>) {
          return fan({Vec3(s.a), Vec3(s.b), Vec3(s.c)});
        } else if constexpr (std::is_same_v<T, Polygon>) {
          PolyMesh poly;  // to_tri_mesh triangulates non-convex polygons too
          for (const auto& v : s.vertices) poly.positions.push_back(Vec3(v));
          std::vector<uint32_t> face(poly.positions.size());
          for (size_t i = 0; i < face.size(); ++i) face[i] = uint32_t(i);
          poly.add_face(face);
          return unwelded(to_tri_mesh(poly));
        } else if constexpr (std::is_same_v<T, Box>) {
          const Vec3 lo(s.lo), hi(s.hi), mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
          return unwelded(
              transformed(to_tri_mesh(make_box()), translate(mid.x, mid.y, mid.z) * scale(half.x, half.y, half.z)));
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          const double mid = 0.5 * (s.y0 + s.y1), half = 0.5 * (s.y1 - s.y0);
          TriMesh side = to_tri_mesh(make_cylinder(segments, false));
          side.normals.clear();
          for (const auto& p : side.positions) side.normals.push_back(glm::normalize(Vec3(p.x, 0, p.z)));
          TriMesh mesh = transformed(side, translate(0, mid, 0) * scale(s.radius, half, s.radius));
          if (s.capped)
            for (double y : {double(s.y0), double(s.y1)}) {
              const TriMesh cap = fan(circle({0, y, 0}, {0, y == s.y1 ? 1.0 : -1.0, 0}, s.radius, segments));
              const auto base = uint32_t(mesh.positions.size());
              mesh.positions.insert(mesh.positions.end(), cap.positions.begin(), cap.positions.end());
              mesh.normals.insert(mesh.normals.end(), cap.normals.begin(), cap.normals.end());
              for (uint32_t i : cap.indices) mesh.indices.push_back(base + i);
            }
          return mesh;
        } else if constexpr (std::is_same_v<T, Cone>) {
          // make_cone: apex at y = 1, base of radius 1 at y = -1; the notes' cone opens upward from its apex.
          const TriMesh unit = unwelded(to_tri_mesh(make_cone(segments, s.capped)));
          return transformed(unit, translate(s.apex.x, s.apex.y + 0.5 * s.height, s.apex.z) *
                                       scale(s.radius, -0.5 * s.height, s.radius));
        } else {  // Disk
          return fan(circle(Vec3(s.center), glm::normalize(Vec3(s.normal)), s.radius, segments));
        }
      },
      shape);
  mesh.uvs.clear();  // the rasterizer evaluates the shape's own texture coordinates at each pixel
  return mesh;
}

namespace {

/// Where the rasterizer puts a light that is not directional: a point light's position, an area light's center.
Vec3 light_center(const Light& light) {
  Vec3 position(light.position);
  if (light.type == LightType::rect) position += 0.5 * Vec3(light.edge_u + light.edge_v);
  return position;
}

/// The shadow map of a light for the casters in [lo, hi] (world space), fitted as the mesh view fits its own
/// (fitted_shadow_map): orthographic for a directional light, else from the light's position (an area light's center).
raster3d::ShadowMap shadow_map(const Light& light, const Vec3& lo, const Vec3& hi, int size) {
  const bool directional = light.type == LightType::directional;
  return fitted_shadow_map(directional ? -Vec3(light.direction) : light_center(light), !directional, lo, hi, size);
}

/// What the fragment shader of one object reads besides the surface uniforms: its material, and for a shape its
/// texture coordinates' source.
struct ObjectShading {
  const Material* material = nullptr;
  /// A shape: its texture coordinates are the ray tracer's, the uv of the shape's own intersection (in object space)
  /// along the interpolated normal from `probe` outside the tessellated surface. Null for a mesh (interpolated uvs).
  const Shape* shape = nullptr;
  float probe = 0;
  Mat4f eye_to_object{1.0f};
  Mat3f normal_to_object{1.0f};  ///< eye-space normals to object space (the transposed model-view)
  Vec3f ambient_light{0.0f};     ///< the scene's C_a in the pass that adds the ambient term, else 0
  Vec3f environment{0.0f};       ///< what a mirror ray sees (the background), in that pass, else 0
  /// In that pass, what a mirror ray sees instead: the other objects around the object's center (a dynamic cube map),
  /// or null.
  const CubeMap* reflection = nullptr;
};

/// The ray tracer's surface terms per pixel: the surface color C_r (the checkerboard of world-space cells, times the
/// texture at the ray tracer's uv), the lighting and shadows of raster3d's surface shader, the ambient term
/// C_r ambient C_a, and the mirror term K_refl environment(R), R = 2 (N.E) N - E in world space: the object's cube map
/// of the others, or the background. The normal faces the viewer, as the ray tracer faces it toward the ray. The alpha
/// is 1 - K_trans (the mean of its channels; with fresnel, after Schlick's term moved weight to K_refl), the part of
/// what lies behind that blending lets through: dst' = color + K_trans dst.
struct SceneFragmentShader {
  const raster3d::SurfaceUniforms* uniforms;
  const ObjectShading* object;

  Vec2f texture_uv(const raster3d::SurfaceVaryings& in) const {
    const ObjectShading& o = *object;
    if (!o.shape) return in.uv;
    Ray probe;
    const Vec3f n = glm::normalize(o.normal_to_object * in.normal);
    probe.origin = Vec3f(o.eye_to_object * Vec4f(in.position, 1.0f)) + o.probe * n;
    probe.dir = -n;
    Hit hit;
    return intersect(*o.shape, probe, hit) ? hit.uv : Vec2f(0.0f);
  }

  bool operator()(const raster3d::SurfaceVaryings& in, const raster3d::SurfaceVaryings& ddx,
                  const raster3d::SurfaceVaryings& ddy, Vec4f& color) const {
    const raster3d::SurfaceUniforms& u = *uniforms;
    const Material& m = *object->material;
    raster3d::SurfaceVaryings v = in;
    const Vec3f e = glm::normalize(Vec3f(u.viewer) - in.position * u.viewer.w);
    const bool front = glm::dot(in.normal, e) >= 0.0f;
    v.normal = glm::normalize(front ? in.normal : -in.normal);
    Vec3f cr = m.diffuse;
    if (m.checker > 0.0f) {
      const Vec3f world(u.eye_to_world * Vec4f(in.position, 1.0f));
      const Vec3f cell = glm::floor(world * (1.0f / m.checker) + 1e-4f);  // the ray tracer's cells and offset
      if ((int64_t(cell.x) + int64_t(cell.y) + int64_t(cell.z)) & 1) cr = m.checker_color;
    }
    if (m.texture) cr *= Vec3f(m.texture->sample(texture_uv(in)));
    v.color = cr;
    Vec3f c;
    raster3d::SurfaceFragmentShader{uniforms}(v, ddx, ddy, c);
    Vec3f k_refl = m.reflection, k_trans = m.transmission;
    if (k_trans != Vec3f(0.0f) && m.fresnel) {
      const float n1 = front ? ior::kVacuum : m.ior, n2 = front ? m.ior : ior::kVacuum;
      const float f = schlick_fresnel(glm::abs(glm::dot(glm::normalize(in.normal), e)), n1, n2);
      k_refl += f * k_trans;
      k_trans *= 1.0f - f;
    }
    Vec3f environment = object->environment;
    if (object->reflection && k_refl != Vec3f(0.0f)) {
      const Vec3f r = Mat3f(u.eye_to_world) * (2 * glm::dot(v.normal, e) * v.normal - e);
      environment = Vec3f(object->reflection->lookup(r));
    }
    c += cr * m.ambient * object->ambient_light + k_refl * environment;
    color = Vec4f(glm::clamp(c, 0.0f, 1.0f), 1.0f - (k_trans.x + k_trans.y + k_trans.z) / 3.0f);
    return true;
  }
};

/// Whether a material lets light through (drawn blended, after the opaque objects).
bool transparent(const Material& m) { return m.transmission != Vec3f(0.0f); }
/// Whether a material reflects what is around it (a mirror, or glass whose Fresnel term reflects).
bool reflective(const Material& m) { return m.reflection != Vec3f(0.0f) || (m.fresnel && transparent(m)); }

/// The scene with each visible area light's surface as an object that glows with the light's color and casts no
/// shadow, as the ray tracer's add_light_surfaces adds them.
Scene with_light_surfaces(const Scene& scene) {
  Scene out = scene;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    if (!light.is_area() || !light.visible) continue;
    std::string name = fmt::format("(area light {})", i);
    while (out.materials.count(name)) name += "'";  // a name no material of the file has
    Material glow;
    glow.diffuse = Vec3f(0.0f);
    glow.emission = light.color;
    out.materials[name] = glow;
    SceneObject surface;
    surface.shape = light_surface(light);
    surface.material = name;
    surface.casts_shadows = false;
    out.objects.push_back(std::move(surface));
  }
  return out;
}

}  // namespace

ImageRGB rasterize_scene(const Scene& described, int width, int height, RasterShadows shadows, int shadow_map_size) {
  const Scene scene = with_light_surfaces(described);
  if (width <= 0 || height <= 0) throw InvalidInput(fmt::format("rasterize: bad image size {}x{}", width, height));
  if (shadows == RasterShadows::map && (shadow_map_size < 1 || shadow_map_size > raster3d::ShadowMap::kMaxSize))
    throw InvalidInput(fmt::format("rasterize: shadow map size {} is outside [1, {}]", shadow_map_size,
                                   raster3d::ShadowMap::kMaxSize));
  // A shadow map per light, refused over the memory budget before any is drawn: 4 bytes a texel, 1.5 times size^2
  // texels where a point light lies among the casters (six faces of size/2).
  const int map_count =
      shadows == RasterShadows::map ? std::min<int>(int(scene.lights.size()), raster3d::kMaxLights) : 0;
  const uint64_t map_side = uint64_t(shadow_map_size);
  if (map_count > 0)
    MemoryBudget::check(saturating_product({uint64_t(map_count), map_side, map_side, 6}),
                        fmt::format("rasterize: {} shadow map{} of {}x{} texels", map_count, map_count == 1 ? "" : "s",
                                    shadow_map_size, shadow_map_size));
  const bool ortho = scene.camera.orthographic;
  // z-fail counting needs the volumes' far caps, at infinity, inside the view: the far plane at infinity. An
  // orthographic projection cannot put it there (a point at infinity has w = 0 after it), and z-pass counting goes
  // wrong wherever the near plane, as wide as the scene, cuts a volume open.
  if (shadows == RasterShadows::volumes && ortho)
    throw InvalidInput(
        "rasterize: shadow volumes need a perspective camera (an orthographic projection cannot keep their far caps "
        "at infinity); use shadow maps");
  const Camera camera = scene.camera.camera(double(width) / height, 0.05, 4000);
  const Mat4 projection = shadows == RasterShadows::volumes
                              ? infinite_perspective(camera.fovy, camera.aspect, camera.near)
                              : camera.projection();
  const Mat4 view = camera.view();

  // The lights in eye space for a view, as glLight places them under the view matrix. The ambient term is the fragment
  // shader's (C_r ambient C_a); the highlights see the eye where it is (a local viewer) as the ray tracer's do, or
  // along the gaze under an orthographic projection.
  const auto lights_seen_by = [&](const Mat4& eye_view, bool local_viewer) {
    raster3d::Lighting lighting;
    lighting.model_ambient = Vec3f(0.0f);
    lighting.local_viewer = local_viewer;
    lighting.color_material = true;
    lighting.light_count = std::min<int>(int(scene.lights.size()), raster3d::kMaxLights);
    for (int i = 0; i < lighting.light_count; ++i) {
      const Light& l = scene.lights[size_t(i)];
      raster3d::Light& gl = lighting.lights[size_t(i)];
      gl.diffuse = gl.specular = l.color;
      gl.position = l.type == LightType::directional
                        ? Vec4f(Vec3f(Mat3(eye_view) * -glm::normalize(Vec3(l.direction))), 0.0f)
                        : Vec4f(Vec3f(eye_view * glm::dvec4(light_center(l), 1.0)), 1.0f);
    }
    return lighting;
  };
  const raster3d::Lighting lighting = lights_seen_by(view, !ortho);

  // Every object tessellated once; for a shadow map, the casters' world box (planes are infinite: they only receive).
  const auto casts = [](const SceneObject& o) {
    return o.casts_shadows && !(o.shape && std::holds_alternative<Plane>(*o.shape));
  };
  const auto material = [&](const SceneObject& o) -> const Material& { return scene.materials.at(o.material); };
  std::vector<raster3d::VertexArrays> arrays;
  std::vector<ObjectShading> shading;
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const SceneObject& o : scene.objects) {
    // A mesh without normals shows its facets, as the ray tracer shades it with the geometric normal; a textured mesh
    // without uvs gets the ray tracer's, each triangle's barycentrics.
    const bool barycentric = o.mesh && o.mesh->uvs.empty() && material(o).texture;
    arrays.push_back(raster3d::VertexArrays::from_mesh(o.shape ? tessellate(*o.shape)
                                                       : o.mesh->normals.empty() || barycentric
                                                           ? unwelded(*o.mesh, o.mesh->normals.empty())
                                                           : *o.mesh));
    ObjectShading s;
    s.material = &material(o);
    if (o.shape) {
      s.shape = &*o.shape;
      float radius = 0;
      for (const Vec3f& p : arrays.back().positions) radius = std::max(radius, glm::length(p));
      s.probe = 0.01f * radius;  // well beyond the tessellation's chords (0.2% of a radius at 48 segments)
    }
    shading.push_back(s);
    if (!casts(o) || shadows != RasterShadows::map) continue;
    for (const Vec3f& p : arrays.back().positions) {
      const Vec3 w = transform_point(o.transform, Vec3(p));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
  }
  // The notes' pass 1, for every light.
  std::vector<raster3d::ShadowMap> maps;
  if (shadows == RasterShadows::map && lo.x <= hi.x)
    for (int i = 0; i < lighting.light_count; ++i) {
      maps.push_back(shadow_map(scene.lights[size_t(i)], lo, hi, shadow_map_size));
      for (size_t k = 0; k < scene.objects.size(); ++k)
        if (casts(scene.objects[k])) maps.back().draw(arrays[k], scene.objects[k].transform);
    }
  std::vector<size_t> opaque, see_through;
  for (size_t k = 0; k < scene.objects.size(); ++k)
    (transparent(material(scene.objects[k])) ? see_through : opaque).push_back(k);

  // Each mirror's surroundings (filled in below): what its reflected rays see.
  std::vector<std::optional<CubeMap>> reflections(scene.objects.size());
  // Draws object k into `target` through (projection, eye_view) under `lights` (the scene's, or one pass's) with its
  // material's terms; the emission, ambient and mirror terms only when `ambient` (a light's pass adds that light
  // alone).
  const auto draw_object = [&](raster3d::Framebuffer& target, const Mat4& projection_k, const Mat4& eye_view, size_t k,
                               const raster3d::RasterState& state, const raster3d::Lighting& lights, bool ambient) {
    const SceneObject& o = scene.objects[k];
    const Material& m = material(o);
    raster3d::Lighting l = lights;
    l.material.specular = m.specular;
    l.material.shininess = m.shininess;
    l.material.emission = ambient ? m.emission : Vec3f(0);
    l.specular_model =
        m.model == SpecularModel::blinn ? raster3d::SpecularModel::blinn : raster3d::SpecularModel::phong;
    if (const auto shader = scene.shaders.find(o.material); shader != scene.shaders.end()) {
      // The material's GLSL program shades the whole surface once, in the pass with the ambient terms.
      if (!ambient) return;
      raster3d::ProgramState p;
      p.model_view = Mat4f(eye_view * o.transform);
      p.projection = Mat4f(projection_k);
      p.lighting = l;
      p.lighting.material.ambient = m.ambient;
      p.lighting.material.diffuse = m.diffuse;
      p.lighting.model_ambient = scene.ambient;
      for (int i = 0; i < l.light_count; ++i) p.light_on[size_t(i)] = true;
      p.color = m.diffuse;
      shader->second->draw_arrays(target, state, p, arrays[k].attributes(), uint32_t(arrays[k].positions.size()),
                                  arrays[k].indices);
      return;
    }
    raster3d::SurfaceUniforms u;
    u.set_camera(projection_k, eye_view, o.transform);
    u.lighting = raster3d::PreparedLighting(l);
    for (size_t i = 0; i < maps.size(); ++i) u.maps.shadows[i] = &maps[i];
    ObjectShading s = shading[k];
    const Mat4 model_view = eye_view * o.transform;
    s.eye_to_object = Mat4f(glm::inverse(model_view));
    s.normal_to_object = Mat3f(glm::transpose(Mat3(model_view)));
    s.ambient_light = ambient ? scene.ambient : Vec3f(0.0f);
    s.environment = ambient ? scene.image.background : Vec3f(0.0f);
    s.reflection = ambient && reflections[k] ? &*reflections[k] : nullptr;
    const raster3d::SurfaceVertexShader vs{arrays[k].attributes(), nullptr, nullptr, &u};
    raster3d::draw_triangles(target, state, uint32_t(arrays[k].positions.size()), arrays[k].indices, vs,
                             SceneFragmentShader{&u, &s});
  };
  // Transparency by blending (raster3d's sorted transparency): the see-through objects but `skip` after the opaque
  // ones, far to near by their centers and each one's triangles sorted far to near, depth-tested against the opaque
  // ones but not written, each blended over what lies behind it (dst' = color + K_trans dst).
  const auto draw_see_through = [&](raster3d::Framebuffer& target, const Mat4& projection_k, const Mat4& eye_view,
                                    const raster3d::Lighting& lights, size_t skip) {
    const auto depth = [&](size_t k) {
      Vec3 c(0.0);
      for (const Vec3f& p : arrays[k].positions) c += Vec3(p);
      return (eye_view * scene.objects[k].transform * glm::dvec4(c / double(arrays[k].positions.size()), 1.0)).z;
    };
    std::vector<size_t> order;
    for (const size_t k : see_through)
      if (k != skip) order.push_back(k);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return depth(a) < depth(b); });
    raster3d::RasterState blend;
    blend.depth_write = false;
    blend.blend = true;
    blend.blend_function = {raster3d::BlendFactor::one, raster3d::BlendFactor::one_minus_src_alpha};
    for (const size_t k : order) {
      raster3d::sort_back_to_front(arrays[k], eye_view * scene.objects[k].transform);
      draw_object(target, projection_k, eye_view, k, blend, lights, true);
    }
  };
  // The whole scene but object `skip`, shadowed by the maps (if any).
  const auto draw_all = [&](raster3d::Framebuffer& target, const Mat4& projection_k, const Mat4& eye_view,
                            const raster3d::Lighting& lights, size_t skip) {
    for (const size_t k : opaque)
      if (k != skip) draw_object(target, projection_k, eye_view, k, raster3d::RasterState{}, lights, true);
    draw_see_through(target, projection_k, eye_view, lights, skip);
  };

  // Environment mapping of the other objects (the notes' cube mapping: "render scene 6 times, eye at center of
  // cube"): each reflective object sees the rest of the scene, drawn from its center, one bounce deep (the objects in
  // its cube map reflect only the background). A mirror plane's cube map is drawn from the eye's mirror image instead,
  // through which every ray it reflects passes: exact but for the texels (under an orthographic camera the reflected
  // rays are parallel and share no point, so a plane reflects the background there).
  std::vector<std::optional<CubeMap>> surroundings(scene.objects.size());
  // About a texel per pixel where a mirror fills the picture (its visible half shows a face across half the width; a
  // plane's reflection spans about the view's own angles).
  const int reflection_size = std::clamp(std::max(width, height) / 2, 16, 256);
  const int plane_reflection_size = std::clamp(std::max(width, height), 16, 512);
  for (size_t k = 0; k < scene.objects.size(); ++k) {
    const SceneObject& o = scene.objects[k];
    const Plane* plane = o.shape ? std::get_if<Plane>(&*o.shape) : nullptr;
    if (!reflective(material(o)) || (plane && ortho)) continue;
    Vec3 center(0.0);
    if (plane) {
      const Vec3 q = transform_point(o.transform, Vec3(plane->point));
      const Vec3 n = glm::normalize(glm::transpose(glm::inverse(Mat3(o.transform))) * Vec3(plane->normal));
      center = camera.eye - 2 * glm::dot(camera.eye - q, n) * n;
    } else {
      for (const Vec3f& p : arrays[k].positions) center += Vec3(p);
      center = transform_point(o.transform, center / double(arrays[k].positions.size()));
    }
    surroundings[k] = raster3d::render_cube_map(
        center, plane ? plane_reflection_size : reflection_size,
        [&](raster3d::Framebuffer& face, const Mat4& face_projection, const Mat4& face_view) {
          face.clear(scene.image.background);
          draw_all(face, face_projection, face_view, lights_seen_by(face_view, true), k);
        },
        0.01, 4000);
  }
  reflections = std::move(surroundings);
  raster3d::Framebuffer fb(width, height);
  fb.clear(scene.image.background);
  const size_t none = scene.objects.size();
  if (shadows == RasterShadows::map) {
    draw_all(fb, projection, view, lighting, none);
    return fb.color_rgb();
  }
  // Shadow volumes: the casters' volumes for each light, then an ambient pass (ambient, emission, mirror term) and
  // one pass per light adding its own diffuse and specular terms where no volume holds the surface; the see-through
  // objects over that, unshadowed (the volumes count only the opaque surfaces' pixels).
  std::vector<std::vector<raster3d::ShadowVolume>> volumes(size_t(lighting.light_count));
  for (size_t k = 0; k < scene.objects.size(); ++k) {
    if (!casts(scene.objects[k])) continue;
    std::vector<Vec3f> world;
    for (const Vec3f& p : arrays[k].positions)
      world.push_back(Vec3f(transform_point(scene.objects[k].transform, Vec3(p))));
    for (int i = 0; i < lighting.light_count; ++i) {
      const Light& l = scene.lights[size_t(i)];
      const Vec4f light =
          l.type == LightType::directional ? Vec4f(-glm::normalize(l.direction), 0) : Vec4f(Vec3f(light_center(l)), 1);
      volumes[size_t(i)].push_back(raster3d::shadow_volume(world, arrays[k].indices, light));
    }
  }
  raster3d::draw_lights_with_shadow_volumes(fb, volumes, Mat4f(projection * view), raster3d::ShadowCount::zfail,
                                            [&](const raster3d::RasterState& state, int light) {
                                              raster3d::Lighting pass = lighting;
                                              if (light >= 0) {
                                                pass.lights[0] = lighting.lights[size_t(light)];
                                                pass.light_count = 1;
                                              } else {
                                                pass.light_count = 0;
                                              }
                                              for (const size_t k : opaque)
                                                draw_object(fb, projection, view, k, state, pass, light < 0);
                                            });
  draw_see_through(fb, projection, view, lighting, none);
  return fb.color_rgb();
}

}  // namespace tessera
