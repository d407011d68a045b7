#include "tessera/curves/convex.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

template <class P>
P combine_impl(std::span<const P> points, std::span<const double> weights) {
  if (points.empty() || points.size() != weights.size())
    throw InvalidInput(
        fmt::format("combine: {} points and {} weights (need the same, at least one)", points.size(), weights.size()));
  P sum(0.0);
  for (size_t i = 0; i < points.size(); ++i) sum += weights[i] * points[i];
  return sum;
}

template <class P>
double distance_to_segment_impl(const P& p, const P& a, const P& b) {
  const P ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

}  // namespace

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) { return distance_to_segment_impl(p, a, b); }
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) { return distance_to_segment_impl(p, a, b); }

Vec2 combine(std::span<const Vec2> points, std::span<const double> weights) { return combine_impl(points, weights); }
Vec3 combine(std::span<const Vec3> points, std::span<const double> weights) { return combine_impl(points, weights); }

bool is_convex_combination(std::span<const double> weights, double tolerance) {
  double sum = 0;
  for (const double w : weights) {
    if (w < -tolerance) return false;
    sum += w;
  }
  return !weights.empty() && std::abs(sum - 1.0) <= tolerance;
}

double signed_area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

std::array<double, 3> barycentric(const Vec2& q, const Vec2& p1, const Vec2& p2, const Vec2& p3) {
  const double area = signed_area2(p1, p2, p3);
  if (area == 0.0 || !std::isfinite(area)) throw InvalidInput("barycentric: the triangle has zero area");
  // a_i is the area of the triangle formed by q and the edge opposite p_i.
  return {signed_area2(q, p2, p3) / area, signed_area2(p1, q, p3) / area, signed_area2(p1, p2, q) / area};
}

std::array<double, 3> barycentric(const Vec3& q, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const Vec3 n = glm::cross(p2 - p1, p3 - p1);
  const double area = glm::dot(n, n);  // |n|^2: signed areas below are projected on n, so they share the factor |n|
  if (area == 0.0 || !std::isfinite(area)) throw InvalidInput("barycentric: the triangle has zero area");
  return {glm::dot(glm::cross(p2 - q, p3 - q), n) / area, glm::dot(glm::cross(p3 - q, p1 - q), n) / area,
          glm::dot(glm::cross(p1 - q, p2 - q), n) / area};
}

std::vector<Vec2> convex_hull(std::span<const Vec2> points) {
  std::vector<Vec2> sorted(points.begin(), points.end());
  std::sort(sorted.begin(), sorted.end(),
            [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  if (sorted.size() < 3) return sorted;
  std::vector<Vec2> hull(2 * sorted.size());
  size_t k = 0;
  for (const Vec2& p : sorted) {  // lower chain
    while (k >= 2 && signed_area2(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (size_t i = sorted.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && signed_area2(hull[k - 2], hull[k - 1], sorted[i]) <= 0) --k;
    hull[k++] = sorted[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

bool in_convex_hull(const Vec2& q, std::span<const Vec2> points, double tolerance) {
  const std::vector<Vec2> hull = convex_hull(points);
  if (hull.empty()) return false;
  if (hull.size() == 1) return glm::length(q - hull[0]) <= tolerance;
  if (hull.size() == 2) return distance_to_segment(q, hull[0], hull[1]) <= tolerance;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Vec2& a = hull[i];
    const Vec2& b = hull[(i + 1) % hull.size()];
    // Signed distance of q from the edge's line, positive on the inner (left) side.
    if (signed_area2(a, b, q) / glm::length(b - a) < -tolerance) return false;
  }
  return true;
}

}  // namespace tessera
