#pragma once
// Standard ray sets for tests and benchmarks (DESIGN.md section 4, `tessera bench raycast`).
#include <cstdint>
#include <vector>

#include "tessera/math/camera.hpp"
#include "tessera/math/ray.hpp"

namespace tessera {

/// The usual incoherent-ray workload: origins uniform in `box` scaled 1.1x about its center, directions uniform on the
/// sphere. Ray i depends only on (seed, i), so the set is the same for any thread count.
std::vector<Ray> incoherent_rays(const AABB& box, size_t count, uint64_t seed = 1);

/// The notes' eye rays through the centers of a width x height image, row-major from the top row.
std::vector<Ray> primary_rays(const Camera& camera, int width, int height);

}  // namespace tessera
