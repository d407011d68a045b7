#pragma once
// Parametric surfaces (s, t) -> point (the notes' "Parametric Surfaces": parallelogram, cylinder, sphere) and a generic
// tessellator into a TriMesh with normals and uvs.
#include <functional>

#include "tessera/math/types.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// A closed parameter interval [lo, hi] (lo < hi).
struct ParamInterval {
  double lo = 0, hi = 1;
};

/// A parametric surface over [s.lo, s.hi] x [t.lo, t.hi]. The front side is where ∂P/∂s x ∂P/∂t points.
struct ParametricSurface {
  std::function<Vec3(double s, double t)> position;
  std::function<Vec3(double s, double t)> normal;  ///< unit normal if known analytically; empty: finite differences
  ParamInterval s{0, 1};
  ParamInterval t{0, 1};
};

/// The notes' parallelogram: P(s, t) = p1 + s (p2 - p1) + t (p3 - p1), s, t in [0, 1] (p1 the bottom-left corner,
/// p2 and p3 its neighbours). Normal (p2 - p1) x (p3 - p1). Throws InvalidInput when the three points are collinear.
ParametricSurface parallelogram(const Vec3& p1, const Vec3& p2, const Vec3& p3);

/// The notes' cylinder: P(s, t) = (r cos s, r sin s, h t), s in [0, 2π] (angle), t in [0, 1] (height), normals
/// outward. Throws InvalidInput unless radius, height > 0.
ParametricSurface cylinder(double radius = 1, double height = 1);

/// The notes' sphere: P(s, t) = r (cos t cos s, cos t sin s, sin t), s in [0, 2π] (longitude), t in [-π/2, π/2]
/// (latitude, π/2 the north pole), normals outward. Throws InvalidInput unless radius > 0.
ParametricSurface sphere(double radius = 1);

/// The unit normal of `surface` at (s, t): the analytic one when given, else the normalized cross product of central
/// finite-difference partials (one-sided at the borders). Where the partials are parallel or vanish (a pole, a
/// collapsed edge) it is the normal at the nearest regular point toward the domain's center. Zero if none is found.
Vec3 surface_normal(const ParametricSurface& surface, double s, double t);

/// Samples the surface on an (s_steps + 1) x (t_steps + 1) grid, uniform in s and t, and joins it into 2 s_steps
/// t_steps triangles, counterclockwise around the normal. Vertex k = i (t_steps + 1) + j holds P(s_i, t_j), its
/// normal and uv = ((s_i - s.lo) / (s.hi - s.lo), (t_j - t.lo) / (t.hi - t.lo)). Seams and poles keep their duplicate
/// vertices (one per uv). `position` and `normal` are called from several threads at once. Throws InvalidInput
/// unless both step counts are in 1..4096, or when `position` is empty or a range is empty.
TriMesh tessellate(const ParametricSurface& surface, int s_steps, int t_steps);

}  // namespace tessera
