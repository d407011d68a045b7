// The mesh view: the polygons become triangles with their own corners (so that a face keeps its color and, when
// flat, its normal), drawn twice by raster3d — front faces, then back faces with flipped normals and darker colors
// (OpenGL's two-sided lighting done with two culled passes) — then the polygon edges as lines pulled slightly toward
// the eye, all at `samples` x `samples` resolution and box-filtered down.
#include "mesh_view.hpp"

#include <algorithm>
#include <cmath>

#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"

namespace tessera::examples {
namespace {

constexpr float kBackShade = 0.55f;      // back faces are this much darker
constexpr double kWireDepthBias = 1e-3;  // edges win over the surface they lie on (normalized device depth)

/// A camera looking at the mesh's bounding sphere from direction (1, 0.8, 1.6), the sphere filling the view.
Camera frame_mesh(const PolyMesh& mesh) {
  const Bounds3 box = bounding_box(mesh);
  const Vec3 center = 0.5 * (box.lo + box.hi);
  double radius = 0;
  for (const Vec3& p : mesh.positions) radius = std::max(radius, glm::distance(p, center));
  return frame_sphere(Camera{}, center, std::max(radius, 1e-9), Vec3(1, 0.8, 1.6), 1.08);
}

/// Front and back passes: every fan triangle with its own three corners.
struct Surfaces {
  raster3d::VertexArrays front, back;
};

Surfaces triangles(const PolyMesh& mesh, const MeshViewOptions& o) {
  const bool flat = o.shading == raster3d::ShadingModel::flat;
  const std::vector<Vec3> vertex_normals_ = flat || !mesh.corner_normals.empty() ? std::vector<Vec3>{}
                                            : mesh.normals.empty()               ? vertex_normals(mesh)
                                                                                 : mesh.normals;
  Surfaces s;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    const Vec3f color = f < o.face_colors.size() ? o.face_colors[f] : o.color;
    const Vec3 face_n = face_normal(mesh, f);
    const auto normal = [&](size_t corner) {
      if (flat) return Vec3f(face_n);
      if (!mesh.corner_normals.empty()) return Vec3f(mesh.corner_normals[mesh.face_offsets[f] + corner]);
      return Vec3f(vertex_normals_[face[corner]]);
    };
    for (size_t i = 1; i + 1 < face.size(); ++i)
      for (const size_t corner : {size_t(0), i, i + 1}) {
        const Vec3f p(mesh.positions[face[corner]]), n = normal(corner);
        for (raster3d::VertexArrays* a : {&s.front, &s.back}) {
          a->indices.push_back(uint32_t(a->positions.size()));
          a->positions.push_back(p);
        }
        s.front.normals.push_back(n);
        s.front.colors.push_back(color);
        s.back.normals.push_back(-n);
        s.back.colors.push_back(kBackShade * color);
      }
  }
  return s;
}

}  // namespace

ImageRGB downsample(const ImageRGB& image, int s) {
  if (s == 1) return image;
  ImageRGB out(image.width() / s, image.height() / s);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      Vec3f sum(0.0f);
      for (int dy = 0; dy < s; ++dy)
        for (int dx = 0; dx < s; ++dx) sum += image(x * s + dx, y * s + dy);
      out(x, y) = sum / float(s * s);
    }
  return out;
}

PolyMesh with_face_normals(PolyMesh mesh) {
  mesh.corner_normals.clear();
  for (size_t f = 0; f < mesh.face_count(); ++f)
    mesh.corner_normals.insert(mesh.corner_normals.end(), mesh.face(f).size(), face_normal(mesh, f));
  return mesh;
}

raster3d::Lighting surface_lighting(const Vec3& to_light, const Mat4& view, float ambient, float specular) {
  raster3d::Lighting l;
  l.material = raster3d::Material::plastic(Vec3f(1), 24, specular);
  l.color_material = true;
  l.model_ambient = Vec3f(ambient);
  l.lights[0].position = Vec4f(Vec3f(glm::normalize(Mat3(view) * to_light)), 0);
  return l;
}

