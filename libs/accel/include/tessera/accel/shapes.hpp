#pragma once
// Ray-shape intersection kernels (the notes' "add a primitive" contract: intersect a ray and return the hit point and
// surface normal; return a bounding box) and instancing under an affine transform.
//
// Every kernel accepts a ray whose direction need not be unit length (Instance hands them rays in object space) and
// reports the nearest hit with t in [ray.tmin, ray.tmax]. Normals are unit, geometric and point out of the solid (for
// the open plane, disk, triangle and polygon: along the normal the shape defines, whichever side the ray comes from).
#include <limits>
#include <span>
#include <variant>
#include <vector>

#include "tessera/math/ray.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// What a ray hits: parameter, point, unit outward geometric normal, surface coordinates and primitive index.
struct Hit {
  float t = std::numeric_limits<float>::infinity();
  Vec3f point{0.0f};
  Vec3f normal{0.0f};  ///< unit, geometric, outward
  Vec2f uv{0.0f};      ///< shape-specific surface coordinates (each shape documents its own)
  int prim = -1;       ///< primitive index for aggregates (MeshAccel: triangle), -1 otherwise
};

/// The sphere |P - center| = radius. uv = (phi / 2pi, theta / pi), phi around +y from +x toward -z, theta from +y.
struct Sphere {
  Vec3f center{0.0f};
  float radius = 1.0f;
};

/// The infinite plane through `point` with the given normal (need not be unit). uv = coordinates in a tangent frame.
struct Plane {
  Vec3f point{0.0f};
  Vec3f normal{0.0f, 1.0f, 0.0f};
};

/// A triangle; normal (b - a) x (c - a) (counterclockwise = front). uv = barycentrics (b1, b2) of b and c.
struct Triangle {
  Vec3f a, b, c;
};

/// The notes' three point-in-polygon tests, applied in 2D after dropping the normal's largest coordinate.
enum class PointInPolygon {
  crossing,    ///< parity of the crossings of a ray from the point (even-odd rule)
  winding,     ///< winding number != 0 (nonzero rule)
  half_plane,  ///< the point lies on the inner side of every edge line; for a non-convex polygon applied to the
               ///< triangles of a fan, counting parity (Haines, "Point in Polygon Strategies", 1994)
};

/// A planar polygon (vertices in order, counterclockwise = front, convex or not, simple). Plane from Newell's normal.
/// uv = the two kept coordinates of the projected hit point.
struct Polygon {
  std::vector<Vec3f> vertices;
  PointInPolygon test = PointInPolygon::crossing;
};

/// An axis-aligned box. uv = coordinates in [0,1]^2 on the face hit.
struct Box {
  Vec3f lo{-1.0f}, hi{1.0f};
};

/// A cylinder about the y axis x^2 + z^2 = radius^2, y in [y0, y1], with or without its two disk caps (place it with
/// an Instance). uv = (phi / 2pi, (y - y0) / (y1 - y0)) on the side; cap points (x/r, z/r) * 0.5 + 0.5.
struct Cylinder {
  float radius = 1.0f, y0 = 0.0f, y1 = 1.0f;
  bool capped = true;
};

/// The notes' cone: apex B, axis +y, (x - xb)^2 + (z - zb)^2 = (k (y - yb))^2 for y in [yb, yb + height] with
/// k = radius / height, and its base cap (the disk at y = yb + height, normal (0, 1, 0)). Side normal by the notes'
/// construction N = T1 x T2 (T1 the base-center-to-P direction rotated by pi/2, T2 = B - P). uv as Cylinder.
struct Cone {
  Vec3f apex{0.0f};
  float radius = 1.0f;
  float height = 1.0f;
  bool capped = true;
};

/// A flat disk. uv = (r / radius, phi / 2pi) in a tangent frame.
struct Disk {
  Vec3f center{0.0f};
  Vec3f normal{0.0f, 1.0f, 0.0f};
  float radius = 1.0f;
};

/// An axis-aligned ellipsoid ((P - center) / radii)^2 = 1. uv as Sphere on the unit sphere it maps to.
struct Ellipsoid {
  Vec3f center{0.0f};
  Vec3f radii{1.0f};
};

bool intersect(const Sphere& s, const Ray& ray, Hit& hit);
bool intersect(const Plane& s, const Ray& ray, Hit& hit);
bool intersect(const Triangle& s, const Ray& ray, Hit& hit);
bool intersect(const Polygon& s, const Ray& ray, Hit& hit);
bool intersect(const Box& s, const Ray& ray, Hit& hit);
bool intersect(const Cylinder& s, const Ray& ray, Hit& hit);
bool intersect(const Cone& s, const Ray& ray, Hit& hit);
bool intersect(const Disk& s, const Ray& ray, Hit& hit);
bool intersect(const Ellipsoid& s, const Ray& ray, Hit& hit);

/// Bounding boxes. A Plane's is infinite: keep planes out of a BVH and test them separately.
AABB bounds(const Sphere& s);
AABB bounds(const Plane& s);
AABB bounds(const Triangle& s);
AABB bounds(const Polygon& s);
AABB bounds(const Box& s);
AABB bounds(const Cylinder& s);
AABB bounds(const Cone& s);
AABB bounds(const Disk& s);
AABB bounds(const Ellipsoid& s);

/// 2D point-in-polygon by one of the notes' tests; `poly` holds the polygon's projected vertices in order.
bool point_in_polygon(std::span<const Vec2f> poly, Vec2f p, PointInPolygon test);

/// Any shape.
using Shape = std::variant<Sphere, Plane, Triangle, Polygon, Box, Cylinder, Cone, Disk, Ellipsoid>;

/// Nearest hit of a ray with any shape, t in [ray.tmin, ray.tmax]; fills t, point, normal, uv.
bool intersect(const Shape& shape, const Ray& ray, Hit& hit);
/// The shape's bounding box (infinite for a Plane).
AABB bounds(const Shape& shape);
/// Whether the ray hits the shape with t in [ray.tmin, ray.tmax] (shadow rays): intersect's test, returning at the
/// first hit found and computing no point, normal or uv.
bool occludes(const Shape& shape, const Ray& ray);

/// A shape placed in the world by an affine transform (instancing). The ray is carried into object space (its
/// direction is not renormalized, so t is the same in both spaces); hit points go back by to_world and normals by its
/// inverse transpose. Throws InvalidInput when to_world is singular.
class Instance {
 public:
  explicit Instance(Shape shape, const Mat4& to_world = Mat4(1));
  /// Nearest hit in world space; t in [ray.tmin, ray.tmax].
  bool intersect(const Ray& ray, Hit& hit) const;
  /// Whether the ray hits the shape with t in [ray.tmin, ray.tmax] (shadow rays; see tessera::occludes).
  bool occludes(const Ray& ray) const;
  /// The world box: the 8 corners of the object box transformed (infinite for a plane).
  AABB bounds() const;
  const Shape& shape() const { return shape_; }
  const Mat4f& to_world() const { return to_world_; }

 private:
  Shape shape_;
  Mat4f to_world_, to_object_;
  Mat3f normal_to_world_;
};

}  // namespace tessera
