#pragma once
// Independent references for the raster2d tests: point-in-polygon at pixel centers and a supersampled coverage, both
// computed directly from the contours (no edge table, no increments), plus random test polygons.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "tessera/raster2d/path.hpp"

namespace tessera::test {

/// Crossing number / winding number of p against every edge, counting an edge when min_y <= p.y < max_y and its
/// intersection is at or left of p.x (the half-open rule: centers on left and top edges are in).
inline bool point_in_path(const Path& path, FillRule rule, const Vec2& p) {
  int winding = 0, crossings = 0;
  for (const auto& c : path.contours) {
    if (c.size() < 3) continue;
    for (size_t i = 0; i < c.size(); ++i) {
      const Vec2 a = c[i], b = c[(i + 1) % c.size()];
      if (a.y == b.y) continue;
      const Vec2 lo = a.y < b.y ? a : b, hi = a.y < b.y ? b : a;
      if (!(lo.y <= p.y && p.y < hi.y)) continue;
      const double x = lo.x + (p.y - lo.y) * (hi.x - lo.x) / (hi.y - lo.y);
      if (x <= p.x) {
        ++crossings;
        winding += a.y < b.y ? 1 : -1;
      }
    }
  }
  return rule == FillRule::non_zero ? winding != 0 : (crossings & 1) != 0;
}

/// The fraction of each pixel's n x n subsample centers inside the path (row-major, width x height). Each subsample
/// row is resolved exactly: its crossings are found, sorted, and the inside intervals count the subsample columns.
inline std::vector<double> supersampled_coverage(const Path& path, FillRule rule, int width, int height, int n) {
  std::vector<double> cov(size_t(width) * size_t(height), 0.0);
  std::vector<std::pair<double, int>> xs;
  for (int sy = 0; sy < height * n; ++sy) {
    const double y = (sy + 0.5) / n;
    xs.clear();
    for (const auto& c : path.contours) {
      if (c.size() < 3) continue;
      for (size_t i = 0; i < c.size(); ++i) {
        const Vec2 a = c[i], b = c[(i + 1) % c.size()];
        if (a.y == b.y) continue;
        const Vec2 lo = a.y < b.y ? a : b, hi = a.y < b.y ? b : a;
        if (!(lo.y <= y && y < hi.y)) continue;
        xs.push_back({lo.x + (y - lo.y) * (hi.x - lo.x) / (hi.y - lo.y), a.y < b.y ? 1 : -1});
      }
    }
    std::sort(xs.begin(), xs.end());
    int winding = 0, crossings = 0;
    for (size_t k = 0; k + 1 < xs.size(); ++k) {
      winding += xs[k].second;
      ++crossings;
      const bool in = rule == FillRule::non_zero ? winding != 0 : (crossings & 1) != 0;
      if (!in) continue;
      // Subsample columns sx with center (sx + 0.5) / n in [xs[k], xs[k + 1]).
      const long s0 = std::max(0L, long(std::ceil(xs[k].first * n - 0.5)));
      const long s1 = std::min(long(width) * n, long(std::ceil(xs[k + 1].first * n - 0.5)));
      for (long sx = s0; sx < s1; ++sx) cov[size_t(sy / n) * size_t(width) + size_t(sx / n)] += 1.0;
    }
  }
  for (double& c : cov) c /= double(n) * n;
  return cov;
}

/// A random star-shaped (generally concave) contour about c with radii in [r_min, r_max], counterclockwise in
/// angle order, reversed when `reverse`.
inline std::vector<Vec2> random_star(std::mt19937& rng, Vec2 c, double r_min, double r_max, int points, bool reverse) {
  std::uniform_real_distribution<double> radius(r_min, r_max), jitter(-0.3, 0.3);
  std::vector<Vec2> poly;
  for (int i = 0; i < points; ++i) {
    const double a = 2 * kPi * (i + 0.5 + jitter(rng)) / points;
    const double r = radius(rng);
    poly.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  }
  if (reverse) std::reverse(poly.begin(), poly.end());
  return poly;
}

/// A concave star about the center of a width x height image with 1-2 star holes of random orientation inside its
/// inner radius (simple contours that do not cross each other).
inline Path random_polygon_with_holes(std::mt19937& rng, int width, int height) {
  const Vec2 c(width * 0.5 + 0.37, height * 0.5 - 0.21);
  const double r = std::min(width, height) * 0.45;
  Path path;
  path.contours.push_back(random_star(rng, c, 0.55 * r, r, 9 + int(rng() % 12), false));
  const int holes = 1 + int(rng() % 2);
  for (int h = 0; h < holes; ++h) {
    const Vec2 hc = c + Vec2(h == 0 ? -0.25 * r : 0.25 * r, 0.03 * r);
    path.contours.push_back(random_star(rng, hc, 0.08 * r, 0.2 * r, 5 + int(rng() % 6), rng() % 2 == 0));
  }
  return path;
}

}  // namespace tessera::test
