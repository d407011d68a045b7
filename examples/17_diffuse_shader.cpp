// Example 17: the notes' diffuse shader pair as C++ shaders. The vertex program passes the eye-space normal
// (NormalMatrix * normal) and the vector from the vertex to the light (light position - ModelView * vertex); the
// fragment program normalizes both and writes clamp(dot(n, l), 0, 1) * red. Both vectors are interpolated, so the
// diffuse term is evaluated per pixel: a point light close to the surface gives a bright spot that no per-vertex
// scheme could place between vertices. Left: a light far to the upper left; right: a point light just above the
// front of the ring.
#include "gallery.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace {

using namespace tessera;

ImageRGB diffuse(const raster3d::VertexArrays& torus, const Vec3& light_world) {
  raster3d::Framebuffer framebuffer(320, 320);
  framebuffer.clear({0.05f, 0.05f, 0.08f});
  const Mat4 view = look_at({0, 2.2, 3.2}, {0, 0, 0}, {0, 1, 0});
  raster3d::DiffuseVertexShader vs;
  vs.attributes = torus.attributes();
  vs.model_view = Mat4f(view);
  vs.model_view_projection = Mat4f(perspective(radians(40), 1, 1, 10) * view);
  vs.normal_matrix = Mat3f(normal_matrix(view));
  vs.light_position = Vec3f(transform_point(view, light_world));  // gl_LightSource[0].position is in eye space
  raster3d::draw_triangles(framebuffer, raster3d::RasterState{}, uint32_t(torus.positions.size()), torus.indices, vs,
                           raster3d::DiffuseFragmentShader{});
  return framebuffer.color_rgb();
}

}  // namespace

TESSERA_EXAMPLE(ex17_diffuse_shader, "17_diffuse_shader", "The notes' diffuse shader (vertex + fragment program)") {
  const raster3d::VertexArrays torus = raster3d::VertexArrays::from_mesh(to_tri_mesh(make_torus(1.0, 0.4, 48, 24)));
  gallery.add("17_diffuse_shader.png",
              examples::side_by_side({diffuse(torus, {-6, 6, 2}), diffuse(torus, {0.6, 0.75, 0.9})}),
              "The notes' diffuse vertex and fragment programs on a torus: red * clamp(N.L, 0, 1) per pixel, with a "
              "distant light (left) and a point light just above the front of the ring (right).");
}
