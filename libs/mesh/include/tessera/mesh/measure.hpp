#pragma once
// Bounding box, surface area and enclosed volume of a polygon mesh.
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// An axis-aligned box in double precision; lo > hi when empty.
struct Bounds3 {
  Vec3 lo{INFINITY}, hi{-INFINITY};
  bool empty() const { return lo.x > hi.x; }
};

/// The bounding box of all vertex positions (referenced or not).
Bounds3 bounding_box(const PolyMesh& mesh);

/// The sum of the face areas (each polygon as the length of its vector area, exact for planar faces).
double surface_area(const PolyMesh& mesh);

/// The signed volume enclosed by the faces, sum over fan triangles of p0 . (p1 x p2) / 6 (divergence theorem).
/// Positive for a closed, outward-oriented mesh; meaningless (origin-dependent) for an open one.
double signed_volume(const PolyMesh& mesh);

}  // namespace tessera
