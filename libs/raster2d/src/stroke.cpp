// Stroke outlines as a union of convex pieces filled with the nonzero rule: one rectangle per segment, one wedge per
// join on the outer side of the turn (miter, round or bevel), one piece per round cap (square caps lengthen the end
// segments). Every piece is oriented the same way, so their union under nonzero is the stroke, and pieces that meet
// share collinear edges, so antialiased coverage adds up exactly across them.
#include <algorithm>
#include <cmath>

#include "tessera/raster2d/path.hpp"

namespace tessera {
namespace {

// Flattening tolerance of round joins and caps, in path units (device pixels).
constexpr double kArcTolerance = 0.01;

double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

// Twice the signed area (shoelace).
double signed_area2(const std::vector<Vec2>& poly) {
  double s = 0;
  for (size_t i = 0; i < poly.size(); ++i) s += cross(poly[i], poly[(i + 1) % poly.size()]);
  return s;
}

void add_piece(Path& out, std::vector<Vec2> poly) {
  if (poly.size() < 3) return;
  if (signed_area2(poly) < 0) std::reverse(poly.begin(), poly.end());
  out.contours.push_back(std::move(poly));
}

// Points on the circle of radius r about c from angle a0 sweeping by `sweep` (signed), both ends excluded, spaced so
// the chords stay within kArcTolerance of the circle.
void append_arc(std::vector<Vec2>& poly, const Vec2& c, double r, double a0, double sweep) {
  const double step_max = r > kArcTolerance ? 2.0 * std::acos(1.0 - kArcTolerance / r) : kPi / 2;
  const int n = std::max(2, int(std::ceil(std::fabs(sweep) / step_max)));
  for (int i = 1; i < n; ++i) {
    const double a = a0 + sweep * i / n;
    poly.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  }
}

double angle_of(const Vec2& v) { return std::atan2(v.y, v.x); }

// The join at p between unit directions d0 (in) and d1 (out) for half width r.
void add_join(Path& out, const Vec2& p, const Vec2& d0, const Vec2& d1, double r, const StrokeStyle& style) {
  const double turn = cross(d0, d1), along = glm::dot(d0, d1);
  if (std::fabs(turn) < 1e-12 && along > 0) return;  // straight on: the rectangles already meet
  const Vec2 n0(-d0.y, d0.x), n1(-d1.y, d1.x);
  const double side = turn > 0 ? -1.0 : 1.0;  // the outer side of the turn
  const Vec2 a = p + side * r * n0, b = p + side * r * n1;
  if (style.join == LineJoin::round) {
    std::vector<Vec2> poly{p, a};
    double sweep = angle_of(b - p) - angle_of(a - p);
    // Sweep the short way round on the outer side; a reversal sweeps half a turn through the direction d0.
    if (std::fabs(turn) < 1e-12) sweep = -side * kPi;
    while (sweep > kPi) sweep -= 2 * kPi;
    while (sweep < -kPi) sweep += 2 * kPi;
    append_arc(poly, p, r, angle_of(a - p), sweep);
    poly.push_back(b);
    add_piece(out, std::move(poly));
    return;
  }
  if (std::fabs(turn) < 1e-12) return;  // a reversal has no bevel or miter area
  // Miter length / width = 1 / sin(theta / 2) for the angle theta between the segments, = 1 / sqrt((1 + d0.d1) / 2).
  const double ratio = 1.0 / std::sqrt(std::max(1e-300, 0.5 * (1.0 + along)));
  if (style.join == LineJoin::miter && ratio <= style.miter_limit) {
    const Vec2 bisector = glm::normalize(n0 + n1);
    add_piece(out, {p, a, p + side * r * ratio * bisector, b});
  } else {
    add_piece(out, {p, a, b});
  }
}

// A round cap: the half disk beyond `p` in direction d (unit), for half width r.
void add_round_cap(Path& out, const Vec2& p, const Vec2& d, double r) {
  const Vec2 n(-d.y, d.x);
  std::vector<Vec2> poly{p + r * n};
  append_arc(poly, p, r, angle_of(n), -kPi);
  poly.push_back(p - r * n);
  add_piece(out, std::move(poly));
}

}  // namespace

Path stroke_path(const std::vector<Vec2>& polyline, bool closed, const StrokeStyle& style) {
  Path out;
  if (!(style.width > 0) || !std::isfinite(style.width)) return out;
  const double r = 0.5 * style.width;
  std::vector<Vec2> pts;
  for (const Vec2& p : polyline)
    if (std::isfinite(p.x) && std::isfinite(p.y) && (pts.empty() || p != pts.back())) pts.push_back(p);
  if (closed && pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
  if (pts.empty()) return out;
  if (pts.size() == 1) {  // a zero-length subpath: a dot for round and square caps (SVG)
    const Vec2 p = pts[0];
    if (style.cap == LineCap::round) {
      add_round_cap(out, p, Vec2(1, 0), r);
      add_round_cap(out, p, Vec2(-1, 0), r);
    } else if (style.cap == LineCap::square) {
      add_piece(out, {p + Vec2(-r, -r), p + Vec2(r, -r), p + Vec2(r, r), p + Vec2(-r, r)});
    }
    return out;
  }
  closed = closed && pts.size() >= 3;
  const size_t n = pts.size(), segments = closed ? n : n - 1;
  auto direction = [&](size_t i) { return glm::normalize(pts[(i + 1) % n] - pts[i]); };
  for (size_t i = 0; i < segments; ++i) {
    Vec2 a = pts[i], b = pts[(i + 1) % n];
    const Vec2 d = direction(i), normal(-d.y, d.x);
    if (!closed && style.cap == LineCap::square) {
      if (i == 0) a -= r * d;
      if (i + 1 == segments) b += r * d;
    }
    add_piece(out, {a + r * normal, a - r * normal, b - r * normal, b + r * normal});
  }
  for (size_t i = closed ? 0 : 1; i < (closed ? n : n - 1); ++i)
    add_join(out, pts[i], direction((i + n - 1) % n), direction(i), r, style);
  if (!closed && style.cap == LineCap::round) {
    add_round_cap(out, pts[0], -direction(0), r);
    add_round_cap(out, pts[n - 1], direction(n - 2), r);
  }
  return out;
}

}  // namespace tessera
