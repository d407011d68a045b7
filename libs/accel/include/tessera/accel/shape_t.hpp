#pragma once
// t-only ray-shape kernels for the hottest loops: the nearest t at which a ray meets a sphere or a plane, and whether a
// shadow segment meets one, without the point, normal or uv that the full kernels (shapes.hpp) compute. Inline, so a
// loop over many shapes keeps the ray in registers; the ray tracer's flat list of spheres and planes calls them.
//
// sphere_t multiplies by the ray's 1 / (d . d) where the full sphere kernel divides by d . d: the two can differ in the
// last bit of t (measured: 25 of 19,200 pixels of the built-in `shapes` scene, by at most 4e-7, when the full kernel
// was made to call sphere_t), so each keeps its own arithmetic and every existing result stays as it was.
#include <cmath>
#include <limits>
#include <utility>

#include "tessera/math/ray.hpp"

namespace tessera {

/// The nearest t in [ray.tmin, ray.tmax] where the ray meets the sphere |P - center| = radius, or NaN: the notes'
/// quadratic in the form of Haines et al. ("Precision improvements for ray/sphere intersection", Ray Tracing Gems
/// ch. 7), with a = d . d and inv_a = 1 / a passed in, so that a loop over many spheres computes them once per ray.
/// The direction need not be unit length. A ray starting outside and moving away (tmin >= 0) is rejected first.
inline float sphere_t(const Vec3f& center, float radius, const Ray& ray, float a, float inv_a) {
  const Vec3f f = ray.origin - center;
  const float b = glm::dot(f, ray.dir);  // half of the usual b
  const float c = glm::dot(f, f) - radius * radius;
  if (c > 0 && b > 0 && ray.tmin >= 0) return std::numeric_limits<float>::quiet_NaN();  // outside, moving away
  const Vec3f l = f - (b * inv_a) * ray.dir;
  const float disc = radius * radius - glm::dot(l, l);  // = (b^2 - a c) / a
  if (disc < 0) return std::numeric_limits<float>::quiet_NaN();
  const float q = -(b + std::copysign(std::sqrt(a * disc), b));
  float t0 = c / q, t1 = q * inv_a;
  if (t0 > t1) std::swap(t0, t1);
  return ray.in_range(t0) ? t0 : t1;
}

/// Whether the segment [ray.tmin, ray.tmax] of the ray meets the sphere (shadow rays); a = d . d. From outside the
/// sphere neither root nor division is needed: the ray must approach the center (b = f . d < 0) with its line within
/// the radius (b^2 >= a c), and then the segment enters the sphere when it reaches the line's closest point to the
/// center (t = -b / a <= tmax) or ends inside; otherwise as sphere_t.
inline bool sphere_blocks(const Vec3f& center, float radius, const Ray& ray, float a) {
  const Vec3f f = ray.origin - center;
  const float b = glm::dot(f, ray.dir);
  const float c = glm::dot(f, f) - radius * radius;
  if (c <= 0 || ray.tmin < 0) return ray.in_range(sphere_t(center, radius, ray, a, 1.0f / a));
  if (b >= 0 || b * b < a * c) return false;  // moving away, or the line misses
  if (-b <= ray.tmax * a) return true;
  const Vec3f end = f + ray.tmax * ray.dir;
  return glm::dot(end, end) <= radius * radius;
}

/// plane_t (math/ray.hpp: t = (n . (p - o)) / (n . d), NaN when parallel) for a nearest-hit search: NaN without the
/// division when the hit lies behind a ray with tmin >= 0 (out of range anyway, e.g. a ray above a floor going up).
inline float plane_t_ahead(const Vec3f& point, const Vec3f& normal, const Ray& ray) {
  const float num = glm::dot(normal, point - ray.origin), denom = glm::dot(normal, ray.dir);
  if (ray.tmin >= 0 && num * denom < 0.0f) return std::numeric_limits<float>::quiet_NaN();
  return denom == 0 ? std::numeric_limits<float>::quiet_NaN() : num / denom;
}

/// Whether the segment [ray.tmin, ray.tmax] of the ray meets the plane through `point` with normal `normal` (shadow
/// rays). A finite segment from tmin >= 0 whose two ends lie strictly on the same side (the usual light and point above
/// a floor) is answered without a division; otherwise as plane_t.
inline bool plane_blocks(const Vec3f& point, const Vec3f& normal, const Ray& ray) {
  const float start = glm::dot(normal, ray.origin - point);
  if (ray.tmin >= 0 && std::isfinite(ray.tmax) && start * glm::dot(normal, ray.at(ray.tmax) - point) > 0.0f)
    return false;
  return ray.in_range(plane_t(point, normal, ray));
}

}  // namespace tessera
