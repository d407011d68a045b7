// Example 26: transparency by blending, the fragment stage's last step (the notes, "GPUs": fragment processors
// "shade, texture, transparency"; OpenGL's glBlendFunc). A translucent surface is blended "over" what lies behind
// it, C = alpha C_src + (1 - alpha) C_dst, so the order of drawing matters: the opaque objects first, then the
// translucent triangles far to near (as the painter's algorithm orders them), tested against the z-buffer but not
// written to it. First panel: the torus drawn in its mesh order with depth writes on, so wherever a near part came
// first the parts behind it are never blended in (dark gaps inside the ring). Second: sorted far to near, depth writes
// off: every layer shows. Third: additive blending (one, one) of three colored spheres, light adding up to white.
#include <cmath>

#include "gallery.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"

namespace {

using namespace tessera;

// A context looking at the origin, lit over the viewer's shoulder, Gouraud shading.
void set_view(raster3d::Context& ctx, const Vec3f& background) {
  ctx.clear(background);
  ctx.perspective(radians(40), 1, 20);
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  ctx.light(0, {.position = Vec4f(glm::normalize(Vec3f(-0.4f, 0.6f, 1.0f)), 0)});
  ctx.look_at({0, 1.2, 4.5}, {0, 0, 0}, {0, 1, 0});
  ctx.shading(raster3d::ShadingModel::gouraud);
}

// An opaque object of `color` under `model`.
void draw_opaque(raster3d::Context& ctx, const TriMesh& mesh, const Mat4& model, const Vec3f& color) {
  ctx.push_matrix();
  ctx.mult_matrix(model);
  ctx.material(raster3d::Material::plastic(color, 32, 0.4f));
  ctx.draw(mesh);
  ctx.pop_matrix();
}

ImageRGB translucent_torus(bool sorted) {
  raster3d::Context ctx(300, 300);
  set_view(ctx, {0.95f, 0.95f, 0.92f});
  const TriMesh sphere = to_tri_mesh(make_uv_sphere(32, 16));
  draw_opaque(ctx, to_tri_mesh(make_grid(8, 8)), translate(0, -1.2, -0.5) * scale(2.5, 1, 2.5), {0.8f, 0.8f, 0.75f});
  draw_opaque(ctx, sphere, translate(-0.8, -0.5, -1.4) * scale(0.7, 0.7, 0.7), {0.85f, 0.25f, 0.2f});
  draw_opaque(ctx, sphere, translate(0.9, -0.6, -0.9) * scale(0.55, 0.55, 0.55), {0.25f, 0.7f, 0.3f});
  const Mat4 model = rotate_x(1.1) * rotate_z(0.3);
  raster3d::VertexArrays torus = raster3d::VertexArrays::from_mesh(to_tri_mesh(make_torus(1.1, 0.35, 48, 24)));
  if (sorted) raster3d::sort_back_to_front(torus, ctx.model_view() * model);
  ctx.mult_matrix(model);
  ctx.material(raster3d::Material::plastic({0.2f, 0.45f, 0.95f}, 32, 0.6f));
  ctx.alpha(0.45f);
  ctx.blend(true);
  ctx.blend_function({raster3d::BlendFactor::src_alpha, raster3d::BlendFactor::one_minus_src_alpha});
  ctx.depth_write(!sorted);
  ctx.draw(torus);
  return ctx.framebuffer().color_rgb();
}

ImageRGB additive_spheres() {
  raster3d::Context ctx(300, 300);
  set_view(ctx, {0, 0, 0});
  ctx.shading(raster3d::ShadingModel::unlit);
  ctx.blend(true);
  ctx.blend_function({raster3d::BlendFactor::one, raster3d::BlendFactor::one});
  ctx.depth_write(false);  // each sphere adds its light whatever lies in front of it
  const TriMesh sphere = to_tri_mesh(make_uv_sphere(32, 16));
  const Vec3f colors[3] = {{0.6f, 0, 0}, {0, 0.6f, 0}, {0, 0, 0.6f}};
  for (int i = 0; i < 3; ++i) {
    const double a = radians(90.0 + 120.0 * i);
    ctx.push_matrix();
    ctx.translate(0.55 * std::cos(a), 0.55 * std::sin(a), 0);
    ctx.color(colors[i]);
    ctx.draw(sphere);  // front and back faces: 2 x 0.6 per sphere where it is seen through
    ctx.pop_matrix();
  }
  return ctx.framebuffer().color_rgb();
}

}  // namespace

TESSERA_EXAMPLE(ex26_transparency, "26_transparency",
                "Transparency by blending: drawing order, and additive blending") {
  gallery.add("26_transparency.png",
              examples::side_by_side({translucent_torus(false), translucent_torus(true), additive_spheres()}),
              "A translucent torus (alpha 0.45, blended over) in front of opaque objects: drawn in mesh order with "
              "depth writes on (the parts behind a nearer part drawn first are lost: dark gaps), and sorted far to "
              "near with depth writes off (every layer shows); three spheres blended additively (one, one).");
}
