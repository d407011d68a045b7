#pragma once
// Adaptive flattening of quadratic and cubic Bezier curves into polylines, within a distance tolerance.
// Used by the 2D canvas (bezierVertex) and the SVG front end for their paths.
#include <vector>

#include "tessera/math/types.hpp"

namespace tessera {

/// Appends points approximating the cubic Bezier p0..p3 to `out`, excluding p0 and including p3, so that every point
/// of the curve is within `tolerance` of the polyline. Uses recursive de Casteljau subdivision at t = 1/2 with the
/// control-polygon flatness bound (max distance of p1, p2 from the chord), depth-limited to 16: tessera::flatten of
/// bezier.hpp on the cubic p0..p3.
void flatten_cubic(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double tolerance,
                   std::vector<Vec2>& out);

/// The same for the quadratic Bezier p0, p1, p2 (degree-elevated to a cubic first).
void flatten_quadratic(const Vec2& p0, const Vec2& p1, const Vec2& p2, double tolerance, std::vector<Vec2>& out);

}  // namespace tessera
