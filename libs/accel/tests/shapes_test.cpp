// Shape kernels against analytic references: hit points on the surface, unit outward normals (the implicit function's
// gradient, independent of each kernel's own construction), no surface crossing before the reported t, the image area
// of a sphere, the three point-in-polygon tests against each other, and instances against transformed shapes.
#include "tessera/accel/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>

#include "tessera/core/error.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/math/camera.hpp"

namespace tessera {
namespace {

Vec3f random_unit(Rng& rng) {
  for (;;) {
    const Vec3f v(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
    const float l = glm::length(v);
    if (l > 0.1f && l <= 1) return v / l;
  }
}

/// A closed solid as an implicit function f (< 0 inside) with its analytic gradient.
struct Solid {
  Shape shape;
  std::function<float(const Vec3f&)> f;
  std::function<Vec3f(const Vec3f&)> grad;  ///< outward normal direction at a surface point
  float scale;                              ///< size of the shape (for tolerances)
};

/// Random rays from points outside the solid's box toward random points near it. Checks against the implicit
/// function: a reported hit lies on the surface with the gradient's direction as normal, every sample of the ray
/// before it is outside, a point just past it is inside; a miss has no inside sample along the ray.
void check_solid(const Solid& s, uint64_t seed, int rays = 4000) {
  Rng rng(seed);
  const AABB box = bounds(s.shape);
  const Vec3f c = box.center();
  const float r = 0.5f * glm::length(box.extent());
  int hits = 0, not_inside = 0;
  for (int i = 0; i < rays; ++i) {
    Ray ray;
    ray.origin = c + 2.5f * r * random_unit(rng);
    const Vec3f target = c + 0.9f * r * Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * 2.0f;
    ray.dir = (target - ray.origin) * (0.5f + rng.uniform());  // not unit: kernels must not assume it
    Hit hit;
    const float len = glm::length(ray.dir);
    const float tol = 2e-4f * s.scale;
    const float end = 6 * r / len;
    if (intersect(s.shape, ray, hit)) {
      ++hits;
      ASSERT_NEAR(glm::length(hit.point - ray.at(hit.t)), 0.0f, tol);
      ASSERT_NEAR(s.f(hit.point), 0.0f, 5 * tol) << "hit not on the surface, ray " << i;
      ASSERT_NEAR(glm::length(hit.normal), 1.0f, 1e-5f);
      const Vec3f g = glm::normalize(s.grad(hit.point));
      EXPECT_GT(glm::dot(g, hit.normal), 0.999f) << "ray " << i;
      for (int k = 0; k < 200; ++k) {
        const float t = hit.t * float(k) / 200.0f;
        ASSERT_GE(s.f(ray.at(t)), -tol) << "surface crossed before the hit, ray " << i;
      }
      // Just past an entry the ray is inside (unless it grazed the surface).
      // (A ray entering within a hair of an edge may leave again at once: a few are allowed.)
      if (glm::dot(hit.normal, ray.dir) < -0.05f * len) not_inside += s.f(ray.at(hit.t + 10 * tol / len)) >= 0;
    } else {
      for (int k = 0; k <= 2000; ++k) ASSERT_GE(s.f(ray.at(end * float(k) / 2000.0f)), -tol) << "missed, ray " << i;
    }
  }
  EXPECT_GT(hits, rays / 10);
  EXPECT_LT(hits, rays);
  EXPECT_LE(not_inside, rays / 500);
}

TEST(Shapes, SphereSurfaceNormalsAndFirstCrossing) {
  const Vec3f c(1, -2, 0.5f);
  const float r = 1.5f;
  check_solid(
      {Sphere{c, r}, [=](const Vec3f& p) { return glm::length(p - c) - r; }, [=](const Vec3f& p) { return p - c; }, r},
      1);
}

TEST(Shapes, SphereMatchesDoubleQuadraticFromInsideAndFar) {
  // t against the quadratic solved in double precision, including a tiny sphere far away (where the textbook form
  // loses every digit) and rays starting inside (far root).
  Rng rng(2);
  for (int i = 0; i < 2000; ++i) {
    const bool far = i % 2 == 0;
    const Vec3f c = far ? Vec3f(0, 0, -1e4f) : Vec3f(0.3f, 0.1f, -0.2f);
    const float r = far ? 1.0f : 2.0f;
    Ray ray;
    ray.origin = far ? Vec3f(0.0f) : c + 0.5f * random_unit(rng);
    ray.dir = far ? glm::normalize(c + 0.9f * r * random_unit(rng) - ray.origin) : random_unit(rng);
    Hit hit;
    ASSERT_TRUE(intersect(Sphere{c, r}, ray, hit));
    const glm::dvec3 o(ray.origin), d(ray.dir), f = o - glm::dvec3(c);
    const double a = glm::dot(d, d), b = glm::dot(f, d), cc = glm::dot(f, f) - double(r) * r;
    const double disc = b * b - a * cc;
    const double t = (far ? -b - std::sqrt(disc) : -b + std::sqrt(disc)) / a;
    EXPECT_NEAR(hit.t, t, 1e-6 * std::abs(t) + 1e-5);
  }
}

TEST(Shapes, SphereImageAreaMatchesProjectedArea) {
  // A sphere of radius r at distance D on the view axis subtends a cone of half-angle asin(r / D); on the view plane
  // at focal length d its silhouette is a disk of radius d tan(asin(r / D)). The fraction of eye rays that hit is its
  // area over the view plane's 2 aspect x 2.
  Camera cam;
  cam.eye = Vec3(0, 0, 6);
  cam.fovy = radians(40);
  const int w = 600, h = 400;
  cam.aspect = double(w) / h;
  const EyeRays rays(cam, w, h);
  const Sphere s{Vec3f(0.0f), 1.3f};
  long hits = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      Hit hit;
      hits += intersect(s, rays.ray(i, j), hit);
    }
  const double d = rays.focal_length();
  const double rho = d * std::tan(std::asin(1.3 / 6.0));
  const double expected = kPi * rho * rho / (4 * cam.aspect);
  EXPECT_NEAR(double(hits) / (w * h), expected, 0.01 * expected);
}

TEST(Shapes, BoxSurfaceAndNormals) {
  const Vec3f lo(-1, 0, 2), hi(0.5f, 3, 2.5f);
  const Vec3f c = 0.5f * (lo + hi), hh = 0.5f * (hi - lo);
  auto f = [=](const Vec3f& p) {
    const Vec3f q = glm::abs(p - c) - hh;
    return std::max({q.x, q.y, q.z});
  };
  auto grad = [=](const Vec3f& p) {
    const Vec3f q = glm::abs(p - c) - hh;
    const int a = q.x >= q.y && q.x >= q.z ? 0 : (q.y >= q.z ? 1 : 2);
    Vec3f g(0.0f);
    g[a] = p[a] > c[a] ? 1.0f : -1.0f;
    return g;
  };
  check_solid({Box{lo, hi}, f, grad, 3}, 3);
}

TEST(Shapes, CappedCylinderSurfaceAndNormals) {
  const Cylinder cyl{0.7f, -0.5f, 1.5f, true};
  auto f = [=](const Vec3f& p) {
    return std::max({std::sqrt(p.x * p.x + p.z * p.z) - cyl.radius, cyl.y0 - p.y, p.y - cyl.y1});
  };
  auto grad = [=](const Vec3f& p) {
    const float side = std::sqrt(p.x * p.x + p.z * p.z) - cyl.radius, bottom = cyl.y0 - p.y, top = p.y - cyl.y1;
    if (side >= bottom && side >= top) return Vec3f(p.x, 0, p.z);
    return bottom > top ? Vec3f(0, -1, 0) : Vec3f(0, 1, 0);
  };
  check_solid({cyl, f, grad, 2}, 4);
}

TEST(Shapes, NotesConeWithBaseCapSurfaceAndNormals) {
  // The implicit cone sqrt((x-xb)^2 + (z-zb)^2) - k (y - yb) has gradient (x, -k rho, z) / rho: an independent check
  // of the notes' T1 x T2 normal construction.
  const Cone cone{Vec3f(0.5f, -1, 0.2f), 0.8f, 2.0f, true};
  const float k = cone.radius / cone.height;
  auto f = [=](const Vec3f& p) {
    const Vec3f q = p - cone.apex;
    const float rho = std::sqrt(q.x * q.x + q.z * q.z);
    return std::max({(rho - k * q.y) / std::sqrt(1 + k * k), q.y - cone.height, -q.y});
  };
  auto grad = [=](const Vec3f& p) {
    const Vec3f q = p - cone.apex;
    const float rho = std::sqrt(q.x * q.x + q.z * q.z);
    if (q.y - cone.height > (rho - k * q.y) / std::sqrt(1 + k * k)) return Vec3f(0, 1, 0);
    return Vec3f(q.x / rho, -k, q.z / rho);
  };
  check_solid({cone, f, grad, 2}, 5);
}

TEST(Shapes, EllipsoidSurfaceAndNormals) {
  const Vec3f c(0.2f, 0.3f, -0.4f), r(2.0f, 0.5f, 1.0f);
  // Normalized so that f is about a distance near the surface for the tolerance check.
  auto f = [=](const Vec3f& p) { return 0.5f * (glm::length((p - c) / r) - 1.0f); };
  auto grad = [=](const Vec3f& p) { return (p - c) / (r * r); };
  check_solid({Ellipsoid{c, r}, f, grad, 2}, 6);
}

TEST(Shapes, UncappedCylinderIsOpen) {
  // Looking down the axis of an open tube, the ray passes through; a capped one stops at the top cap.
  Ray ray;
  ray.origin = Vec3f(0.1f, 5, 0);
  ray.dir = Vec3f(0, -1, 0);
  Hit hit;
  EXPECT_FALSE(intersect(Cylinder{1, 0, 1, false}, ray, hit));
  ASSERT_TRUE(intersect(Cylinder{1, 0, 1, true}, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 4.0f);
  EXPECT_EQ(hit.normal, Vec3f(0, 1, 0));
  // From the side, the open tube's inside wall reports the outward geometric normal.
  ray.origin = Vec3f(0, 0.5f, 0);
  ray.dir = Vec3f(1, 0, 0);
  ASSERT_TRUE(intersect(Cylinder{1, 0, 1, false}, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 1.0f);
  EXPECT_NEAR(hit.normal.x, 1.0f, 1e-6f);
}

TEST(Shapes, ConeCapNormalIsUpAndApexSideFacesDown) {
  const Cone cone{Vec3f(0.0f), 1.0f, 1.0f, true};
  Hit hit;
  Ray down{Vec3f(0.2f, 3, 0.1f), Vec3f(0, -1, 0)};
  ASSERT_TRUE(intersect(cone, down, hit));
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
  EXPECT_EQ(hit.normal, Vec3f(0, 1, 0));
  // From below, a ray up the x = 0.5 line enters the side at y = 0.5 (45 degree cone) with normal (1, -1, 0)/sqrt 2.
  Ray up{Vec3f(0.5f, -2, 0), Vec3f(0, 1, 0)};
  ASSERT_TRUE(intersect(cone, up, hit));
  EXPECT_NEAR(hit.t, 2.5f, 1e-5f);
  EXPECT_NEAR(hit.normal.x, std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(hit.normal.y, -std::sqrt(0.5f), 1e-5f);
  // Without the cap, a ray down the axis enters nothing until the apex from inside.
  Ray axis{Vec3f(0.3f, 3, 0), Vec3f(0, -1, 0)};
  ASSERT_TRUE(intersect(Cone{Vec3f(0.0f), 1, 1, false}, axis, hit));
  EXPECT_NEAR(hit.t, 2.7f, 1e-5f);  // the inside of the side wall at y = 0.3
}

/// Flat shapes: the hit lies on the plane and inside the shape, and rays to points inside always hit.
TEST(Shapes, PlaneDiskTriangleHitPoints) {
  Rng rng(7);
  const Vec3f n = glm::normalize(Vec3f(0.3f, 1, -0.2f));
  const Vec3f p0(1, 2, 3);
  for (int i = 0; i < 2000; ++i) {
    Ray ray;
    ray.origin = p0 + 4.0f * random_unit(rng);
    const Vec3f target = p0 + 2.0f * random_unit(rng);
    ray.dir = target - ray.origin;
    Hit hit;
    if (intersect(Plane{p0, 3.0f * n}, ray, hit)) {
      EXPECT_NEAR(glm::dot(hit.point - p0, n), 0.0f, 1e-4f);
      EXPECT_NEAR(glm::length(hit.normal - n), 0.0f, 1e-6f);
    } else {
      // A miss: the plane is behind the origin or beyond the ray's end... here tmax is infinite, so behind.
      EXPECT_LE(glm::dot(p0 - ray.origin, n) / glm::dot(ray.dir, n), 0.0f);
    }
    if (intersect(Disk{p0, n, 1.5f}, ray, hit)) {
      EXPECT_NEAR(glm::dot(hit.point - p0, n), 0.0f, 1e-4f);
      EXPECT_LE(glm::length(hit.point - p0), 1.5f + 1e-4f);
      EXPECT_NEAR(hit.uv.x, glm::length(hit.point - p0) / 1.5f, 1e-4f);
    }
    const Triangle tri{Vec3f(0, 0, 0), Vec3f(2, 0.5f, 0), Vec3f(0.5f, 2, 1)};
    Ray tray;
    tray.origin = Vec3f(0.7f, 0.7f, 0.3f) + 3.0f * random_unit(rng);
    const float b1 = rng.uniform(), b2 = rng.uniform() * (1 - b1);
    const Vec3f inside = (1 - b1 - b2) * tri.a + b1 * tri.b + b2 * tri.c;
    tray.dir = inside - tray.origin;
    ASSERT_TRUE(intersect(tri, tray, hit));
    EXPECT_NEAR(hit.t, 1.0f, 1e-4f);
    EXPECT_NEAR(hit.uv.x, b1, 1e-4f);
    EXPECT_NEAR(hit.uv.y, b2, 1e-4f);
  }
}

TEST(Shapes, RayIntervalIsRespected) {
  const Sphere s{Vec3f(0, 0, -5), 1};
  Ray ray;
  Hit hit;
  ray.tmax = 3.9f;
  EXPECT_FALSE(intersect(s, ray, hit));
  ray.tmax = 4.1f;
  ASSERT_TRUE(intersect(s, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 4.0f);
  ray.tmin = 4.5f;  // past the entry: the exit
  ray.tmax = 100;
  ASSERT_TRUE(intersect(s, ray, hit));
  EXPECT_FLOAT_EQ(hit.t, 6.0f);
}

/// A random simple star-shaped polygon (concave in general): n vertices at sorted angles and random radii.
std::vector<Vec2f> star_polygon(Rng& rng, int n) {
  std::vector<float> angles(static_cast<size_t>(n));
  for (float& a : angles) a = float(2 * kPi) * rng.uniform();
  std::sort(angles.begin(), angles.end());
  std::vector<Vec2f> poly;
  for (float a : angles) {
    const float r = 0.2f + rng.uniform();
    poly.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return poly;
}

TEST(Shapes, PointInPolygonTestsAgreeOnConcavePolygons) {
  Rng rng(8);
  int inside = 0, total = 0;
  for (int k = 0; k < 200; ++k) {
    std::vector<Vec2f> poly = star_polygon(rng, 3 + k % 20);
    if (k % 2) std::reverse(poly.begin(), poly.end());  // either orientation
    for (int i = 0; i < 200; ++i) {
      const Vec2f p(2.4f * rng.uniform() - 1.2f, 2.4f * rng.uniform() - 1.2f);
      const bool crossing = point_in_polygon(poly, p, PointInPolygon::crossing);
      ASSERT_EQ(point_in_polygon(poly, p, PointInPolygon::winding), crossing) << "polygon " << k << " point " << i;
      ASSERT_EQ(point_in_polygon(poly, p, PointInPolygon::half_plane), crossing) << "polygon " << k << " point " << i;
      inside += crossing;
      ++total;
    }
  }
  EXPECT_GT(inside, total / 10);
  EXPECT_LT(inside, total * 9 / 10);
}

TEST(Shapes, PointInPolygonHandCases) {
  // An L shape (concave): the notch is outside, both arms inside.
  const std::vector<Vec2f> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (PointInPolygon test : {PointInPolygon::crossing, PointInPolygon::winding, PointInPolygon::half_plane}) {
    EXPECT_TRUE(point_in_polygon(l, {0.2f, 0.7f}, test)) << int(test);
    // Points exactly on the diagonals (0, 0)-(1, 1) and (0, 0)-(1, 2) shared by two of the half-plane test's fan
    // triangles: inside exactly once.
    EXPECT_TRUE(point_in_polygon(l, {0.5f, 0.5f}, test)) << int(test);
    EXPECT_TRUE(point_in_polygon(l, {0.5f, 1.0f}, test)) << int(test);
    EXPECT_TRUE(point_in_polygon(l, {1.5f, 0.4f}, test)) << int(test);
    EXPECT_TRUE(point_in_polygon(l, {0.4f, 1.5f}, test)) << int(test);
    EXPECT_FALSE(point_in_polygon(l, {1.5f, 1.5f}, test)) << int(test);
    EXPECT_FALSE(point_in_polygon(l, {-0.5f, 0.5f}, test)) << int(test);
    // The crossing ray from (0.25, 1) runs along the edge (2, 1)-(1, 1) and through the vertex (1, 1): counted once
    // by the half-open rule.
    EXPECT_TRUE(point_in_polygon(l, {0.25f, 1.0f}, test)) << int(test);
  }
  // A pixel grid over a square whose fan diagonal (-1, -1)-(1, 1) passes through pixel centers: all agree.
  const std::vector<Vec2f> square = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const Vec2f p((float(x) + 0.5f) / 32 - 1, (float(y) + 0.5f) / 32 - 1);
      ASSERT_TRUE(point_in_polygon(square, p, PointInPolygon::half_plane)) << x << "," << y;
      ASSERT_TRUE(point_in_polygon(square, p, PointInPolygon::crossing)) << x << "," << y;
    }
  // A pentagram drawn as a self-intersecting star: the center has winding number 2 (inside by the nonzero rule) but
  // crosses an even number of edges (outside by even-odd): where the rules differ.
  std::vector<Vec2f> star;
  for (int i = 0; i < 5; ++i) {
    const double a = kPi / 2 + i * 4 * kPi / 5;
    star.emplace_back(float(std::cos(a)), float(std::sin(a)));
  }
  EXPECT_TRUE(point_in_polygon(star, {0, 0}, PointInPolygon::winding));
  EXPECT_FALSE(point_in_polygon(star, {0, 0}, PointInPolygon::crossing));
}

TEST(Shapes, PolygonInSpaceMatchesItsTriangles) {
  // A convex polygon in a tilted plane: every ray hits it exactly when it hits one of its fan triangles, at the same
  // t and with the same normal; likewise for all three tests.
  Rng rng(9);
  const Vec3f n = glm::normalize(Vec3f(0.2f, 0.5f, 1.0f));
  Vec3f t1 = glm::normalize(glm::cross(n, Vec3f(1, 0, 0))), t2 = glm::cross(n, t1);
  std::vector<Vec3f> verts;
  for (int i = 0; i < 7; ++i) {
    const float a = float(2 * kPi * i / 7);
    verts.push_back(Vec3f(1, 2, 3) + std::cos(a) * t1 + std::sin(a) * t2);
  }
  int disagree = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray ray;
    ray.origin = Vec3f(1, 2, 3) + 3.0f * random_unit(rng);
    ray.dir = Vec3f(1, 2, 3) + 1.2f * random_unit(rng) - ray.origin;
    Hit tri_hit;
    bool any = false;
    for (size_t k = 1; k + 1 < verts.size(); ++k)
      any |= intersect(Triangle{verts[0], verts[k], verts[k + 1]}, ray, tri_hit);
    for (PointInPolygon test : {PointInPolygon::crossing, PointInPolygon::winding, PointInPolygon::half_plane}) {
      Hit hit;
      const bool poly = intersect(Polygon{verts, test}, ray, hit);
      if (poly != any) {  // only rays within float rounding of an edge may go either way
        ++disagree;
        continue;
      }
      if (poly) {
        EXPECT_NEAR(hit.t, tri_hit.t, 1e-4f);
        EXPECT_NEAR(glm::dot(hit.normal, n), 1.0f, 1e-5f);
      }
    }
  }
  EXPECT_LE(disagree, 3);
}

/// The transform of an instance applied to a test ray's hit, versus the same shape transformed by hand.
TEST(Shapes, InstanceOfSphereUnderScaleIsTheEllipsoid) {
  const Vec3f c(1, -1, 2), radii(2, 0.5f, 1.25f);
  const Mat4 m = glm::scale(glm::translate(Mat4(1), Vec3(c)), Vec3(radii));
  const Instance inst(Sphere{Vec3f(0.0f), 1.0f}, m);
  const Ellipsoid ell{c, radii};
  Rng rng(10);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray ray;
    ray.origin = c + 5.0f * random_unit(rng);
    ray.dir = glm::normalize(c + 2.0f * random_unit(rng) - ray.origin);
    Hit a, b;
    const bool ha = inst.intersect(ray, a), hb = intersect(ell, ray, b);
    ASSERT_EQ(ha, hb) << i;
    if (!ha) continue;
    ++hits;
    EXPECT_NEAR(a.t, b.t, 1e-4f);
    EXPECT_NEAR(glm::length(a.normal - b.normal), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(a.point - b.point), 0.0f, 1e-4f);
    EXPECT_TRUE(inst.bounds().contains(a.point + 0.0f * a.normal) ||
                glm::length(glm::max(inst.bounds().lo - a.point, a.point - inst.bounds().hi)) < 1e-4f);
  }
  EXPECT_GT(hits, 300);
}

TEST(Shapes, InstanceOfTriangleUnderShearAndRotation) {
  // An affine map with rotation, non-uniform scale and shear: the instance's hit equals the hit of the triangle with
  // transformed vertices (same t, same normal: the inverse transpose maps normals to the image's normal).
  Mat4 m = glm::translate(Mat4(1), Vec3(0.5, 1, -2));
  m = glm::rotate(m, 0.7, glm::normalize(Vec3(1, 2, 0.5)));
  m = glm::scale(m, Vec3(2, 0.5, 1.5));
  m[1][0] = 0.4;  // shear x by y
  const Triangle local{Vec3f(-1, -1, 0), Vec3f(1, -1, 0.2f), Vec3f(0, 1, -0.3f)};
  auto apply = [&](const Vec3f& p) { return Vec3f(m * Vec4(Vec3(p), 1.0)); };
  const Triangle world{apply(local.a), apply(local.b), apply(local.c)};
  const Instance inst(local, m);
  Rng rng(11);
  int hits = 0, disagree = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray ray;
    const Vec3f c = (world.a + world.b + world.c) / 3.0f;
    ray.origin = c + 6.0f * random_unit(rng);
    ray.dir = c + 2.0f * random_unit(rng) - ray.origin;
    Hit a, b;
    const bool ha = inst.intersect(ray, a), hb = intersect(world, ray, b);
    if (ha != hb) ++disagree;  // only rays within rounding of an edge
    if (!ha || !hb) continue;
    ++hits;
    EXPECT_NEAR(a.t, b.t, 1e-4f * std::max(1.0f, b.t));
    EXPECT_NEAR(glm::length(a.normal - b.normal), 0.0f, 1e-4f);
    EXPECT_NEAR(a.uv.x, b.uv.x, 1e-4f);
  }
  EXPECT_GT(hits, 100);
  EXPECT_LE(disagree, 3);
}

TEST(Shapes, InstanceBoundsAndErrors) {
  const Mat4 m = glm::rotate(glm::translate(Mat4(1), Vec3(3, 0, 0)), kPi / 4, Vec3(0, 0, 1));
  const AABB b = Instance(Box{Vec3f(-1.0f), Vec3f(1.0f)}, m).bounds();
  EXPECT_NEAR(b.lo.x, 3 - std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(b.hi.y, std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(b.hi.z, 1.0f, 1e-5f);
  EXPECT_FALSE(std::isfinite(Instance(Plane{}, m).bounds().hi.x));
  EXPECT_THROW(Instance(Sphere{}, glm::scale(Mat4(1), Vec3(1, 0, 1))), InvalidInput);
}

TEST(Shapes, BoundsContainTheShapes) {
  const Disk disk{Vec3f(1, 2, 3), Vec3f(1, 1, 0), 2};
  const AABB b = bounds(disk);
  EXPECT_NEAR(b.hi.z, 5.0f, 1e-5f);
  EXPECT_NEAR(b.hi.x, 1 + std::sqrt(2.0f), 1e-5f);
  const AABB cb = bounds(Cone{Vec3f(0, 1, 0), 2, 3, true});
  EXPECT_EQ(cb.lo, Vec3f(-2, 1, -2));
  EXPECT_EQ(cb.hi, Vec3f(2, 4, 2));
  EXPECT_FALSE(std::isfinite(bounds(Shape(Plane{})).lo.x));
}

/// The any-hit test (shadow rays) answers exactly whether intersect finds a hit in [tmin, tmax], for every shape and
/// an instance, with random intervals and origins inside and outside (intersect itself is checked above against the
/// implicit functions).
TEST(Shapes, OccludesAgreesWithIntersect) {
  const std::vector<Shape> shapes = {
      Sphere{Vec3f(0.2f, 0, 0), 1.0f},
      Plane{Vec3f(0, 0.3f, 0), Vec3f(0.2f, 1, 0.1f)},
      Triangle{Vec3f(-1, -1, 0), Vec3f(1, -1, 0.2f), Vec3f(0, 1, -0.1f)},
      Polygon{{Vec3f(-1, 0, -1), Vec3f(1, 0, -1), Vec3f(0.1f, 0, 0), Vec3f(1, 0, 1), Vec3f(-1, 0, 1)}},
      Box{Vec3f(-1, -0.5f, -0.7f), Vec3f(0.8f, 0.9f, 1)},
      Cylinder{0.8f, -1, 1, true},
      Cylinder{0.8f, -1, 1, false},
      Cone{Vec3f(0, -1, 0), 0.9f, 2, true},
      Cone{Vec3f(0, -1, 0), 0.9f, 2, false},
      Disk{Vec3f(0.1f, 0, 0), Vec3f(0.3f, 1, 0.2f), 1},
      Ellipsoid{Vec3f(0), Vec3f(1, 0.5f, 0.8f)},
  };
  const Instance instance(Cone{Vec3f(0, -1, 0), 0.9f, 2, true},
                          glm::rotate(glm::scale(Mat4(1), Vec3(1.5, 0.7, 1)), 0.6, Vec3(1, 1, 0)));
  Rng rng(77);
  for (size_t k = 0; k <= shapes.size(); ++k) {
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
      Ray ray;
      ray.origin = (i % 4 == 0 ? 0.5f : 3.0f) * random_unit(rng);
      ray.dir = random_unit(rng) * (0.5f + rng.uniform());
      ray.tmin = i % 3 == 0 ? 0.0f : 2.0f * rng.uniform();
      ray.tmax = i % 5 == 0 ? std::numeric_limits<float>::infinity() : ray.tmin + 4.0f * rng.uniform();
      Hit hit;
      const bool found = k < shapes.size() ? intersect(shapes[k], ray, hit) : instance.intersect(ray, hit);
      const bool any = k < shapes.size() ? occludes(shapes[k], ray) : instance.occludes(ray);
      ASSERT_EQ(any, found) << "shape " << k << " ray " << i;
      hits += found;
    }
    EXPECT_GT(hits, 500) << "shape " << k;  // both answers are exercised
    EXPECT_LT(hits, 19000) << "shape " << k;
  }
}

}  // namespace
}  // namespace tessera
