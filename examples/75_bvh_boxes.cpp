// The notes' bounding hierarchy made visible: the boxes of a binned-SAH BVH over the Stanford bunny (a torus when the
// shared data is absent), drawn as wireframes over the ray-cast mesh and colored by depth, three levels per panel.
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "gallery.hpp"
#include "tessera/accel/mesh_accel.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"

namespace {

using namespace tessera;

/// A fully saturated hue for t in [0, 1) (red, yellow, green, cyan, blue, magenta).
Vec3f hue(float t) {
  const float h = 6 * (t - std::floor(t));
  return glm::clamp(Vec3f(std::abs(h - 3) - 1, 2 - std::abs(h - 2), 2 - std::abs(h - 4)), 0.0f, 1.0f);
}

/// Draws the segment a-b (pixel coordinates) by sampling it once per pixel step.
void draw_line(ImageRGB& img, Vec2f a, Vec2f b, const Vec3f& color) {
  const int steps = int(std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y)))) + 1;
  for (int s = 0; s <= steps; ++s) {
    const Vec2f p = a + (b - a) * (float(s) / float(steps));
    const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
    if (img.contains(x, y)) img(x, y) = color;
  }
}

/// The 12 edges of a box projected through view-projection vp into a w x h image.
void draw_box(ImageRGB& img, const Mat4& vp, const AABB& box, const Vec3f& color) {
  Vec2f corner[8];
  for (int i = 0; i < 8; ++i) {
    const Vec4 p(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z, 1.0);
    const Vec4 clip = vp * p;
    corner[i] =
        Vec2f(float((clip.x / clip.w + 1) * 0.5 * img.width()), float((1 - clip.y / clip.w) * 0.5 * img.height()));
  }
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) draw_line(img, corner[i], corner[i | bit], color);
}

}  // namespace

TESSERA_EXAMPLE(ex75_bvh_boxes, "75_bvh_boxes", "A bounding volume hierarchy, boxes colored by depth") {
  const auto bunny = gallery.data_file("meshes/bunny/bun_zipper_res2.ply", "a torus");
  const TriMesh mesh = bunny ? to_tri_mesh(read_mesh(*bunny)) : to_tri_mesh(make_torus(1.0, 0.35, 96, 48));
  const MeshAccel accel(mesh);
  const AABB root = accel.bvh().bounds();

  const int size = 320;
  Camera cam;
  cam.center = Vec3(root.center());
  cam.eye = cam.center + 1.9 * double(glm::length(root.extent())) * glm::normalize(Vec3(0.5, 0.35, 1));
  cam.fovy = radians(35);
  const EyeRays eye(cam, size, size);
  const Mat4 vp = cam.projection() * cam.view();

  // The mesh, dimmed, by headlight ray casting.
  ImageRGB base(size, size, Vec3f(0.05f));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      Ray ray = eye.ray(x, y);
      Hit hit;
      if (accel.intersect(ray, hit))
        base(x, y) = Vec3f(0.35f) * (0.2f + 0.8f * std::abs(glm::dot(hit.normal, ray.dir)));
    }

  // Node depths by walking the flattened tree (the first child follows its parent).
  const auto nodes = accel.bvh().nodes();
  std::vector<int> depth(nodes.size(), 0);
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].count == 0) depth[i + 1] = depth[size_t(nodes[i].first)] = depth[i] + 1;

  std::vector<ImageRGB> panels;
  for (int first_level : {0, 3, 6}) {
    ImageRGB panel = base;
    // Deeper boxes first so that the shallower ones (drawn last) stay visible where edges coincide.
    for (int level = first_level + 2; level >= first_level; --level)
      for (size_t i = 0; i < nodes.size(); ++i)
        if (depth[i] == level) draw_box(panel, vp, nodes[i].box, hue(float(level) / 9.0f));
    panels.push_back(panel);
  }
  const std::string caption = "Binned-SAH BVH over the " + std::string(bunny ? "bunny's " : "torus's ") +
                              std::to_string(mesh.triangle_count()) + " triangles (" + std::to_string(nodes.size()) +
                              " nodes, depth " + std::to_string(accel.bvh().depth()) +
                              "): levels 0-2, 3-5 and 6-8, hue by depth (red = root).";
  gallery.add("75_bvh_boxes.png", examples::side_by_side(panels),
              bunny ? caption : examples::stand_in_caption("a torus", "the Stanford bunny", caption));
}
