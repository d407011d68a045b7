#include "tessera/volume/procedural.hpp"

#include <array>
#include <cmath>
#include <functional>

#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/core/rng.hpp"

namespace tessera {
namespace {

/// Samples f over [-1, 1]^3 on an n^3 grid.
Volume<float> sample_field(int n, const std::function<double(const Vec3&)>& f) {
  if (n < 2) throw InvalidInput(fmt::format("procedural volume size must be >= 2, got {}", n));
  // The volume and the copy of its values that profiling sorts (Otsu's threshold, percentiles), as the readers count.
  MemoryBudget::check(saturating_product({uint64_t(n), uint64_t(n), uint64_t(n), 2 * sizeof(float)}),
                      fmt::format("a procedural volume of {}^3 voxels", n));
  const double h = 2.0 / double(n - 1);
  Volume<float> v(glm::ivec3(n), 0.0f, Vec3(h), Vec3(-1.0));
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) v(x, y, z) = float(f(v.to_world(Vec3(x, y, z))));
  return v;
}

}  // namespace

Volume<float> make_sphere(int n, double radius, const Vec3& center) {
  return sample_field(n, [&](const Vec3& p) { return radius - glm::length(p - center); });
}

Volume<float> make_torus(int n, double major, double minor) {
  return sample_field(n, [&](const Vec3& p) {
    const double q = std::hypot(p.x, p.y) - major;
    return minor - std::hypot(q, p.z);
  });
}

Volume<float> make_gyroid(int n, double periods) {
  const double k = periods * kPi;
  return sample_field(n, [&](const Vec3& p) {
    const Vec3 q = k * p;
    return std::sin(q.x) * std::cos(q.y) + std::sin(q.y) * std::cos(q.z) + std::sin(q.z) * std::cos(q.x);
  });
}

Volume<float> make_metaballs(int n) {
  static constexpr std::array<std::array<double, 4>, 4> kBalls{
      {{-0.35, -0.2, 0.0, 0.35}, {0.35, -0.15, 0.1, 0.3}, {0.0, 0.35, -0.1, 0.32}, {0.05, 0.0, 0.45, 0.22}}};
  return sample_field(n, [](const Vec3& p) {
    double sum = 0;
    for (const auto& b : kBalls) {
      const double d2 = glm::dot(p - Vec3(b[0], b[1], b[2]), p - Vec3(b[0], b[1], b[2]));
      sum += b[3] * b[3] / std::max(d2, 1e-6);
    }
    return sum;
  });
}

Volume<float> make_noise(int n, uint64_t seed, double frequency) {
  // A lattice of random values per octave, hashed from (seed, octave, lattice point): no state, any order.
  const auto lattice = [seed](int octave, int i, int j, int k) {
    const uint64_t key = (uint64_t(uint32_t(i)) * 73856093u) ^ (uint64_t(uint32_t(j)) * 19349663u) ^
                         (uint64_t(uint32_t(k)) * 83492791u) ^ (uint64_t(octave) << 40);
    Rng rng(key, seed);
    return 2.0 * rng.uniform_double() - 1.0;
  };
  const auto value_noise = [&](int octave, const Vec3& p) {
    const Vec3 f = glm::floor(p), t = p - f;
    const Vec3 s = t * t * (3.0 - 2.0 * t);  // smoothstep weights
    const int i = int(f.x), j = int(f.y), k = int(f.z);
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
      const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
      sum +=
          (dx ? s.x : 1 - s.x) * (dy ? s.y : 1 - s.y) * (dz ? s.z : 1 - s.z) * lattice(octave, i + dx, j + dy, k + dz);
    }
    return sum;
  };
  return sample_field(n, [&](const Vec3& p) {
    double sum = 0, amplitude = 0.6, freq = frequency;
    for (int octave = 0; octave < 4; ++octave, amplitude *= 0.5, freq *= 2)
      sum += amplitude * value_noise(octave, (p + 1.0) * freq);
    return sum;
  });
}

bool make_procedural(const std::string& spec, Volume<float>& out) {
  const auto parts = split(spec, ':');
  if (parts.size() < 2) return false;
  const std::string name(parts[0]);
  const auto size = [&] {
    // Checked before the conversion to int: sphere:99999999999 wrapped to another size.
    const auto n = parse_int(parts[1], fmt::format("size of procedural volume '{}'", spec));
    if (n < 2 || n > (1 << 30))
      throw InvalidInput(fmt::format("size of procedural volume '{}' must be in 2..{}", spec, 1 << 30));
    return int(n);
  };
  if (parts.size() == 2 && name == "sphere")
    out = make_sphere(size());
  else if (parts.size() == 2 && name == "torus")
    out = make_torus(size());
  else if (parts.size() == 2 && name == "gyroid")
    out = make_gyroid(size());
  else if (parts.size() == 2 && name == "metaballs")
    out = make_metaballs(size());
  else if (name == "noise" && parts.size() <= 3)
    out = make_noise(size(), parts.size() == 3 ? uint64_t(parse_int(parts[2], "noise seed")) : 1);
  else
    return false;
  return true;
}

}  // namespace tessera
