// A scene through the rasterizer: shapes tessellated, materials and lights in OpenGL's terms.
#include "tessera/scene/raster.hpp"

#include <algorithm>
#include <limits>

#include "tessera/core/error.hpp"
#include "tessera/math/frame.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/shadow_map.hpp"
#include "tessera/raster3d/shadow_volume.hpp"
#include "tessera/raster3d/surface_shader.hpp"

namespace tessera {
namespace {

/// Every triangle with its own three vertices and its face normal (sharp edges on flat-faced shapes).
TriMesh faceted(const TriMesh& mesh) {
  TriMesh out;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* v = &mesh.indices[3 * t];
    const Vec3 a = mesh.positions[v[0]], b = mesh.positions[v[1]], c = mesh.positions[v[2]];
    const Vec3 cross = glm::cross(b - a, c - a);
    const Vec3 n = glm::length(cross) > 0 ? glm::normalize(cross) : Vec3(0, 1, 0);
    for (int k = 0; k < 3; ++k) {
      out.indices.push_back(uint32_t(out.positions.size()));
      out.positions.push_back(mesh.positions[v[k]]);
      out.normals.push_back(n);
    }
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
  return faceted(to_tri_mesh(poly));
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
  return std::visit(
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
          return faceted(to_tri_mesh(poly));
        } else if constexpr (std::is_same_v<T, Box>) {
          const Vec3 lo(s.lo), hi(s.hi), mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
          return faceted(
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
          const TriMesh unit = faceted(to_tri_mesh(make_cone(segments, s.capped)));
          return transformed(unit, translate(s.apex.x, s.apex.y + 0.5 * s.height, s.apex.z) *
                                       scale(s.radius, -0.5 * s.height, s.radius));
        } else {  // Disk
          return fan(circle(Vec3(s.center), glm::normalize(Vec3(s.normal)), s.radius, segments));
        }
      },
      shape);
}

namespace {

/// Where the rasterizer puts a light that is not directional: a point light's position, an area light's center.
Vec3 light_center(const Light& light) {
  Vec3 position(light.position);
  if (light.type == LightType::rect) position += 0.5 * Vec3(light.edge_u + light.edge_v);
  return position;
}

/// The shadow map of a light for the casters in [lo, hi] (world space): orthographic for a directional light, else
/// from the light's position (an area light's center): one perspective view, or six around a light among the casters.
raster3d::ShadowMap shadow_map(const Light& light, const Vec3& lo, const Vec3& hi, int size) {
  if (light.type == LightType::directional)
    return raster3d::ShadowMap(size, raster3d::ShadowMap::directional(-Vec3(light.direction), lo, hi));
  return raster3d::ShadowMap::point(size, light_center(light), lo, hi);
}

}  // namespace

ImageRGB rasterize_scene(const Scene& scene, int width, int height, RasterShadows shadows, int shadow_map_size) {
  if (width <= 0 || height <= 0) throw InvalidInput(fmt::format("rasterize: bad image size {}x{}", width, height));
  if (shadows == RasterShadows::map && (shadow_map_size < 1 || shadow_map_size > raster3d::ShadowMap::kMaxSize))
    throw InvalidInput(fmt::format("rasterize: shadow map size {} is outside [1, {}]", shadow_map_size,
                                   raster3d::ShadowMap::kMaxSize));
  const double aspect = double(width) / height, fovy = radians(scene.camera.fovy);
  // z-fail counting needs the volumes' far caps, at infinity, inside the view: the far plane at infinity.
  const Mat4 projection = shadows == RasterShadows::volumes ? infinite_perspective(fovy, aspect, 0.05)
                                                            : perspective(fovy, aspect, 0.05, 4000);
  const Mat4 view = look_at(scene.camera.eye, scene.camera.center, scene.camera.up);
  const Mat3 view_linear(view);

  // The lights in eye space, as glLight places them under the view matrix.
  raster3d::Lighting lighting;
  lighting.model_ambient = Vec3f(scene.ambient);
  lighting.light_count = std::min<int>(int(scene.lights.size()), raster3d::kMaxLights);
  for (int i = 0; i < lighting.light_count; ++i) {
    const Light& l = scene.lights[size_t(i)];
    raster3d::Light& gl = lighting.lights[size_t(i)];
    gl.diffuse = gl.specular = l.color;
    gl.position = l.type == LightType::directional
                      ? Vec4f(Vec3f(view_linear * -glm::normalize(Vec3(l.direction))), 0.0f)
                      : Vec4f(Vec3f(view * glm::dvec4(light_center(l), 1.0)), 1.0f);
  }

  // Every object tessellated once; for a shadow map, the casters' world box (planes are infinite: they only receive).
  const auto casts = [](const SceneObject& o) {
    return o.casts_shadows && !(o.shape && std::holds_alternative<Plane>(*o.shape));
  };
  std::vector<raster3d::VertexArrays> arrays;
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const SceneObject& o : scene.objects) {
    // A mesh without normals shows its facets, as the ray tracer shades it with the geometric normal.
    arrays.push_back(raster3d::VertexArrays::from_mesh(o.shape                ? tessellate(*o.shape)
                                                       : o.mesh->normals.empty() ? faceted(*o.mesh)
                                                                                 : *o.mesh));
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

  raster3d::Framebuffer fb(width, height);
  fb.clear(scene.image.background);
  // Draws every object under `lights` (the scene's, or one pass's) with the materials' terms; the emission only when
  // `emission` (a light's pass adds that light alone).
  const auto draw_objects = [&](const raster3d::RasterState& state, const raster3d::Lighting& lights, bool emission) {
    for (size_t k = 0; k < scene.objects.size(); ++k) {
      const SceneObject& o = scene.objects[k];
      const Material& m = scene.materials.at(o.material);
      raster3d::Lighting l = lights;
      l.material.diffuse = m.diffuse;
      l.material.ambient = m.diffuse * m.ambient;
      l.material.specular = m.specular;
      l.material.shininess = m.shininess;
      l.material.emission = emission ? m.emission : Vec3f(0);
      l.specular_model =
          m.model == SpecularModel::blinn ? raster3d::SpecularModel::blinn : raster3d::SpecularModel::phong;
      raster3d::SurfaceUniforms u;
      u.set_camera(projection, view, o.transform);
      u.lighting = raster3d::PreparedLighting(l);
      for (size_t i = 0; i < maps.size(); ++i) u.maps.shadows[i] = &maps[i];
      raster3d::draw_surface(fb, state, arrays[k], u);
    }
  };
  if (shadows == RasterShadows::map) {
    draw_objects(raster3d::RasterState{}, lighting, true);
    return fb.color_rgb();
  }
  // Shadow volumes: the casters' volumes for each light, then an ambient pass (ambient and emission) and one pass per
  // light adding its own diffuse and specular terms where no volume holds the surface.
  std::vector<std::vector<raster3d::ShadowVolume>> volumes(size_t(lighting.light_count));
  for (size_t k = 0; k < scene.objects.size(); ++k) {
    if (!casts(scene.objects[k])) continue;
    std::vector<Vec3f> world;
    for (const Vec3f& p : arrays[k].positions)
      world.push_back(Vec3f(transform_point(scene.objects[k].transform, Vec3(p))));
    for (int i = 0; i < lighting.light_count; ++i) {
      const Light& l = scene.lights[size_t(i)];
      const Vec4f light = l.type == LightType::directional ? Vec4f(-glm::normalize(l.direction), 0)
                                                           : Vec4f(Vec3f(light_center(l)), 1);
      volumes[size_t(i)].push_back(raster3d::shadow_volume(world, arrays[k].indices, light));
    }
  }
  raster3d::draw_lights_with_shadow_volumes(
      fb, volumes, Mat4f(projection * view), raster3d::ShadowCount::zfail,
      [&](const raster3d::RasterState& state, int light) {
        raster3d::Lighting pass = lighting;
        if (light < 0) {
          pass.light_count = 0;
        } else {
          pass.lights[0] = lighting.lights[size_t(light)];
          pass.light_count = 1;
          pass.model_ambient = Vec3f(0);
        }
        draw_objects(state, pass, light < 0);
      });
  return fb.color_rgb();
}

}  // namespace tessera
