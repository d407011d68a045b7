// Internal: face areas computed on points scaled by a power of two (tessera/math/power_of_two.hpp), so that they
// neither overflow nor underflow where the result is a double (normals.cpp, measure.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera::detail {

/// The area of face f (the length of its vector area), computed on its points scaled by a power of two: finite and
/// nonzero whenever the area is (faces of coordinates near 1e300 or 1e-300 included).
double face_area(const PolyMesh& mesh, size_t f);

}  // namespace tessera::detail
