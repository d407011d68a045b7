#include "tessera/fractal/self_similar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

void check_depth(int depth, int max_depth, const char* what) {
  if (depth < 0 || depth > max_depth)
    throw InvalidInput(fmt::format("{} depth must be in [0, {}], got {}", what, max_depth, depth));
}

int64_t power(int64_t base, int exponent) {
  int64_t p = 1;
  for (int i = 0; i < exponent; ++i) p *= base;
  return p;
}

/// Left ends of the depth-n Cantor intervals in units of 3^-n: every number whose n base-3 digits avoid 1.
std::vector<int64_t> cantor_starts(int depth) {
  std::vector<int64_t> starts{0};
  for (int level = 0; level < depth; ++level) {
    std::vector<int64_t> next;
    next.reserve(starts.size() * 2);
    for (int64_t s : starts) next.push_back(3 * s), next.push_back(3 * s + 2);
    starts = std::move(next);
  }
  return starts;
}

void koch_segment(Vec2 p, Vec2 q, int depth, std::vector<Vec2>& out) {
  if (depth == 0) {
    out.push_back(q);
    return;
  }
  const Vec2 d = (q - p) / 3.0;
  const Vec2 a = p + d, b = p + 2.0 * d;
  // The apex: d turned 60 degrees counterclockwise (to the left of p -> q).
  const double c = 0.5, s = std::sqrt(3.0) / 2.0;
  const Vec2 apex = a + Vec2(c * d.x - s * d.y, s * d.x + c * d.y);
  koch_segment(p, a, depth - 1, out);
  koch_segment(a, apex, depth - 1, out);
  koch_segment(apex, b, depth - 1, out);
  koch_segment(b, q, depth - 1, out);
}

void sierpinski_split(const Triangle2& t, int depth, std::vector<Triangle2>& out) {
  if (depth == 0) {
    out.push_back(t);
    return;
  }
  const Vec2 ab = 0.5 * (t.a + t.b), bc = 0.5 * (t.b + t.c), ca = 0.5 * (t.c + t.a);
  sierpinski_split({t.a, ab, ca}, depth - 1, out);
  sierpinski_split({ab, t.b, bc}, depth - 1, out);
  sierpinski_split({ca, bc, t.c}, depth - 1, out);
}

}  // namespace

std::vector<Interval> cantor_set(int depth) {
  check_depth(depth, 20, "Cantor set");
  const double unit = double(power(3, depth));
  std::vector<Interval> out;
  for (int64_t s : cantor_starts(depth)) out.push_back({double(s) / unit, double(s + 1) / unit});
  return out;
}

std::vector<Rect> cantor_dust(int depth) {
  check_depth(depth, 10, "Cantor dust");
  const std::vector<Interval> line = cantor_set(depth);
  std::vector<Rect> out;
  out.reserve(line.size() * line.size());
  for (const Interval& y : line)
    for (const Interval& x : line) out.push_back({x.a, y.a, x.b - x.a, y.b - y.a});
  return out;
}

std::vector<Rect> sierpinski_carpet(int depth) {
  check_depth(depth, 7, "Sierpinski carpet");
  // Cells (i, j) of the 3^n grid; a cell stays iff no base-3 digit position has 1 in both i and j.
  std::vector<std::pair<int64_t, int64_t>> cells{{0, 0}};
  for (int level = 0; level < depth; ++level) {
    std::vector<std::pair<int64_t, int64_t>> next;
    next.reserve(cells.size() * 8);
    for (const auto& [i, j] : cells)
      for (int dj = 0; dj < 3; ++dj)
        for (int di = 0; di < 3; ++di)
          if (di != 1 || dj != 1) next.emplace_back(3 * i + di, 3 * j + dj);
    cells = std::move(next);
  }
  const double unit = double(power(3, depth));
  std::vector<Rect> out;
  out.reserve(cells.size());
  for (const auto& [i, j] : cells) out.push_back({double(i) / unit, double(j) / unit, 1.0 / unit, 1.0 / unit});
  return out;
}

std::vector<Triangle2> sierpinski_triangle(int depth) {
  check_depth(depth, 12, "Sierpinski triangle");
  std::vector<Triangle2> out;
  out.reserve(size_t(power(3, depth)));
  sierpinski_split({{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2.0}}, depth, out);
  return out;
}

std::vector<Vec2> koch_curve(int depth, Vec2 a, Vec2 b) {
  check_depth(depth, 10, "Koch curve");
  std::vector<Vec2> out{a};
  out.reserve(size_t(power(4, depth)) + 1);
  koch_segment(a, b, depth, out);
  return out;
}

