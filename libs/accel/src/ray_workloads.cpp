// Standard ray sets for tests and benchmarks.
#include "tessera/accel/ray_workloads.hpp"

#include <cmath>

#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"

namespace tessera {

std::vector<Ray> incoherent_rays(const AABB& box, size_t count, uint64_t seed) {
  std::vector<Ray> rays(count);
  const Vec3f c = box.center(), h = 0.55f * box.extent();
  parallel_for(0, int64_t(count), 4096, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      Rng rng(uint64_t(i), seed);
      Ray& r = rays[size_t(i)];
      r.origin = c + h * Vec3f(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
      // Uniform on the sphere: z uniform in [-1, 1], longitude uniform (Archimedes' hat-box theorem).
      const float z = 2 * rng.uniform() - 1, phi = float(2 * kPi) * rng.uniform();
      const float s = std::sqrt(std::max(0.0f, 1 - z * z));
      r.dir = Vec3f(s * std::cos(phi), s * std::sin(phi), z);
    }
  });
  return rays;
}

std::vector<Ray> primary_rays(const Camera& camera, int width, int height) {
  const EyeRays eye(camera, width, height);
  std::vector<Ray> rays(size_t(width) * size_t(height));
  parallel_for(0, height, 8, [&](int64_t y0, int64_t y1) {
    for (int64_t j = y0; j < y1; ++j)
      for (int i = 0; i < width; ++i) rays[size_t(j) * size_t(width) + size_t(i)] = eye.ray(i, double(j));
  });
  return rays;
}

}  // namespace tessera
