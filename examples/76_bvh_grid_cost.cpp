// Where the work goes: for every eye ray, the nodes (BVH) or cells (uniform grid) visited plus the triangles tested,
// as a heat map on one shared scale, BVH left and grid right. The scene mixes a dense mesh with a large ground quad
// and a few big triangles, the case the notes warn about ("good for similarly sized objects, bad for very different
// sizes").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "gallery.hpp"
#include "tessera/accel/bvh.hpp"
#include "tessera/accel/grid.hpp"
#include "tessera/accel/shapes.hpp"
#include "tessera/color/colormap.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"

namespace {

using namespace tessera;

/// Nodes or cells visited plus triangles tested for every pixel.
template <class Accel>
std::vector<float> cost_image(const Accel& accel, const std::vector<Triangle>& tris, const EyeRays& eye, int w, int h) {
  std::vector<float> cost(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Ray ray = eye.ray(x, y);
      TraversalStats stats;
      accel.intersect(
          ray,
          [&](int prim, Ray& r) {
            Hit hit;
            if (!intersect(tris[size_t(prim)], r, hit)) return false;
            r.tmax = hit.t;
            return true;
          },
          &stats);
      cost[size_t(y) * size_t(w) + size_t(x)] = float(stats.nodes + stats.prims);
    }
  return cost;
}

}  // namespace

TESSERA_EXAMPLE(ex76_bvh_grid_cost, "76_bvh_grid_cost", "Traversal cost: BVH versus uniform grid") {
  const auto bunny = gallery.data_file("meshes/bunny/bun_zipper_res2.ply", "a torus");
  TriMesh mesh = bunny ? to_tri_mesh(read_mesh(*bunny)) : to_tri_mesh(make_torus(0.08, 0.03, 96, 48));
  std::vector<Triangle> tris;
  AABB box;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle tri{Vec3f(mesh.positions[mesh.indices[3 * t]]), Vec3f(mesh.positions[mesh.indices[3 * t + 1]]),
                       Vec3f(mesh.positions[mesh.indices[3 * t + 2]])};
    tris.push_back(tri);
    box.expand(bounds(tri));
  }
  // A ground quad ten times the mesh's size under it, and two tall slivers beside it.
  const Vec3f c = box.center(), e = box.extent();
  const float g = 5 * std::max(e.x, e.z), y0 = box.lo.y;
  tris.push_back({Vec3f(c.x - g, y0, c.z - g), Vec3f(c.x - g, y0, c.z + g), Vec3f(c.x + g, y0, c.z + g)});
  tris.push_back({Vec3f(c.x - g, y0, c.z - g), Vec3f(c.x + g, y0, c.z + g), Vec3f(c.x + g, y0, c.z - g)});
  for (float side : {-1.0f, 1.0f})
    tris.push_back({Vec3f(c.x + side * 0.8f * e.x, y0, c.z - 3 * e.z),
                    Vec3f(c.x + side * 0.8f * e.x, y0, c.z + 3 * e.z),
                    Vec3f(c.x + side * 0.8f * e.x, y0 + 1.5f * e.y, c.z)});
  std::vector<AABB> boxes;
  for (const Triangle& t : tris) boxes.push_back(bounds(t));
  const Bvh bvh(boxes);
  const UniformGrid grid(boxes);

  const int w = 320, h = 240;
  Camera cam;
  cam.center = Vec3(c);
  cam.eye = cam.center + 2.2 * double(glm::length(e)) * glm::normalize(Vec3(0.3, 0.45, 1));
  cam.fovy = radians(40);
  cam.aspect = double(w) / h;
  const EyeRays eye(cam, w, h);
  const std::vector<float> bvh_cost = cost_image(bvh, tris, eye, w, h);
  const std::vector<float> grid_cost = cost_image(grid, tris, eye, w, h);

  // One scale for both: the 99th percentile of all costs (a few extreme pixels would wash the rest out).
  std::vector<float> all = bvh_cost;
  all.insert(all.end(), grid_cost.begin(), grid_cost.end());
  std::nth_element(all.begin(), all.begin() + long(all.size() * 99 / 100), all.end());
  const float scale = std::max(1.0f, all[all.size() * 99 / 100]);
  auto to_image = [&](const std::vector<float>& cost) {
    ImageRGB img(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) img(x, y) = heat_color(cost[size_t(y) * size_t(w) + size_t(x)] / scale);
    return img;
  };
  auto mean = [](const std::vector<float>& v) {
    double s = 0;
    for (float x : v) s += x;
    return s / double(v.size());
  };
  const glm::ivec3 res = grid.resolution();
  const std::string caption = fmt::format(
      "Nodes/cells visited + triangles tested per eye ray, blue = 0 to red = {:.0f}: BVH (left, "
      "mean {:.1f}) and {}x{}x{} uniform grid (right, mean {:.1f}) over {} triangles.",
      scale, mean(bvh_cost), res.x, res.y, res.z, mean(grid_cost), tris.size());
  gallery.add("76_bvh_grid_cost.png", examples::side_by_side({to_image(bvh_cost), to_image(grid_cost)}),
              bunny ? caption : examples::stand_in_caption("a torus", "the Stanford bunny", caption));
}
