// Ray-shape intersection kernels (the notes' chapter on ray-object intersection).
#include "tessera/accel/shapes.hpp"

#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>

#include "tessera/core/error.hpp"

namespace tessera {

namespace {

constexpr float kTwoPi = 6.28318530717958647692f;
constexpr float kInvPi = 0.31830988618379067154f;

/// Fills the hit for parameter t with an (already unit) normal and uv.
inline bool accept(const Ray& ray, float t, const Vec3f& normal, const Vec2f& uv, Hit& hit) {
  hit.t = t;
  hit.point = ray.at(t);
  hit.normal = normal;
  hit.uv = uv;
  return true;
}

/// The real roots t0 <= t1 of a t^2 + b t + c = 0 by the cancellation-free form q = -(b + sign(b) sqrt(disc)) / 2,
/// roots q / a and c / q (Numerical Recipes 5.6). Double precision: cylinders and cones square their coordinates.
/// A vanishing a (a ray parallel to a cone's side) leaves the one root of the linear equation in both.
bool solve_quadratic(double a, double b, double c, double& t0, double& t1) {
  if (std::abs(a) < 1e-12 * (std::abs(b) + std::abs(c))) {
    if (b == 0) return false;
    t0 = t1 = -c / b;
    return true;
  }
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return false;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  t0 = q / a;
  t1 = q != 0 ? c / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

/// u = phi / 2pi around +y (from +x toward -z), v = theta / pi from +y, for a unit direction n.
Vec2f spherical_uv(const Vec3f& n) {
  float phi = std::atan2(-n.z, n.x);
  if (phi < 0) phi += kTwoPi;
  return {phi / kTwoPi, std::acos(std::clamp(n.y, -1.0f, 1.0f)) * kInvPi};
}

/// An orthonormal tangent pair for unit n (Duff et al. 2017, "Building an orthonormal basis, revisited").
void tangent_frame(const Vec3f& n, Vec3f& t1, Vec3f& t2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  t1 = Vec3f(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  t2 = Vec3f(b, sign + n.y * n.y * a, -n.y);
}

/// A disk-shaped cap of the y axis at height y (radius r, outward normal ny = +1 or -1).
template <bool Full>
bool cap_hit(float y, float r, float ny, const Ray& ray, float& t_best, Hit& hit) {
  if (ray.dir.y == 0) return false;
  const float t = (y - ray.origin.y) / ray.dir.y;
  if (!ray.in_range(t) || t >= t_best) return false;
  const Vec3f p = ray.at(t);
  if (p.x * p.x + p.z * p.z > r * r) return false;
  t_best = t;
  if constexpr (!Full) return true;
  return accept(ray, t, Vec3f(0, ny, 0), Vec2f(0.5f * p.x / r + 0.5f, 0.5f * p.z / r + 0.5f), hit);
}

/// u = phi / 2pi around the y axis for an offset (x, z) from the axis.
float azimuth_u(float x, float z) {
  float phi = std::atan2(-z, x);
  if (phi < 0) phi += kTwoPi;
  return phi / kTwoPi;
}

AABB box_of(std::span<const Vec3f> points) {
  AABB b;
  for (const Vec3f& p : points) b.expand(p);
  return b;
}

/// Newell's normal of a polygon (robust for non-convex and slightly non-planar polygons), not normalized.
Vec3f newell_normal(const std::vector<Vec3f>& v) {
  Vec3f n(0.0f);
  for (size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    n.x += (v[j].y - v[i].y) * (v[j].z + v[i].z);
    n.y += (v[j].z - v[i].z) * (v[j].x + v[i].x);
    n.z += (v[j].x - v[i].x) * (v[j].y + v[i].y);
  }
  return n;
}

/// The two coordinates kept when the normal's largest one is dropped (the notes: project onto the plane where the
/// polygon's projection has the largest area).
void kept_axes(const Vec3f& n, int& a0, int& a1) {
  const Vec3f m = glm::abs(n);
  const int drop = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  a0 = (drop + 1) % 3;
  a1 = (drop + 2) % 3;
}

float cross2(Vec2f a, Vec2f b) { return a.x * b.y - a.y * b.x; }

}  // namespace

// The kernels, each templated on Full: true fills the whole hit (t, point, normal, uv); false (any-hit, for shadow
// rays) returns at the first hit in range with only hit.t set, skipping the normal, the point and the trigonometry of
// the uv.
namespace {

template <bool Full>
bool kernel(const Sphere& s, const Ray& ray, Hit& hit) {
  // The notes' quadratic |o + t d - c|^2 = r^2 in the form of Haines et al. ("Precision improvements for ray/sphere
  // intersection", Ray Tracing Gems ch. 7): the discriminant from the distance of the center to the line, roots by
  // the cancellation-free q.
  const Vec3f f = ray.origin - s.center;
  const float a = glm::dot(ray.dir, ray.dir);
  const float b = glm::dot(f, ray.dir);  // half of the usual b
  const float c = glm::dot(f, f) - s.radius * s.radius;
  const Vec3f l = f - (b / a) * ray.dir;
  const float disc = s.radius * s.radius - glm::dot(l, l);  // = (b^2 - a c) / a
  if (disc < 0) return false;
  const float q = -(b + std::copysign(std::sqrt(a * disc), b));
  float t0 = c / q, t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  const float t = ray.in_range(t0) ? t0 : t1;
  if (!ray.in_range(t)) return false;
  if constexpr (!Full) {
    hit.t = t;
    return true;
  }
  const Vec3f n = glm::normalize(ray.at(t) - s.center);
  return accept(ray, t, n, spherical_uv(n), hit);
}

template <bool Full>
bool kernel(const Plane& s, const Ray& ray, Hit& hit) {
  const float t = plane_t(s.point, s.normal, ray);
  if (!ray.in_range(t)) return false;  // false for NaN too
  if constexpr (!Full) {
    hit.t = t;
    return true;
  }
  const Vec3f n = glm::normalize(s.normal);
  Vec3f t1, t2;
  tangent_frame(n, t1, t2);
  const Vec3f d = ray.at(t) - s.point;
  return accept(ray, t, n, Vec2f(glm::dot(d, t1), glm::dot(d, t2)), hit);
}

template <bool Full>
bool kernel(const Triangle& s, const Ray& ray, Hit& hit) {
  // Moller-Trumbore: solve o + t d = a + b1 (b - a) + b2 (c - a) by Cramer's rule.
  const Vec3f e1 = s.b - s.a, e2 = s.c - s.a;
  const Vec3f p = glm::cross(ray.dir, e2);
  const float det = glm::dot(e1, p);
  if (det == 0) return false;
  const float inv = 1.0f / det;
  const Vec3f tv = ray.origin - s.a;
  const float b1 = glm::dot(tv, p) * inv;
  if (b1 < 0 || b1 > 1) return false;
  const Vec3f q = glm::cross(tv, e1);
  const float b2 = glm::dot(ray.dir, q) * inv;
  if (b2 < 0 || b1 + b2 > 1) return false;
  const float t = glm::dot(e2, q) * inv;
  if (!ray.in_range(t)) return false;
  if constexpr (!Full) {
    hit.t = t;
    return true;
  }
  return accept(ray, t, glm::normalize(glm::cross(e1, e2)), Vec2f(b1, b2), hit);
}

}  // namespace

bool point_in_polygon(std::span<const Vec2f> poly, Vec2f p, PointInPolygon test) {
  const size_t n = poly.size();
  if (n < 3) return false;
  switch (test) {
    case PointInPolygon::crossing: {
      // Cast a ray from p toward +x and count the edges it crosses. An edge counts when its endpoints lie on
      // different sides of the line y = p.y, one endpoint on the line counting as above: a ray through a vertex is
      // counted once (the notes' "messes up at corners", fixed by this half-open rule).
      bool inside = false;
      for (size_t i = 0, j = n - 1; i < n; j = i++) {
        const Vec2f a = poly[j], b = poly[i];
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
      }
      return inside;
    }
    case PointInPolygon::winding: {
      // The notes: join p to every vertex and add the signed angles between consecutive joins; the sum is 2 pi times
      // the winding number (0 outside).
      double sum = 0;
      for (size_t i = 0, j = n - 1; i < n; j = i++) {
        const Vec2f a = poly[j] - p, b = poly[i] - p;
        sum += std::atan2(double(cross2(a, b)), double(glm::dot(a, b)));
      }
      return std::abs(sum) > kPi;  // |winding number| >= 1
    }
    case PointInPolygon::half_plane: {
      // The notes' test: p is inside a convex polygon when it lies on the inner side of every edge line. A non-convex
      // polygon is covered by the fan of triangles (v0, vi, vi+1) with parity (Haines 1994), which for a convex
      // polygon is exactly the notes' test.
      // The side of the line a-b is computed from the lexicographically smaller endpoint, so the two triangles that
      // share a diagonal get bit-identical opposite answers; a point exactly on a line is treated as if moved by an
      // infinitesimal (epsilon, epsilon^2) (simulation of simplicity). A point then lies in exactly one of the two.
      auto side = [&p](Vec2f a, Vec2f b) {
        const bool swapped = b.x < a.x || (b.x == a.x && b.y < a.y);
        if (swapped) std::swap(a, b);
        const Vec2f d = b - a;
        const float e = cross2(d, p - a);
        return swapped != (e != 0 ? e > 0 : (d.y != 0 ? d.y < 0 : d.x > 0));
      };
      bool inside = false;
      for (size_t i = 1; i + 1 < n; ++i) {
        const bool s0 = side(poly[0], poly[i]), s1 = side(poly[i], poly[i + 1]), s2 = side(poly[i + 1], poly[0]);
        if (s0 == s1 && s1 == s2) inside = !inside;
      }
      return inside;
    }
  }
  return false;
}

namespace {

template <bool Full>
bool kernel(const Polygon& s, const Ray& ray, Hit& hit) {
  // The notes: intersect the polygon's plane, project the point and the polygon to 2D by dropping the coordinate in
  // which the normal is largest, then test the point in the polygon.
  if (s.vertices.size() < 3) return false;
  const Vec3f n = newell_normal(s.vertices);
  const float t = plane_t(s.vertices[0], n, ray);
  if (!ray.in_range(t)) return false;
  int a0, a1;
  kept_axes(n, a0, a1);
  const Vec3f p = ray.at(t);
  // Small polygons project on the stack; larger ones allocate.
  constexpr size_t kInline = 16;
  Vec2f inline_buf[kInline];
  std::vector<Vec2f> heap_buf;
  Vec2f* proj = inline_buf;
  if (s.vertices.size() > kInline) {
    heap_buf.resize(s.vertices.size());
    proj = heap_buf.data();
  }
  for (size_t i = 0; i < s.vertices.size(); ++i) proj[i] = Vec2f(s.vertices[i][a0], s.vertices[i][a1]);
  const Vec2f q(p[a0], p[a1]);
  if (!point_in_polygon({proj, s.vertices.size()}, q, s.test)) return false;
  if constexpr (!Full) {
    hit.t = t;
    return true;
  }
  return accept(ray, t, glm::normalize(n), q, hit);
}

template <bool Full>
bool kernel(const Box& s, const Ray& ray, Hit& hit) {
  const Vec3f inv(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
  float t0, t1;
  const AABB box{s.lo, s.hi};
  if (!intersect_slabs(box, ray, inv, t0, t1)) return false;
  // The entry point unless the ray starts inside (or at tmin on the surface), then the exit point.
  float tn = -std::numeric_limits<float>::infinity(), tf = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    const float x0 = (s.lo[a] - ray.origin[a]) * inv[a], x1 = (s.hi[a] - ray.origin[a]) * inv[a];
    tn = std::max(tn, std::min(x0, x1));
    tf = std::min(tf, std::max(x0, x1));
  }
  const float t = tn >= ray.tmin ? tn : tf;
  if (!ray.in_range(t)) return false;
  if constexpr (!Full) {
    hit.t = t;
    return true;
  }
  // The face: the axis along which the point is relatively farthest from the center.
  const Vec3f p = ray.at(t), c = 0.5f * (s.lo + s.hi), h = 0.5f * (s.hi - s.lo);
  const Vec3f rel = (p - c) / h;
  const Vec3f m = glm::abs(rel);
  const int axis = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  Vec3f n(0.0f);
  n[axis] = rel[axis] > 0 ? 1.0f : -1.0f;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  return accept(ray, t, n, Vec2f(0.5f * rel[u] + 0.5f, 0.5f * rel[v] + 0.5f), hit);
}

template <bool Full>
bool kernel(const Cylinder& s, const Ray& ray, Hit& hit) {
  const Vec3f o = ray.origin, d = ray.dir;
  float t_best = std::numeric_limits<float>::infinity();
  double t0, t1;
  // Side: (ox + t dx)^2 + (oz + t dz)^2 = r^2, kept where y is in [y0, y1].
  if (solve_quadratic(double(d.x) * d.x + double(d.z) * d.z, 2.0 * (double(o.x) * d.x + double(o.z) * d.z),
                      double(o.x) * o.x + double(o.z) * o.z - double(s.radius) * s.radius, t0, t1)) {
    for (const double td : {t0, t1}) {
      const float t = float(td);
      if (!ray.in_range(t)) continue;
      const Vec3f p = ray.at(t);
      if (p.y < s.y0 || p.y > s.y1) continue;
      if constexpr (!Full) {
        hit.t = t;
        return true;
      }
      const Vec3f n = glm::normalize(Vec3f(p.x, 0, p.z));
      t_best = t;
      accept(ray, t, n, Vec2f(azimuth_u(p.x, p.z), (p.y - s.y0) / (s.y1 - s.y0)), hit);
      break;
    }
  }
  if (s.capped) {
    if (cap_hit<Full>(s.y0, s.radius, -1.0f, ray, t_best, hit) && !Full) {
      hit.t = t_best;
      return true;
    }
    if (cap_hit<Full>(s.y1, s.radius, 1.0f, ray, t_best, hit) && !Full) {
      hit.t = t_best;
      return true;
    }
  }
  return t_best < std::numeric_limits<float>::infinity();
}

template <bool Full>
bool kernel(const Cone& s, const Ray& ray, Hit& hit) {
  // The notes' cone (x - xb)^2 + (z - zb)^2 = (k (y - yb))^2 with the ray substituted, in coordinates about the apex.
  const Vec3f o = ray.origin - s.apex, d = ray.dir;
  const double k2 = double(s.radius) * s.radius / (double(s.height) * s.height);
  const double a = double(d.x) * d.x + double(d.z) * d.z - k2 * d.y * d.y;
  const double b = 2.0 * (double(o.x) * d.x + double(o.z) * d.z - k2 * o.y * d.y);
  const double c = double(o.x) * o.x + double(o.z) * o.z - k2 * o.y * o.y;
  float t_best = std::numeric_limits<float>::infinity();
  double t0, t1;
  if (solve_quadratic(a, b, c, t0, t1)) {
    for (const double td : {t0, t1}) {
      const float t = float(td);
      if (!ray.in_range(t)) continue;
      const Vec3f p = ray.at(t);
      const float y = p.y - s.apex.y;
      if (y < 0 || y > s.height) continue;  // the other nappe, or beyond the base
      if constexpr (!Full) {
        hit.t = t;
        return true;
      }
      // The notes' normal: D from the axis to P, T1 = D rotated by pi/2 about y, T2 = B - P along the surface,
      // N = T1 x T2 normalized (pointing out of the cone; at the apex itself, straight down).
      const Vec3f dvec(p.x - s.apex.x, 0, p.z - s.apex.z);
      const Vec3f t1v(-dvec.z, 0, dvec.x), t2v = s.apex - p;
      const Vec3f cr = glm::cross(t1v, t2v);
      const float len = glm::length(cr);
      const Vec3f n = len > 0 ? cr / len : Vec3f(0, -1, 0);
      t_best = t;
      accept(ray, t, n, Vec2f(azimuth_u(dvec.x, dvec.z), y / s.height), hit);
      break;
    }
  }
  if (s.capped && ray.dir.y != 0) {
    // The base cap: the plane y = yb + h, a hit when its distance to the base center is below the radius; N = +y.
    const float t = (s.apex.y + s.height - ray.origin.y) / ray.dir.y;
    if (ray.in_range(t) && t < t_best) {
      const Vec3f p = ray.at(t);
      const float dx = p.x - s.apex.x, dz = p.z - s.apex.z;
      if (dx * dx + dz * dz <= s.radius * s.radius) {
        t_best = t;
        if constexpr (!Full) {
          hit.t = t;
          return true;
        }
        accept(ray, t, Vec3f(0, 1, 0), Vec2f(0.5f * dx / s.radius + 0.5f, 0.5f * dz / s.radius + 0.5f), hit);
      }
    }
  }
  return t_best < std::numeric_limits<float>::infinity();
}

template <bool Full>
bool kernel(const Disk& s, const Ray& ray, Hit& hit) {
  const float t = plane_t(s.center, s.normal, ray);
  if (!ray.in_range(t)) return false;
  const Vec3f d = ray.at(t) - s.center;
  const float r2 = glm::dot(d, d);
  if (r2 > s.radius * s.radius) return false;
  if constexpr (!Full) {
    hit.t = t;
    return true;
  }
  const Vec3f n = glm::normalize(s.normal);
  Vec3f t1, t2;
  tangent_frame(n, t1, t2);
  float phi = std::atan2(glm::dot(d, t2), glm::dot(d, t1));
  if (phi < 0) phi += kTwoPi;
  return accept(ray, t, n, Vec2f(std::sqrt(r2) / s.radius, phi / kTwoPi), hit);
}

template <bool Full>
bool kernel(const Ellipsoid& s, const Ray& ray, Hit& hit) {
  // Scale space so the ellipsoid becomes the unit sphere; t is unchanged because the direction is scaled too.
  Ray unit = ray;
  unit.origin = (ray.origin - s.center) / s.radii;
  unit.dir = ray.dir / s.radii;
  Hit h;
  if (!kernel<Full>(Sphere{Vec3f(0.0f), 1.0f}, unit, h)) return false;
  if constexpr (!Full) {
    hit.t = h.t;
    return true;
  }
  // The gradient of sum(((P - c) / r)^2) is the normal: the unit sphere's normal divided by the radii.
  return accept(ray, h.t, glm::normalize(h.normal / s.radii), h.uv, hit);
}

}  // namespace

bool intersect(const Sphere& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Plane& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Triangle& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Polygon& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Box& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Cylinder& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Cone& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Disk& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }
bool intersect(const Ellipsoid& s, const Ray& ray, Hit& hit) { return kernel<true>(s, ray, hit); }

AABB bounds(const Sphere& s) { return {s.center - Vec3f(s.radius), s.center + Vec3f(s.radius)}; }

AABB bounds(const Plane&) {
  constexpr float inf = std::numeric_limits<float>::infinity();
  return {Vec3f(-inf), Vec3f(inf)};
}

AABB bounds(const Triangle& s) {
  const Vec3f v[3] = {s.a, s.b, s.c};
  return box_of(v);
}

AABB bounds(const Polygon& s) { return box_of(s.vertices); }

AABB bounds(const Box& s) { return {s.lo, s.hi}; }

AABB bounds(const Cylinder& s) { return {Vec3f(-s.radius, s.y0, -s.radius), Vec3f(s.radius, s.y1, s.radius)}; }

AABB bounds(const Cone& s) {
  return {s.apex - Vec3f(s.radius, 0, s.radius), s.apex + Vec3f(s.radius, s.height, s.radius)};
}

AABB bounds(const Disk& s) {
  // Along axis i the disk reaches radius * sqrt(1 - n_i^2) from its center.
  const Vec3f n = glm::normalize(s.normal);
  const Vec3f e = s.radius * glm::sqrt(glm::max(Vec3f(0.0f), Vec3f(1.0f) - n * n));
  return {s.center - e, s.center + e};
}

AABB bounds(const Ellipsoid& s) { return {s.center - s.radii, s.center + s.radii}; }

bool intersect(const Shape& shape, const Ray& ray, Hit& hit) {
  return std::visit([&](const auto& s) { return kernel<true>(s, ray, hit); }, shape);
}

bool occludes(const Shape& shape, const Ray& ray) {
  Hit hit;
  return std::visit([&](const auto& s) { return kernel<false>(s, ray, hit); }, shape);
}

AABB bounds(const Shape& shape) {
  return std::visit([](const auto& s) { return bounds(s); }, shape);
}

Instance::Instance(Shape shape, const Mat4& to_world) : shape_(std::move(shape)), to_world_(to_world) {
  const double det = glm::determinant(Mat3(to_world));
  if (!(std::abs(det) > 1e-12))
    throw InvalidInput(fmt::format("Instance: the transform is singular (determinant {:g})", det));
  const Mat4 inv = glm::inverse(to_world);
  to_object_ = Mat4f(inv);
  normal_to_world_ = Mat3f(glm::transpose(Mat3(inv)));
}

bool Instance::intersect(const Ray& ray, Hit& hit) const {
  Ray local = ray;
  local.origin = Vec3f(to_object_ * Vec4f(ray.origin, 1.0f));
  local.dir = Mat3f(to_object_) * ray.dir;
  Hit h;
  if (!tessera::intersect(shape_, local, h)) return false;
  hit = h;
  hit.point = ray.at(h.t);
  hit.normal = glm::normalize(normal_to_world_ * h.normal);
  return true;
}

bool Instance::occludes(const Ray& ray) const {
  Ray local = ray;
  local.origin = Vec3f(to_object_ * Vec4f(ray.origin, 1.0f));
  local.dir = Mat3f(to_object_) * ray.dir;
  return tessera::occludes(shape_, local);
}

AABB Instance::bounds() const {
  const AABB b = tessera::bounds(shape_);
  if (!std::isfinite(b.lo.x) || !std::isfinite(b.hi.x)) return b;  // a plane stays infinite
  AABB out;
  for (int i = 0; i < 8; ++i) {
    const Vec3f corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
    out.expand(Vec3f(to_world_ * Vec4f(corner, 1.0f)));
  }
  return out;
}

}  // namespace tessera
