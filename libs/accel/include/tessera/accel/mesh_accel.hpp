#pragma once
// Ray casting of a triangle mesh: a Bvh over its triangles with the triangle data precomputed and stored in leaf order.
#include <vector>

#include "tessera/accel/bvh.hpp"
#include "tessera/accel/shapes.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// A triangle mesh ready for ray casting (a float copy of its geometry; the TriMesh need not outlive it).
class MeshAccel {
 public:
  MeshAccel() = default;
  /// Builds the BVH (parallel, deterministic). Throws InvalidInput for an index out of range or a non-finite vertex.
  explicit MeshAccel(const TriMesh& mesh, const BvhSettings& settings = {});

  /// Nearest hit with t in [ray.tmin, ray.tmax]; on a hit shrinks ray.tmax to it and fills hit: t, point, the unit
  /// geometric normal (b - a) x (c - a) of the triangle, prim = triangle index, uv = barycentrics (b1, b2) of
  /// vertices 1 and 2 of the triangle. stats (optional) counts nodes visited and triangles tested.
  bool intersect(Ray& ray, Hit& hit, TraversalStats* stats = nullptr) const;
  /// Any hit with t in [ray.tmin, ray.tmax] (shadow rays).
  bool occluded(const Ray& ray) const;

  const Bvh& bvh() const { return bvh_; }
  size_t triangle_count() const { return tris_.size(); }

 private:
  /// One triangle in leaf order: vertex 0, the edges to vertices 1 and 2, and its index in the mesh.
  struct PackedTriangle {
    Vec3f v0, e1, e2;
    int index;
  };
  Bvh bvh_;
  RawVector<PackedTriangle> tris_;  // uninitialized growth on huge pages: written in full by the constructor
};

/// The smooth normal at a mesh hit: the vertex normals interpolated by the barycentrics (hit.prim, hit.uv as MeshAccel
/// fills them) and normalized, or hit.normal when the mesh has no per-vertex normals.
Vec3f shading_normal(const TriMesh& mesh, const Hit& hit);

}  // namespace tessera
