// Example 15: hidden surfaces by the z-buffer and by the painter's algorithm (the notes, "Hidden vs. Visible
// Surfaces"). The painter sorts the polygons by their average depth and draws them back to front, so nearer ones
// cover farther ones; the z-buffer keeps the nearest depth per pixel. First pair: a sphere pierced by a slanted
// slab of two big triangles, by the painter and by the z-buffer (the true intersection). The slab's two triangles
// have their centroids near the sphere's center, so the painter draws every sphere triangle nearer than that after
// them: the sphere covers the slab even where the slab is in front (examples/tests/gallery_test.cpp checks this
// against a ray cast). Second
// pair: the painter's failure case, three sticks in cyclic overlap (each lies over the next: A over B over C over
// A). All three have the same average depth, so no drawing order is right; the z-buffer shows the cycle.
#include <cmath>

#include "gallery.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"

namespace {

using namespace tessera;

// A stick from a to b, `width` wide in the xy plane (a flat box of two triangles), with its own color.
void add_stick(TriMesh& mesh, const Vec3& a, const Vec3& b, double width, const Vec3& color) {
  const Vec3 along = glm::normalize(b - a);
  const Vec3 side = 0.5 * width * Vec3(-along.y, along.x, 0);
  const auto base = uint32_t(mesh.positions.size());
  for (const Vec3& p : {a - side, b - side, b + side, a + side}) {
    mesh.positions.push_back(p);
    mesh.colors.push_back(color);
  }
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// Three sticks along the sides of a triangle, each one running from high z (near the viewer) at its start down to
// low z at its end, where it passes under the start of the next one: a cycle.
TriMesh cyclic_sticks() {
  const Vec3 colors[3] = {{0.9, 0.3, 0.25}, {0.3, 0.7, 0.35}, {0.25, 0.45, 0.9}};
  TriMesh mesh;
  for (int i = 0; i < 3; ++i) {
    const double a0 = kPi / 2 + 2 * kPi * i / 3, a1 = a0 + 2 * kPi / 3;
    const Vec3 p(0.75 * std::cos(a0), 0.75 * std::sin(a0) - 0.1, 0),
        q(0.75 * std::cos(a1), 0.75 * std::sin(a1) - 0.1, 0);
    const Vec3 d = glm::normalize(q - p);
    add_stick(mesh, p - 0.35 * d + Vec3(0, 0, 0.3), q + 0.35 * d - Vec3(0, 0, 0.3), 0.26, colors[i]);
  }
  return mesh;
}

// A sphere with a slanted slab of two big triangles through it, both colored by their facing of a fixed light.
TriMesh sphere_and_slab() {
  TriMesh sphere = to_tri_mesh(make_uv_sphere(24, 12));
  TriMesh mesh;
  const Vec3 light = glm::normalize(Vec3(-0.4, 0.6, 1));
  const auto shade = [&](const Vec3& n, const Vec3& color) {
    return color * (0.25 + 0.75 * std::max(0.0, glm::dot(n, light)));
  };
  for (size_t i = 0; i < sphere.positions.size(); ++i) {
    mesh.positions.push_back(0.8 * sphere.positions[i]);
    mesh.colors.push_back(shade(sphere.normals[i], {0.95, 0.75, 0.3}));
  }
  mesh.indices = sphere.indices;
  const Mat4 slab_from_grid = rotate_z(0.25) * rotate_x(0.45) * scale(1.4, 1, 0.8);  // the xz grid, tilted
  const TriMesh grid = to_tri_mesh(make_grid(1, 1));
  const auto base = uint32_t(mesh.positions.size());
  const Vec3 slab_normal = glm::normalize(normal_matrix(slab_from_grid) * Vec3(0, 1, 0));
  for (const Vec3& p : grid.positions) {
    mesh.positions.push_back(transform_point(slab_from_grid, p));
    mesh.colors.push_back(shade(slab_normal, {0.35, 0.55, 0.85}));
  }
  for (const uint32_t i : grid.indices) mesh.indices.push_back(base + i);
  return mesh;
}

ImageRGB draw(const TriMesh& mesh, raster3d::HiddenSurface method, const Mat4& model) {
  raster3d::Context ctx(300, 300);
  ctx.clear({1, 1, 1});
  ctx.perspective(radians(34), 1, 10);
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  ctx.look_at({0, 0, 4.5}, {0, 0, 0}, {0, 1, 0});
  ctx.mult_matrix(model);
  ctx.hidden_surface(method);
  ctx.draw(mesh);
  return ctx.framebuffer().color_rgb();
}

}  // namespace

TESSERA_EXAMPLE(ex15_painter, "15_painter", "Z-buffer versus the painter's algorithm, and its cyclic-overlap failure") {
  const TriMesh pierced = sphere_and_slab(), sticks = cyclic_sticks();
  const Mat4 turn = rotate_y(0.35) * rotate_x(-0.2);
  gallery.add("15_painter.png",
              examples::side_by_side({draw(pierced, raster3d::HiddenSurface::painter, turn),
                                      draw(pierced, raster3d::HiddenSurface::zbuffer, turn),
                                      draw(sticks, raster3d::HiddenSurface::painter, Mat4(1.0)),
                                      draw(sticks, raster3d::HiddenSurface::zbuffer, Mat4(1.0))}),
              "A sphere pierced by a slab of two big triangles. Painter's algorithm (first): each triangle is drawn "
              "whole, far to near by its average depth; the slab's two triangles average near the sphere's center, "
              "so the sphere's near triangles come after them and the sphere covers the slab even where the slab is "
              "in front (only rim triangles farther than the slab lie under it: the notches). Z-buffer (second): the "
              "true intersection, the slab's lower half in front of the sphere. Three sticks in cyclic overlap, red "
              "over blue over green over red as the z-buffer shows (fourth): the painter (third) cannot get all "
              "three crossings right; green covers blue at the lower right, and each stick's two triangles, sorted "
              "apart, break along its diagonal.");
}
