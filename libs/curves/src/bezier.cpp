#include "tessera/curves/bezier.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

template <class P>
void require_points(const BezierCurve<P>& curve, const char* what) {
  if (curve.points.empty()) throw InvalidInput(fmt::format("{}: the Bezier curve has no control points", what));
}

// C(n, k) in double (exact up to n = 56, within rounding beyond).
double binomial(int n, int k) {
  k = std::min(k, n - k);
  double c = 1;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

// The largest control-point norm: the scale that "zero" is relative to.
template <class P>
double max_norm(const std::vector<P>& points) {
  double m = 0;
  for (const P& p : points) m = std::max(m, glm::length(p));
  return m;
}

template <class P>
void flatten_recursive(const BezierCurve<P>& curve, double tolerance, int depth, std::vector<P>& out) {
  // The curve lies in the convex hull of its control points, so it is within this bound of the chord.
  double flatness = 0;
  for (size_t i = 1; i + 1 < curve.points.size(); ++i)
    flatness = std::max(flatness, distance_to_segment(curve.points[i], curve.front(), curve.back()));
  if (flatness <= tolerance || depth >= 16) {
    out.push_back(curve.back());
    return;
  }
  const auto [left, right] = split(curve, 0.5);
  flatten_recursive(left, tolerance, depth + 1, out);
  flatten_recursive(right, tolerance, depth + 1, out);
}

}  // namespace

