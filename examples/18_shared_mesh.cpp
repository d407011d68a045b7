// Example 18: real meshes rendered lit. Keenan Crane's Spot with its texture through a custom shader pair (the
// notes' texture and diffuse programs combined: the vertex shader passes the eye-space normal and the texture
// coordinates, the fragment shader samples the texture and multiplies by ambient + diffuse N.L, plus a Blinn
// highlight), and the Stanford bunny with per-pixel (Phong-interpolated) shading. Both come from the shared data
// (found as Gallery::data_file says); without it, a checker-textured torus and a quad sphere stand in, and the
// caption and stderr say so.
#include <cmath>
#include <filesystem>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace {

using namespace tessera;

struct TexturedVaryings {
  Vec3f normal;
  Vec2f uv;
};

/// Vertex program: clip position, eye-space normal, texture coordinates.
struct TexturedVertexShader {
  raster3d::VertexAttributes attributes;
  Mat4f model_view_projection{1.0f};
  Mat3f normal_matrix{1.0f};

  raster3d::VertexOut<TexturedVaryings> operator()(uint32_t i) const {
    return {model_view_projection * Vec4f(attributes.positions[i], 1.0f),
            {normal_matrix * attributes.normals[i], attributes.uvs[i]}};
  }
};

/// Fragment program: texture color * (ambient + diffuse), plus a white Blinn highlight; light and viewer in eye space.
struct TexturedFragmentShader {
  const Texture2D* texture = nullptr;
  Vec3f to_light{0, 0, 1};  ///< unit, eye space

  bool operator()(const TexturedVaryings& in, Vec3f& color) const {
    const Vec3f n = glm::normalize(in.normal);
    const float diffuse = glm::max(glm::dot(n, to_light), 0.0f);
    const Vec3f h = glm::normalize(to_light + Vec3f(0, 0, 1));
    const float specular = diffuse > 0 ? 0.35f * std::pow(glm::max(glm::dot(n, h), 0.0f), 48.0f) : 0.0f;
    color = glm::clamp(Vec3f(texture->sample(in.uv)) * (0.25f + 0.8f * diffuse) + specular, 0.0f, 1.0f);
    return true;
  }
};

// A checkerboard texture for the fallback torus.
Texture2D checker_texture() {
  ImageRGBA image(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      image(x, y) = (x / 8 + y / 8) % 2 ? Vec4f(0.95f, 0.9f, 0.8f, 1) : Vec4f(0.8f, 0.3f, 0.2f, 1);
  return Texture2D(image);
}

ImageRGB textured(PolyMesh poly, const Texture2D& texture, const Mat4& model) {
  if (poly.normals.empty() && poly.corner_normals.empty()) compute_vertex_normals(poly);
  const raster3d::VertexArrays arrays = raster3d::VertexArrays::from_mesh(to_tri_mesh(poly));
  raster3d::Framebuffer framebuffer(360, 360);
  framebuffer.clear({1, 1, 1});
  const Mat4 model_view = look_at({0, 0.5, 3.4}, {0, 0.05, 0}, {0, 1, 0}) * model;
  TexturedVertexShader vs;
  vs.attributes = arrays.attributes();
  vs.model_view_projection = Mat4f(perspective(radians(38), 1, 1, 10) * model_view);
  vs.normal_matrix = Mat3f(normal_matrix(model_view));
  const TexturedFragmentShader fs{&texture, glm::normalize(Vec3f(-0.5f, 0.7f, 0.8f))};
  raster3d::draw_triangles(framebuffer, raster3d::RasterState{.cull = raster3d::CullMode::back},
                           uint32_t(arrays.positions.size()), arrays.indices, vs, fs);
  return framebuffer.color_rgb();
}

}  // namespace

TESSERA_EXAMPLE(ex18_shared_mesh, "18_shared_mesh", "Real meshes lit: textured Spot and the Stanford bunny") {
  const auto spot = gallery.data_file("meshes/spot/spot_triangulated.obj", "a checker-textured torus for Spot");
  const auto spot_png = gallery.data_file("meshes/spot/spot_texture.png", "a checker-textured torus for Spot");
  const auto bunny = gallery.data_file("meshes/bunny/bun_zipper_res2.ply", "a quad sphere for the bunny");
  const bool have_spot = spot && spot_png;
  const ImageRGB left = have_spot ? textured(read_mesh(*spot), load_texture(*spot_png), rotate_y(radians(145)))
                                  : textured(make_torus(0.72, 0.3, 64, 32), checker_texture(), rotate_x(radians(50)));
  const PolyMesh right_mesh = bunny ? read_mesh(*bunny) : make_quad_sphere(12);
  examples::MeshViewOptions o;
  o.width = o.height = 360;
  o.shading = raster3d::ShadingModel::phong;
  o.material = raster3d::Material::plastic({0.85f, 0.8f, 0.72f}, 30, 0.3f);
  o.light_dir = {-0.3, 0.8, 0.9};
  o.wireframe = false;
  o.camera = Camera{};
  const Bounds3 box = bounding_box(right_mesh);
  const Vec3 mid = 0.5 * (box.lo + box.hi);
  const double radius = 0.5 * glm::length(box.hi - box.lo);
  o.camera->center = mid;
  o.camera->eye =
      mid + Vec3(0.2, 0.25, 1.0) * sphere_fit_distance(radius, o.camera->fovy / 2, 0.8);  // the bunny faces +z
  o.camera->near = 0.2 * radius;
  o.camera->far = 10 * radius;
  gallery.add("18_shared_mesh.png", examples::side_by_side({left, examples::render_mesh(right_mesh, o)}), [&] {
    const std::string caption = std::string(have_spot ? "Keenan Crane's Spot" : "a checker-textured torus") +
                                ", textured and lit by a custom shader pair (texture * (ambient + diffuse) "
                                "+ Blinn highlight), and " +
                                (bunny ? "the Stanford bunny (res2)" : "a quad sphere") + " with Phong interpolation.";
    if (have_spot && bunny) return caption;
    return examples::stand_in_caption(have_spot ? "a quad sphere"
                                      : bunny   ? "a torus"
                                                : "a torus and a quad sphere",
                                      have_spot ? "the bunny"
                                      : bunny   ? "Spot"
                                                : "Spot and the bunny",
                                      caption);
  }());
}
