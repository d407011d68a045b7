#include "tessera/curves/flatten.hpp"

#include <algorithm>
#include <cmath>

namespace tessera {
namespace {

// Distance from p to the segment a-b.
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

void subdivide(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double tolerance, int depth,
               std::vector<Vec2>& out) {
  // The curve lies in the convex hull of its control points, so it is within this bound of the chord.
  const double flatness = std::max(distance_to_segment(p1, p0, p3), distance_to_segment(p2, p0, p3));
  if (flatness <= tolerance || depth >= 16) {
    out.push_back(p3);
    return;
  }
  // de Casteljau at t = 1/2: the midpoints of the midpoints are the two halves' control points.
  const Vec2 p01 = 0.5 * (p0 + p1), p12 = 0.5 * (p1 + p2), p23 = 0.5 * (p2 + p3);
  const Vec2 p012 = 0.5 * (p01 + p12), p123 = 0.5 * (p12 + p23);
  const Vec2 mid = 0.5 * (p012 + p123);
  subdivide(p0, p01, p012, mid, tolerance, depth + 1, out);
  subdivide(mid, p123, p23, p3, tolerance, depth + 1, out);
}

}  // namespace

void flatten_cubic(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double tolerance,
                   std::vector<Vec2>& out) {
  subdivide(p0, p1, p2, p3, std::max(tolerance, 1e-9), 0, out);
}

void flatten_quadratic(const Vec2& p0, const Vec2& p1, const Vec2& p2, double tolerance, std::vector<Vec2>& out) {
  flatten_cubic(p0, p0 + (2.0 / 3.0) * (p1 - p0), p2 + (2.0 / 3.0) * (p1 - p2), p2, tolerance, out);
}

}  // namespace tessera
