#pragma once
// Bezier curves of any degree in 2D and 3D (double precision): the notes' "Bezier Curves" and "Polynomial Evaluation".
//
// A curve of degree n has n + 1 control points P_0..P_n (the notes number a cubic's P1..P4) and is
// Q(t) = sum_i B_i^n(t) P_i, t in [0, 1], with the Bernstein polynomials B_i^n(t) = C(n, i) t^i (1 - t)^(n - i).
// The weights are a convex combination, so the curve stays in the control points' convex hull. Every function is
// defined for P = Vec2 and P = Vec3 (explicitly instantiated in bezier.cpp).
#include <array>
#include <span>
#include <utility>
#include <vector>

#include "tessera/curves/convex.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// A Bezier curve: degree() = points.size() - 1. The functions below throw InvalidInput for an empty curve.
template <class P>
struct BezierCurve {
  std::vector<P> points;  ///< control points P_0..P_n

  /// n, one less than the number of control points.
  int degree() const { return int(points.size()) - 1; }
  /// The first and last control points, Q(0) and Q(1). Precondition: not empty.
  const P& front() const { return points.front(); }
  const P& back() const { return points.back(); }
};

using Bezier2 = BezierCurve<Vec2>;
using Bezier3 = BezierCurve<Vec3>;

/// The notes' cubic basis (B1, B2, B3, B4) = ((1-t)^3, 3t(1-t)^2, 3t^2(1-t), t^3); they sum to 1.
std::array<double, 4> cubic_basis(double t);

/// The Bernstein polynomial B_i^n(t) = C(n, i) t^i (1-t)^(n-i). Requires 0 <= i <= n <= 1000, else InvalidInput.
double bernstein(int n, int i, double t);

/// Q(t) by the Bernstein sum (the notes' Q(t) = B1(t) P1 + ... + B4(t) P4 for a cubic). O(n^2) multiplications.
template <class P>
P evaluate_bernstein(const BezierCurve<P>& curve, double t);

/// Q(t) by de Casteljau's repeated linear interpolation (the notes' subdivision at t: midpoints of midpoints at 1/2).
template <class P>
P evaluate_de_casteljau(const BezierCurve<P>& curve, double t);

/// The de Casteljau triangle at t: level 0 is the control polygon, level k has n + 1 - k points, the last level is
/// the single point Q(t). What the notes draw for the construction at t = 1/2 and 3/4.
template <class P>
std::vector<std::vector<P>> de_casteljau_levels(const BezierCurve<P>& curve, double t);

/// Power-basis coefficients a_0..a_n with Q(t) = sum_k a_k t^k (for a cubic: d, c, b, a of the notes'
/// at^3 + bt^2 + ct + d), a_k = C(n, k) sum_i (-1)^(k-i) C(k, i) P_i.
template <class P>
std::vector<P> power_coefficients(const BezierCurve<P>& curve);

/// Evaluates sum_k a_k t^k by Horner's rule ((a_n t + a_{n-1}) t + ...) + a_0: n multiplications and n additions
/// per coordinate (the notes: 3 and 3 for a cubic). Throws InvalidInput for no coefficients.
template <class P>
P evaluate_horner(std::span<const P> coefficients, double t);

/// Q(t) by Horner's rule on power_coefficients(curve) (converts on every call; keep the coefficients for loops).
template <class P>
P evaluate_horner(const BezierCurve<P>& curve, double t);

/// Q(i / steps) for i = 0..steps by forward differences (the notes' finite-difference method): after an O(n^2)
/// start, each step costs n additions per coordinate and no multiplication (3 for a cubic). Rounding error grows with
/// the step count (about steps^n ulps of the coordinates in the worst case, see docs/curves.md). Requires steps >= 1.
template <class P>
std::vector<P> evaluate_forward_differences(const BezierCurve<P>& curve, int steps);

/// The starting forward differences [f(0), Δf(0), Δ²f(0), ..., Δⁿf(0)] for step h (for a cubic a t^3 + ... + d:
/// d, ah^3 + bh^2 + ch, 6ah^3 + 2bh^2, 6ah^3). Requires h > 0.
template <class P>
std::vector<P> forward_difference_start(const BezierCurve<P>& curve, double h);

/// Splits the curve at t in (0, 1) into the curves over [0, t] and [t, 1], whose control points are the two outer
/// edges of the de Casteljau triangle (the notes' subdivision). Throws InvalidInput for t outside [0, 1].
template <class P>
std::pair<BezierCurve<P>, BezierCurve<P>> split(const BezierCurve<P>& curve, double t);

/// The same curve with degree n + 1: Q_i = (i/(n+1)) P_{i-1} + (1 - i/(n+1)) P_i.
template <class P>
BezierCurve<P> elevate_degree(const BezierCurve<P>& curve);

/// The hodograph Q'(t), a Bezier curve of degree n - 1 with control points n (P_{i+1} - P_i). A degree-0 curve has
/// the zero curve (one zero point) as derivative.
template <class P>
BezierCurve<P> derivative(const BezierCurve<P>& curve);

/// The unit tangent at t. Where Q'(t) vanishes (coincident control points at an end) the first non-zero higher
/// derivative gives the direction, which is the limit of the tangent. Returns zero only for a constant curve.
template <class P>
P unit_tangent(const BezierCurve<P>& curve, double t);

/// Appends points approximating the curve to `out`, excluding P_0 and including P_n, so that every point of the curve
/// lies within `tolerance` of the polyline: recursive split at 1/2 until the interior control points are within the
/// tolerance of the chord (convex-hull bound), depth-limited to 16. Tolerance is clamped to >= 1e-9.
template <class P>
void flatten(const BezierCurve<P>& curve, double tolerance, std::vector<P>& out);

/// A quadratic Bezier (the notes' three-point curve) as a BezierCurve.
template <class P>
BezierCurve<P> quadratic(const P& p0, const P& p1, const P& p2);
/// A cubic Bezier from the notes' P1..P4.
template <class P>
BezierCurve<P> cubic(const P& p1, const P& p2, const P& p3, const P& p4);

/// How smoothly two consecutive curves join (each level implies the ones before it).
enum class Continuity {
  none,  ///< the end of the first is not the start of the second
  c0,    ///< positions meet
  g1,    ///< and the end tangents point the same way
  c1,    ///< and the end derivatives are equal: n(P_n - P_{n-1}) = m(Q_1 - Q_0)
};

/// The continuity at the joint a(1) = b(0), within `tolerance` (absolute, on positions and derivatives; G1 compares
/// unit tangents). Source: the notes' chaining of cubics by sharing the endpoint.
template <class P>
Continuity joint_continuity(const BezierCurve<P>& a, const BezierCurve<P>& b, double tolerance = 1e-9);

/// The weakest joint continuity of a chain (C1 for fewer than two curves).
template <class P>
Continuity chain_continuity(std::span<const BezierCurve<P>> chain, double tolerance = 1e-9);

/// The cubic that continues `previous` with C1 continuity and ends with control points p3, p4: its first two control
/// points are previous's last point and the reflection 2 P_n - P_{n-1} scaled by the degree ratio. Requires a
/// previous curve of degree >= 1.
template <class P>
BezierCurve<P> c1_continuation(const BezierCurve<P>& previous, const P& p3, const P& p4);

/// The cubic that continues `previous` with G1 continuity: the second control point lies on the previous end tangent
/// at distance `length` from the joint (length > 0). Throws InvalidInput when previous's end tangent is zero.
template <class P>
BezierCurve<P> g1_continuation(const BezierCurve<P>& previous, double length, const P& p3, const P& p4);

}  // namespace tessera