ImageRGB render_mesh(const PolyMesh& mesh, const MeshViewOptions& o) {
  if (mesh.face_count() == 0) return ImageRGB(o.width, o.height, o.background);  // e.g. marching-cubes case 0
  Camera camera = o.camera ? *o.camera : frame_mesh(mesh);
  camera.aspect = double(o.width) / o.height;
  const int s = std::max(1, o.samples), width = o.width * s, height = o.height * s;
  const Surfaces surfaces = triangles(mesh, o);

  raster3d::Context ctx(width, height);
  ctx.clear(o.background);
  ctx.matrix_mode(raster3d::MatrixMode::projection);
  ctx.load_matrix(camera.projection());
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  ctx.load_matrix(camera.view());
  ctx.light(0, {.position = Vec4f(Vec3f(glm::normalize(o.light_dir)), 0.0f), .diffuse = Vec3f(0.8f)});
  ctx.shading(o.shading);
  ctx.specular_model(o.specular);
  // Without a material the per-face colors are the surface (GL_COLOR_MATERIAL); with one, its colors are.
  raster3d::Material material = o.material.value_or(raster3d::Material::plastic(o.color, 24, 0.15f));
  ctx.color_material(!o.material);
  ctx.material(material);
  ctx.cull(raster3d::CullMode::back);
  ctx.draw(surfaces.front);
  material.ambient *= kBackShade;
  material.diffuse *= kBackShade;
  ctx.material(material);
  ctx.cull(raster3d::CullMode::front);
  ctx.draw(surfaces.back);

  if (o.wireframe) {
    // Lines are 1 pixel wide at the supersampled size: drawn at s x s one-pixel offsets they come out 1 pixel wide.
    ctx.cull(raster3d::CullMode::none);
    ctx.shading(raster3d::ShadingModel::unlit);
    ctx.color(o.wire_color);
    ctx.matrix_mode(raster3d::MatrixMode::projection);
    for (int dy = 0; dy < s; ++dy)
      for (int dx = 0; dx < s; ++dx) {
        ctx.load_matrix(translate(2.0 * dx / width, 2.0 * dy / height, -kWireDepthBias) * camera.projection());
        ctx.begin(raster3d::Primitive::lines);
        for (size_t f = 0; f < mesh.face_count(); ++f) {
          const auto face = mesh.face(f);
          for (size_t i = 0; i < face.size(); ++i)
            for (const uint32_t v : {face[i], face[(i + 1) % face.size()]})
              ctx.vertex(mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z);
        }
        ctx.end();
      }
  }
  return downsample(ctx.framebuffer().color_rgb(), s);
}

std::vector<SceneObject> shadow_scene() {
  const auto arrays = [](const PolyMesh& mesh) { return raster3d::VertexArrays::from_mesh(to_tri_mesh(mesh)); };
  return {
      {arrays(make_grid(1, 1)), scale(3, 1, 3), {0.85f, 0.85f, 0.8f}},
      {arrays(make_uv_sphere(48, 24)), translate(-0.9, 0.6, 0.4) * scale(0.6, 0.6, 0.6), {0.8f, 0.3f, 0.25f}},
      {arrays(make_torus(0.55, 0.18, 64, 24)), translate(0.9, 0.75, -0.2) * rotate_x(radians(75)), {0.3f, 0.5f, 0.8f}},
      {arrays(with_face_normals(make_box())),
       translate(0.1, 0.5, -1.3) * rotate_y(radians(30)) * scale(0.4, 0.5, 0.4),
       {0.9f, 0.75f, 0.3f}}};
}

std::vector<raster3d::ShadowVolume> caster_volumes(const std::vector<SceneObject>& objects, const Vec4f& light) {
  std::vector<raster3d::ShadowVolume> out;
  for (size_t k = 1; k < objects.size(); ++k) {
    std::vector<Vec3f> world;
    for (const Vec3f& p : objects[k].arrays.positions)
      world.push_back(Vec3f(transform_point(objects[k].model, Vec3(p))));
    out.push_back(raster3d::shadow_volume(world, objects[k].arrays.indices, light));
  }
  return out;
}

}  // namespace tessera::examples
