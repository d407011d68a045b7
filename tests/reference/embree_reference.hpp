#pragma once
// Embree 3 as the reference ray caster of the accel tests and benchmark: one triangle mesh, rtcIntersect1 per ray
// (or rtcIntersect1M for a stream of rays).
#include <memory>
#include <span>

#include "tessera/math/ray.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera::reference {

/// A triangle mesh in an Embree scene (default flags, medium-quality build).
class EmbreeMesh {
 public:
  /// Copies the mesh (as float) and builds Embree's BVH; `threads` sizes Embree's thread pool (0 = its default).
  explicit EmbreeMesh(const TriMesh& mesh, int threads = 0);
  ~EmbreeMesh();
  EmbreeMesh(const EmbreeMesh&) = delete;
  EmbreeMesh& operator=(const EmbreeMesh&) = delete;

  /// Nearest hit with t in [ray.tmin, ray.tmax]: returns the triangle index and sets t, or returns -1.
  int intersect(const Ray& ray, float& t) const;
  /// The same for a stream of rays through Embree's stream API (rtcIntersect1M): prims[i] and t[i] for rays[i].
  void intersect(std::span<const Ray> rays, std::span<int> prims, std::span<float> t) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera::reference
