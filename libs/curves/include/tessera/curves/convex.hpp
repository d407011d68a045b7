#pragma once
// Convex combinations, barycentric coordinates by areas, and 2D convex hulls (the notes' "Convex Hull" section).
//
// A convex combination sum w_i p_i has weights w_i >= 0 summing to 1; the set of all of them is the convex hull of the
// p_i. For a triangle the weights of a point are its barycentric coordinates, w_i = a_i / A with a_i the area of the
// sub-triangle opposite p_i.
#include <array>
#include <span>
#include <vector>

#include "tessera/math/types.hpp"

namespace tessera {

/// sum w_i p_i. Throws InvalidInput when the spans differ in size or are empty; does not require convex weights.
/// Source: the notes' convex combination.
Vec2 combine(std::span<const Vec2> points, std::span<const double> weights);
Vec3 combine(std::span<const Vec3> points, std::span<const double> weights);

/// True when the weights are a convex combination: all >= -tolerance and their sum within tolerance of 1.
bool is_convex_combination(std::span<const double> weights, double tolerance = 1e-12);

/// Barycentric coordinates (w1, w2, w3) of q in triangle p1 p2 p3 by signed areas, w_i = a_i / A (the notes), so
/// w1 p1 + w2 p2 + w3 p3 = q and w1 + w2 + w3 = 1. Throws InvalidInput for a degenerate (zero-area) triangle.
std::array<double, 3> barycentric(const Vec2& q, const Vec2& p1, const Vec2& p2, const Vec2& p3);
/// The same in 3D for q in the triangle's plane (q is projected onto it first); areas are |cross| / 2.
std::array<double, 3> barycentric(const Vec3& q, const Vec3& p1, const Vec3& p2, const Vec3& p3);

/// The distance from p to the segment a-b (to a when a = b).
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b);
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b);

/// Twice the signed area of triangle a b c: positive when counterclockwise in a y-up frame.
double signed_area2(const Vec2& a, const Vec2& b, const Vec2& c);

/// The convex hull of a 2D point set, counterclockwise (y up) without collinear points, starting at the lowest-x
/// point (Andrew's monotone chain, O(n log n)). Fewer than 3 distinct non-collinear points give 1 or 2 points.
std::vector<Vec2> convex_hull(std::span<const Vec2> points);

/// True when q lies in the convex hull of `points` (boundary included, within `tolerance` distance).
/// Empty input gives false.
bool in_convex_hull(const Vec2& q, std::span<const Vec2> points, double tolerance = 1e-9);

}  // namespace tessera