std::vector<Vec2> koch_snowflake(int depth) {
  check_depth(depth, 10, "Koch snowflake");
  const double r = 1.0 / std::sqrt(3.0);  // circumradius of the unit-side triangle
  const Vec2 top{0.5, 0.5 + r}, left{0.0, 0.5 - 0.5 * r}, right{1.0, 0.5 - 0.5 * r};
  // Walk the triangle clockwise so that the bumps (left of each edge) point outwards, then reverse to counterclockwise.
  std::vector<Vec2> out;
  for (const auto& [p, q] : {std::pair{top, right}, std::pair{right, left}, std::pair{left, top}}) {
    const std::vector<Vec2> side = koch_curve(depth, p, q);
    out.insert(out.end(), side.begin(), side.end() - 1);
  }
  std::reverse(out.begin(), out.end());
  return out;
}

std::vector<Vec2> hilbert_curve(int depth) {
  check_depth(depth, 10, "Hilbert curve");
  const int64_t n = power(2, depth);
  std::vector<Vec2> out;
  out.reserve(size_t(n * n));
  for (int64_t d = 0; d < n * n; ++d) {
    // The classic index-to-cell conversion: two bits of d per level, rotating the quadrant as needed.
    int64_t x = 0, y = 0, t = d;
    for (int64_t s = 1; s < n; s *= 2) {
      const int64_t rx = 1 & (t / 2), ry = 1 & (t ^ rx);
      if (ry == 0) {
        if (rx == 1) x = s - 1 - x, y = s - 1 - y;
        std::swap(x, y);
      }
      x += s * rx, y += s * ry;
      t /= 4;
    }
    out.push_back({(double(x) + 0.5) / double(n), (double(y) + 0.5) / double(n)});
  }
  return out;
}

std::vector<Vec2> peano_curve(int depth) {
  check_depth(depth, 7, "Peano curve");
  const int64_t n = power(3, depth);
  std::vector<Vec2> out;
  out.reserve(size_t(n * n));
  std::vector<int> digits(size_t(2 * depth));
  for (int64_t d = 0; d < n * n; ++d) {
    // Base-3 digits of d, most significant first: a1 b1 a2 b2 ... (a: column digits, b: row digits). A column digit
    // is mirrored when the row digits before it sum to an odd number, a row digit when the column digits up to and
    // including its own level do: the serpentine up-down-up of the notes at every level.
    int64_t t = d;
    for (int k = 2 * depth - 1; k >= 0; --k) digits[size_t(k)] = int(t % 3), t /= 3;
    int64_t x = 0, y = 0;
    int sum_a = 0, sum_b = 0;
    for (int level = 0; level < depth; ++level) {
      const int a = digits[size_t(2 * level)], b = digits[size_t(2 * level + 1)];
      sum_a += a;
      x = 3 * x + (sum_b % 2 ? 2 - a : a);
      y = 3 * y + (sum_a % 2 ? 2 - b : b);
      sum_b += b;
    }
    out.push_back({(double(x) + 0.5) / double(n), (double(y) + 0.5) / double(n)});
  }
  return out;
}

double polyline_length(const std::vector<Vec2>& points) {
  double length = 0;
  for (size_t i = 1; i < points.size(); ++i) length += glm::distance(points[i - 1], points[i]);
  return length;
}

double polygon_area(const std::vector<Vec2>& polygon) {
  double twice = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& p = polygon[i];
    const Vec2& q = polygon[(i + 1) % polygon.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return 0.5 * twice;
}

double cantor_measure(int depth) { return std::pow(2.0 / 3.0, depth); }
double carpet_area(int depth) { return std::pow(8.0 / 9.0, depth); }
double sierpinski_triangle_fraction(int depth) { return std::pow(0.75, depth); }
double koch_length(int depth) { return std::pow(4.0 / 3.0, depth); }
double snowflake_area_ratio(int depth) { return 1.0 + 0.6 * (1.0 - std::pow(4.0 / 9.0, depth)); }

double similarity_dimension(double copies, double scale) {
  if (!(copies >= 1) || !(scale > 1) || !std::isfinite(copies) || !std::isfinite(scale))
    throw InvalidInput(
        fmt::format("similarity dimension needs copies >= 1 and scale > 1, got {} and {}", copies, scale));
  return std::log(copies) / std::log(scale);
}

}  // namespace tessera
