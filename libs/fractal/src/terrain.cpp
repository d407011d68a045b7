#include "tessera/fractal/terrain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "tessera/core/error.hpp"
#include "tessera/core/rng.hpp"

namespace tessera {
namespace {

void check_options(const TerrainOptions& options, int max_depth, const char* what) {
  if (options.depth < 0 || options.depth > max_depth)
    throw InvalidInput(fmt::format("{} depth must be in [0, {}], got {}", what, max_depth, options.depth));
  if (!(options.roughness > 0 && options.roughness < 1))
    throw InvalidInput(fmt::format("roughness must be in (0, 1), got {}", options.roughness));
  if (!(options.initial_range >= 0) || !std::isfinite(options.initial_range))
    throw InvalidInput(fmt::format("initial range must be finite and >= 0, got {}", options.initial_range));
}

/// The displacement of the point with `key` at a level of range r: uniform in [-r/2, r/2], one stream per point.
double displacement(uint64_t key, uint64_t seed, double range) {
  Rng rng(key, seed);
  return range * (rng.uniform_double() - 0.5);
}

/// Per-vertex colors by height over the mesh's own height range.
void color_by_height(PolyMesh& mesh) {
  double lo = 0, hi = 0;
  for (const Vec3& p : mesh.positions) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
  mesh.colors.clear();
  for (const Vec3& p : mesh.positions) mesh.colors.push_back(terrain_color(hi > lo ? (p.y - lo) / (hi - lo) : 0.5));
}

}  // namespace

std::vector<double> midpoint_displacement_1d(const TerrainOptions& options) {
  check_options(options, kMaxTerrainDepth1D, "1D mountain");
  const size_t n = size_t(1) << options.depth;
  std::vector<double> h(n + 1, 0.0);
  double range = options.initial_range;
  for (size_t step = n; step > 1; step /= 2, range *= options.roughness)
    for (size_t i = step / 2; i < n; i += step)
      h[i] = 0.5 * (h[i - step / 2] + h[i + step / 2]) + displacement(i, options.seed, range);
  return h;
}

PolyMesh triangle_mountain(const TerrainOptions& options) {
  check_options(options, kMaxTerrainDepthTriangles, "triangle mountain");
  PolyMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 0, -std::sqrt(3.0) / 2}};
  std::vector<std::array<uint32_t, 3>> triangles{{0, 1, 2}};
  double range = options.initial_range;
  for (int level = 0; level < options.depth; ++level, range *= options.roughness) {
    // One midpoint per edge, keyed by its (smaller, larger) vertex pair and shared by the triangles beside it.
    std::unordered_map<uint64_t, uint32_t> midpoints;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
      const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      const auto [it, added] = midpoints.try_emplace(key, uint32_t(mesh.positions.size()));
      if (added) {
        Vec3 m = 0.5 * (mesh.positions[a] + mesh.positions[b]);
        m.y += displacement(key, options.seed, range);
        mesh.positions.push_back(m);
      }
      return it->second;
    };
    std::vector<std::array<uint32_t, 3>> next;
    next.reserve(triangles.size() * 4);
    for (const auto& [a, b, c] : triangles) {
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.push_back({a, ab, ca});
      next.push_back({ab, b, bc});
      next.push_back({ca, bc, c});
      next.push_back({ab, bc, ca});
    }
    triangles = std::move(next);
  }
  for (const auto& t : triangles) mesh.add_face({t[0], t[1], t[2]});
  color_by_height(mesh);
  return mesh;
}

Image<float> diamond_square(const TerrainOptions& options) {
  check_options(options, kMaxTerrainDepthGrid, "diamond-square");
  const int n = 1 << options.depth;
  Image<float> h(n + 1, n + 1, 0.0f);
  const auto key = [&](int x, int y) { return uint64_t(y) * uint64_t(n + 1) + uint64_t(x); };
  double range = options.initial_range;
  for (int step = n; step > 1; step /= 2, range *= options.roughness) {
    const int half = step / 2;
    // Diamond step: the center of every square is the mean of its four corners, displaced.
    for (int y = half; y < n; y += step)
      for (int x = half; x < n; x += step) {
        const double mean = 0.25 * (double(h(x - half, y - half)) + h(x + half, y - half) + h(x - half, y + half) +
                                    h(x + half, y + half));
        h(x, y) = float(mean + displacement(key(x, y), options.seed, range));
      }
    // Square step: every edge midpoint is the mean of its (three or four) diamond neighbours, displaced.
    for (int y = 0; y <= n; y += half)
      for (int x = (y / half) % 2 == 0 ? half : 0; x <= n; x += step) {
        double sum = 0;
        int count = 0;
        for (const auto& [dx, dy] : {std::pair{-half, 0}, std::pair{half, 0}, std::pair{0, -half}, std::pair{0, half}})
          if (h.contains(x + dx, y + dy)) sum += h(x + dx, y + dy), ++count;
        h(x, y) = float(sum / count + displacement(key(x, y), options.seed, range));
      }
  }
  return h;
}

PolyMesh height_map_mesh(const Image<float>& heights, double height_scale) {
  const int w = heights.width(), h = heights.height();
  if (w < 2 || h < 2) throw InvalidInput(fmt::format("a height-map mesh needs at least 2x2 samples, got {}x{}", w, h));
  PolyMesh mesh;
  mesh.positions.reserve(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      mesh.positions.push_back({double(x) / (w - 1), height_scale * heights(x, y), double(y) / (h - 1)});
  const auto v = [&](int x, int y) { return uint32_t(y * w + x); };
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x + 1 < w; ++x) {
      // Seen from above (+y) with z growing toward the viewer, (x, y) -> (x, y+1) -> (x+1, y+1) is counterclockwise.
      mesh.add_face({v(x, y), v(x, y + 1), v(x + 1, y + 1)});
      mesh.add_face({v(x, y), v(x + 1, y + 1), v(x + 1, y)});
    }
  color_by_height(mesh);
  return mesh;
}

ImageRGB height_map_picture(const Image<float>& heights) {
  const auto [lo, hi] = std::minmax_element(heights.pixels().begin(), heights.pixels().end());
  ImageRGB out(heights.width(), heights.height());
  for (int y = 0; y < heights.height(); ++y)
    for (int x = 0; x < heights.width(); ++x)
      out(x, y) = terrain_color(*hi > *lo ? (heights(x, y) - *lo) / (*hi - *lo) : 0.5);
  return out;
}

Vec3f terrain_color(double t) {
  struct Stop {
    double t;
    Vec3f color;
  };
  static const std::array<Stop, 6> kStops{{{0.0, {0.05f, 0.15f, 0.45f}},
                                           {0.30, {0.20f, 0.45f, 0.75f}},
                                           {0.34, {0.85f, 0.80f, 0.55f}},
                                           {0.45, {0.25f, 0.55f, 0.20f}},
                                           {0.75, {0.45f, 0.35f, 0.25f}},
                                           {1.0, {0.97f, 0.97f, 1.0f}}}};
  t = std::clamp(t, 0.0, 1.0);
  size_t i = 1;
  while (i + 1 < kStops.size() && t > kStops[i].t) ++i;
  const auto f = float((t - kStops[i - 1].t) / (kStops[i].t - kStops[i - 1].t));
  return kStops[i - 1].color * (1.0f - f) + kStops[i].color * f;
}

}  // namespace tessera
