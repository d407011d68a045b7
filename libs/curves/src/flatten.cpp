#include "tessera/curves/flatten.hpp"

#include "tessera/curves/bezier.hpp"

namespace tessera {

void flatten_cubic(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double tolerance,
                   std::vector<Vec2>& out) {
  flatten(cubic(p0, p1, p2, p3), tolerance, out);
}

void flatten_quadratic(const Vec2& p0, const Vec2& p1, const Vec2& p2, double tolerance, std::vector<Vec2>& out) {
  flatten(elevate_degree(quadratic(p0, p1, p2)), tolerance, out);
}

}  // namespace tessera
