#pragma once
// Rays r(t) = o + t d and axis-aligned boxes, in float (the renderers' hot-path precision).
#include <algorithm>
#include <limits>

#include "tessera/math/types.hpp"

namespace tessera {

/// A ray o + t d with a valid interval [tmin, tmax] and a time (for motion blur).
struct Ray {
  Vec3f origin{0.0f};
  Vec3f dir{0.0f, 0.0f, -1.0f};
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  float time = 0.0f;

  /// The point at parameter t.
  Vec3f at(float t) const { return origin + t * dir; }
  /// Whether t lies in [tmin, tmax] (false for NaN, so a kernel's "no root" NaN is rejected here).
  bool in_range(float t) const { return t >= tmin && t <= tmax; }
};

/// The ray's parameter at the plane n . (P - p) = 0, or NaN when the ray is parallel to it.
inline float plane_t(const Vec3f& p, const Vec3f& n, const Ray& ray) {
  const float denom = glm::dot(n, ray.dir);
  if (denom == 0) return std::numeric_limits<float>::quiet_NaN();
  return glm::dot(n, p - ray.origin) / denom;
}

/// An axis-aligned bounding box; the default box is empty (lo = +inf, hi = -inf) and absorbs anything.
struct AABB {
  Vec3f lo{std::numeric_limits<float>::infinity()};
  Vec3f hi{-std::numeric_limits<float>::infinity()};

  /// True when no point was added.
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  /// Grows to contain p.
  void expand(const Vec3f& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  /// Grows to contain b.
  void expand(const AABB& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  /// Box center (undefined when empty).
  Vec3f center() const { return 0.5f * (lo + hi); }
  /// Box extent hi - lo.
  Vec3f extent() const { return hi - lo; }
  /// Surface area (0 when empty), the SAH's measure.
  float area() const {
    if (empty()) return 0.0f;
    const Vec3f e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  /// Index of the longest axis.
  int longest_axis() const {
    const Vec3f e = extent();
    return e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  }
  /// True when p is inside or on the boundary.
  bool contains(const Vec3f& p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  }
};

/// The slab test: the parameter interval where the ray is inside the box, clipped to [ray.tmin, ray.tmax].
/// Returns false when it is empty. inv_dir is 1/ray.dir (infinities for zero components are fine).
inline bool intersect_slabs(const AABB& box, const Ray& ray, const Vec3f& inv_dir, float& t0, float& t1) {
  t0 = ray.tmin;
  t1 = ray.tmax;
  for (int a = 0; a < 3; ++a) {
    float tn = (box.lo[a] - ray.origin[a]) * inv_dir[a];
    float tf = (box.hi[a] - ray.origin[a]) * inv_dir[a];
    if (tn > tf) std::swap(tn, tf);
    // Written so that a NaN (0 * inf on a slab plane) keeps the interval unchanged.
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace tessera