std::array<double, 4> cubic_basis(double t) {
  const double s = 1 - t;
  return {s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
}

double bernstein(int n, int i, double t) {
  if (n < 0 || n > 1000 || i < 0 || i > n)
    throw InvalidInput(fmt::format("bernstein: need 0 <= i <= n <= 1000, got n = {}, i = {}", n, i));
  return binomial(n, i) * std::pow(t, i) * std::pow(1 - t, n - i);
}

template <class P>
P evaluate_bernstein(const BezierCurve<P>& curve, double t) {
  require_points(curve, "evaluate_bernstein");
  const int n = curve.degree();
  P q(0.0);
  if (n == 3) {  // the notes' B1..B4
    const auto b = cubic_basis(t);
    for (int i = 0; i < 4; ++i) q += b[i] * curve.points[i];
    return q;
  }
  for (int i = 0; i <= n; ++i) q += bernstein(n, i, t) * curve.points[i];
  return q;
}

template <class P>
P evaluate_de_casteljau(const BezierCurve<P>& curve, double t) {
  require_points(curve, "evaluate_de_casteljau");
  std::vector<P> b = curve.points;
  for (size_t level = b.size() - 1; level > 0; --level)
    for (size_t i = 0; i < level; ++i) b[i] = (1 - t) * b[i] + t * b[i + 1];
  return b[0];
}

template <class P>
std::vector<std::vector<P>> de_casteljau_levels(const BezierCurve<P>& curve, double t) {
  require_points(curve, "de_casteljau_levels");
  std::vector<std::vector<P>> levels{curve.points};
  while (levels.back().size() > 1) {
    const std::vector<P>& prev = levels.back();
    std::vector<P> next(prev.size() - 1);
    for (size_t i = 0; i < next.size(); ++i) next[i] = (1 - t) * prev[i] + t * prev[i + 1];
    levels.push_back(std::move(next));
  }
  return levels;
}

template <class P>
std::vector<P> power_coefficients(const BezierCurve<P>& curve) {
  require_points(curve, "power_coefficients");
  const int n = curve.degree();
  std::vector<P> a(n + 1, P(0.0));
  for (int k = 0; k <= n; ++k) {
    P sum(0.0);
    for (int i = 0; i <= k; ++i) sum += (((k - i) % 2 == 0) ? 1.0 : -1.0) * binomial(k, i) * curve.points[i];
    a[k] = binomial(n, k) * sum;
  }
  return a;
}

template <class P>
P evaluate_horner(std::span<const P> coefficients, double t) {
  if (coefficients.empty()) throw InvalidInput("evaluate_horner: no coefficients");
  P q = coefficients.back();
  for (size_t k = coefficients.size() - 1; k-- > 0;) q = q * t + coefficients[k];
  return q;
}

template <class P>
P evaluate_horner(const BezierCurve<P>& curve, double t) {
  const std::vector<P> a = power_coefficients(curve);
  return evaluate_horner(std::span<const P>(a), t);
}

template <class P>
std::vector<P> forward_difference_start(const BezierCurve<P>& curve, double h) {
  if (!(h > 0)) throw InvalidInput(fmt::format("forward_difference_start: step {} is not positive", h));
  const std::vector<P> a = power_coefficients(curve);
  const int n = curve.degree();
  // Δ^k t^j at t = 0 with step h is h^j k! S(j, k) (S: Stirling numbers of the second kind), so
  // Δ^k f(0) = k! sum_{j >= k} S(j, k) a_j h^j. For a cubic: Δ = ah^3 + bh^2 + ch, Δ² = 6ah^3 + 2bh^2, Δ³ = 6ah^3.
  std::vector<std::vector<double>> stirling(n + 1, std::vector<double>(n + 1, 0.0));
  stirling[0][0] = 1;
  for (int j = 1; j <= n; ++j)
    for (int k = 1; k <= j; ++k) stirling[j][k] = k * stirling[j - 1][k] + stirling[j - 1][k - 1];
  std::vector<P> d(n + 1, P(0.0));
  d[0] = a[0];
  double factorial = 1;
  for (int k = 1; k <= n; ++k) {
    factorial *= k;
    P sum(0.0);
    for (int j = k; j <= n; ++j) sum += (stirling[j][k] * std::pow(h, j)) * a[j];
    d[k] = factorial * sum;
  }
  return d;
}

template <class P>
std::vector<P> evaluate_forward_differences(const BezierCurve<P>& curve, int steps) {
  require_points(curve, "evaluate_forward_differences");
  if (steps < 1) throw InvalidInput(fmt::format("evaluate_forward_differences: steps = {} (need >= 1)", steps));
  std::vector<P> d = forward_difference_start(curve, 1.0 / steps);
  std::vector<P> out;
  out.reserve(size_t(steps) + 1);
  out.push_back(d[0]);
  for (int s = 0; s < steps; ++s) {
    for (size_t k = 0; k + 1 < d.size(); ++k) d[k] += d[k + 1];  // n additions, no multiplication
    out.push_back(d[0]);
  }
  return out;
}

template <class P>
std::pair<BezierCurve<P>, BezierCurve<P>> split(const BezierCurve<P>& curve, double t) {
  require_points(curve, "split");
  if (!(t >= 0 && t <= 1)) throw InvalidInput(fmt::format("split: t = {} is outside [0, 1]", t));
  const size_t n = curve.points.size() - 1;
  std::vector<P> work = curve.points;
  BezierCurve<P> left{std::vector<P>(n + 1)}, right{std::vector<P>(n + 1)};
  left.points[0] = work[0];
  right.points[n] = work[n];
  for (size_t level = 1; level <= n; ++level) {
    for (size_t i = 0; i + level <= n; ++i) work[i] = (1 - t) * work[i] + t * work[i + 1];
    left.points[level] = work[0];
    right.points[n - level] = work[n - level];
  }
  return {std::move(left), std::move(right)};
}

template <class P>
BezierCurve<P> elevate_degree(const BezierCurve<P>& curve) {
  require_points(curve, "elevate_degree");
  const size_t n = curve.points.size() - 1;
  BezierCurve<P> out{std::vector<P>(n + 2)};
  out.points[0] = curve.points[0];
  out.points[n + 1] = curve.points[n];
  for (size_t i = 1; i <= n; ++i) {
    const double a = double(i) / double(n + 1);
    out.points[i] = a * curve.points[i - 1] + (1 - a) * curve.points[i];
  }
  return out;
}

template <class P>
BezierCurve<P> derivative(const BezierCurve<P>& curve) {
  require_points(curve, "derivative");
  const int n = curve.degree();
  if (n == 0) return BezierCurve<P>{{P(0.0)}};
  BezierCurve<P> out{std::vector<P>(size_t(n))};
  for (int i = 0; i < n; ++i) out.points[i] = double(n) * (curve.points[i + 1] - curve.points[i]);
  return out;
}

template <class P>
P unit_tangent(const BezierCurve<P>& curve, double t) {
  BezierCurve<P> d = derivative(curve);
  // Near a zero of Q' the direction of motion is that of the first non-zero derivative Q^(k), with sign
  // (t - t0)^(k-1): approaching t0 = 1 from below flips it for even k.
  for (int k = 1; k <= curve.degree(); ++k) {
    const double scale = max_norm(d.points);
    if (scale == 0) break;
    const P v = evaluate_de_casteljau(d, t);
    const double len = glm::length(v);
    if (len > 1e-12 * scale) return ((t >= 1 && k % 2 == 0) ? -1.0 : 1.0) * (v / len);
    d = derivative(d);
  }
  return P(0.0);
}

template <class P>
void flatten(const BezierCurve<P>& curve, double tolerance, std::vector<P>& out) {
  require_points(curve, "flatten");
  flatten_recursive(curve, std::max(tolerance, 1e-9), 0, out);
}

template <class P>
BezierCurve<P> quadratic(const P& p0, const P& p1, const P& p2) {
  return BezierCurve<P>{{p0, p1, p2}};
}

template <class P>
BezierCurve<P> cubic(const P& p1, const P& p2, const P& p3, const P& p4) {
  return BezierCurve<P>{{p1, p2, p3, p4}};
}

template <class P>
Continuity joint_continuity(const BezierCurve<P>& a, const BezierCurve<P>& b, double tolerance) {
  require_points(a, "joint_continuity");
  require_points(b, "joint_continuity");
  if (glm::length(a.back() - b.front()) > tolerance) return Continuity::none;
  const BezierCurve<P> da = derivative(a), db = derivative(b);
  if (glm::length(da.back() - db.front()) <= tolerance) return Continuity::c1;
  const P ta = unit_tangent(a, 1.0), tb = unit_tangent(b, 0.0);
  const bool both = glm::length(ta) > 0 && glm::length(tb) > 0;
  return both && glm::length(ta - tb) <= tolerance ? Continuity::g1 : Continuity::c0;
}

template <class P>
Continuity chain_continuity(std::span<const BezierCurve<P>> chain, double tolerance) {
  Continuity weakest = Continuity::c1;
  for (size_t i = 1; i < chain.size(); ++i)
    weakest = std::min(weakest, joint_continuity(chain[i - 1], chain[i], tolerance));
  return weakest;
}

template <class P>
BezierCurve<P> c1_continuation(const BezierCurve<P>& previous, const P& p3, const P& p4) {
  require_points(previous, "c1_continuation");
  if (previous.degree() < 1) throw InvalidInput("c1_continuation: the previous curve has degree 0");
  const P joint = previous.back();
  // Equal derivatives: n (P_n - P_{n-1}) = 3 (Q_1 - Q_0).
  const P q1 = joint + (double(previous.degree()) / 3.0) * (joint - previous.points[previous.points.size() - 2]);
  return cubic(joint, q1, p3, p4);
}

template <class P>
BezierCurve<P> g1_continuation(const BezierCurve<P>& previous, double length, const P& p3, const P& p4) {
  if (!(length > 0)) throw InvalidInput(fmt::format("g1_continuation: length {} is not positive", length));
  const P direction = unit_tangent(previous, 1.0);
  if (glm::length(direction) == 0) throw InvalidInput("g1_continuation: the previous curve has no end tangent");
  return cubic(previous.back(), previous.back() + length * direction, p3, p4);
}

#define TESSERA_BEZIER_INSTANTIATE(P)                                                         \
  template P evaluate_bernstein(const BezierCurve<P>&, double);                               \
  template P evaluate_de_casteljau(const BezierCurve<P>&, double);                            \
  template std::vector<std::vector<P>> de_casteljau_levels(const BezierCurve<P>&, double);    \
  template std::vector<P> power_coefficients(const BezierCurve<P>&);                          \
  template P evaluate_horner(std::span<const P>, double);                                     \
  template P evaluate_horner(const BezierCurve<P>&, double);                                  \
  template std::vector<P> evaluate_forward_differences(const BezierCurve<P>&, int);           \
  template std::vector<P> forward_difference_start(const BezierCurve<P>&, double);            \
  template std::pair<BezierCurve<P>, BezierCurve<P>> split(const BezierCurve<P>&, double);    \
  template BezierCurve<P> elevate_degree(const BezierCurve<P>&);                              \
  template BezierCurve<P> derivative(const BezierCurve<P>&);                                  \
  template P unit_tangent(const BezierCurve<P>&, double);                                     \
  template void flatten(const BezierCurve<P>&, double, std::vector<P>&);                      \
  template BezierCurve<P> quadratic(const P&, const P&, const P&);                            \
  template BezierCurve<P> cubic(const P&, const P&, const P&, const P&);                      \
  template Continuity joint_continuity(const BezierCurve<P>&, const BezierCurve<P>&, double); \
  template Continuity chain_continuity(std::span<const BezierCurve<P>>, double);              \
  template BezierCurve<P> c1_continuation(const BezierCurve<P>&, const P&, const P&);         \
  template BezierCurve<P> g1_continuation(const BezierCurve<P>&, double, const P&, const P&);

TESSERA_BEZIER_INSTANTIATE(Vec2)
TESSERA_BEZIER_INSTANTIATE(Vec3)
#undef TESSERA_BEZIER_INSTANTIATE

}  // namespace tessera
