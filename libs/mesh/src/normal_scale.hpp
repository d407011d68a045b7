// Internal: scaling by powers of two, so that face areas and volumes neither overflow nor underflow where the result
// is a double (normals.cpp, measure.cpp).
#pragma once

#include <cstddef>

#include "tessera/mesh/poly_mesh.hpp"

#include <vector>

namespace tessera::detail {

/// The binary exponent of `largest` (a coordinate's or a vector component's magnitude) when it lies outside
/// [2^-128, 2^128], else 0; 0 for 0 and for non-finite values (which are left to propagate). Scaling by 2^-that is
/// exact (but for subnormals) and brings the value near 1.
int scale_exponent(double largest);

/// The largest magnitude of any coordinate of `points`.
double largest_coordinate(const std::vector<Vec3>& points);

/// The area of face f (the length of its vector area), computed on its points scaled by a power of two: finite and
/// nonzero whenever the area is (faces of coordinates near 1e300 or 1e-300 included).
double face_area(const PolyMesh& mesh, size_t f);

}  // namespace tessera::detail
