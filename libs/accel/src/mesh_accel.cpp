// Ray casting of triangle meshes over a Bvh, with the triangles stored in leaf order.
#include "tessera/accel/mesh_accel.hpp"

#include <string>

#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"

namespace tessera {

MeshAccel::MeshAccel(const TriMesh& mesh, const BvhSettings& settings) {
  const size_t nv = mesh.positions.size(), nt = mesh.triangle_count();
  // Fresh arrays of tens of megabytes for large meshes: uninitialized and on huge pages (page faults dominated).
  RawVector<Vec3f> p(nv);
  for (size_t i = 0; i < nv; ++i) {
    p[i] = Vec3f(mesh.positions[i]);
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
      throw InvalidInput("MeshAccel: vertex " + std::to_string(i) + " is not finite");
  }
  RawVector<AABB> boxes(nt);
  for (size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + size_t(k)];
      if (v >= nv)
        throw InvalidInput("MeshAccel: triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) + " of " +
                           std::to_string(nv));
      boxes[t].expand(p[v]);
    }
  }
  bvh_ = Bvh(boxes, settings);
  const auto order = bvh_.prim_indices();
  tris_.resize(order.size());
  for (size_t i = 0; i < order.size(); ++i) {
    const size_t t = size_t(order[i]);
    const Vec3f a = p[mesh.indices[3 * t]], b = p[mesh.indices[3 * t + 1]], c = p[mesh.indices[3 * t + 2]];
    tris_[i] = PackedTriangle{a, b - a, c - a, int(t)};
  }
}

namespace {

/// Moller-Trumbore on a packed triangle: on a hit inside (tmin, ray.tmax) returns true with t and barycentrics.
template <class Tri>
inline bool hit_triangle(const Tri& tri, const Ray& ray, float& t, float& b1, float& b2) {
  const Vec3f p = glm::cross(ray.dir, tri.e2);
  const float det = glm::dot(tri.e1, p);
  if (det == 0) return false;
  const float inv = 1.0f / det;
  const Vec3f tv = ray.origin - tri.v0;
  b1 = glm::dot(tv, p) * inv;
  if (b1 < 0 || b1 > 1) return false;
  const Vec3f q = glm::cross(tv, tri.e1);
  b2 = glm::dot(ray.dir, q) * inv;
  if (b2 < 0 || b1 + b2 > 1) return false;
  t = glm::dot(tri.e2, q) * inv;
  return t >= ray.tmin && t <= ray.tmax;
}

}  // namespace

bool MeshAccel::intersect(Ray& ray, Hit& hit, TraversalStats* stats) const {
  int best = -1;
  float best_b1 = 0, best_b2 = 0;
  bvh_.traverse_leaves<false>(
      ray,
      [&](int first, int count, Ray& r) {
        bool any = false;
        for (int i = first; i < first + count; ++i) {
          float t, b1, b2;
          if (hit_triangle(tris_[size_t(i)], r, t, b1, b2)) {
            r.tmax = t;
            best = i;
            best_b1 = b1;
            best_b2 = b2;
            any = true;
          }
        }
        return any;
      },
      stats);
  if (best < 0) return false;
  const PackedTriangle& tri = tris_[size_t(best)];
  hit.t = ray.tmax;
  hit.point = ray.at(ray.tmax);
  hit.normal = glm::normalize(glm::cross(tri.e1, tri.e2));
  hit.uv = Vec2f(best_b1, best_b2);
  hit.prim = tri.index;
  return true;
}

bool MeshAccel::occluded(const Ray& ray) const {
  Ray r = ray;
  return bvh_.traverse_leaves<true>(
      r,
      [&](int first, int count, Ray& rr) {
        for (int i = first; i < first + count; ++i) {
          float t, b1, b2;
          if (hit_triangle(tris_[size_t(i)], rr, t, b1, b2)) return true;
        }
        return false;
      },
      nullptr);
}

Vec3f shading_normal(const TriMesh& mesh, const Hit& hit) {
  if (mesh.normals.size() != mesh.positions.size() || hit.prim < 0) return hit.normal;
  const size_t t = size_t(hit.prim);
  const Vec3 n = (1.0 - hit.uv.x - hit.uv.y) * mesh.normals[mesh.indices[3 * t]] +
                 double(hit.uv.x) * mesh.normals[mesh.indices[3 * t + 1]] +
                 double(hit.uv.y) * mesh.normals[mesh.indices[3 * t + 2]];
  const double len = glm::length(n);
  return len > 0 ? Vec3f(n / len) : hit.normal;
}

}  // namespace tessera
