#pragma once
// A uniform grid (the notes' spatial partition): space divided into cells, each listing the primitives whose boxes
// overlap it, walked cell by cell along the ray by the 3D-DDA of Amanatides and Woo (1987).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>
#include <limits>
#include <span>
#include <vector>

#include "tessera/accel/bvh.hpp"
#include "tessera/math/ray.hpp"

namespace tessera {

/// Build settings of a UniformGrid.
struct GridSettings {
  /// Cells per primitive: the resolution along axis i is extent_i * cbrt(density * N / volume), rounded, at least 1
  /// (the usual density rule, e.g. Wald et al. 2006; cells come out roughly cubic).
  float density = 2.0f;
  int max_resolution = 512;  ///< cap per axis
};

/// A uniform grid over primitive boxes; the same callback contract as Bvh.
class UniformGrid {
 public:
  UniformGrid() = default;
  /// Builds over prim_bounds (empty boxes are skipped). Throws InvalidInput for bad settings or non-finite boxes.
  explicit UniformGrid(std::span<const AABB> prim_bounds, const GridSettings& settings = {});

  /// Nearest hit; hit_prim(int prim, Ray& ray) -> bool tests a primitive and on a hit shrinks ray.tmax. Cells are
  /// visited front to back and the walk stops once the nearest hit lies before the next cell. A primitive spanning
  /// several cells may be tested more than once (no mailboxes: the callback must be idempotent, as a ray test is).
  template <class F>
  bool intersect(Ray& ray, F&& hit_prim, TraversalStats* stats = nullptr) const {
    return walk<false>(ray, hit_prim, stats);
  }
  /// Any hit in [ray.tmin, ray.tmax].
  template <class F>
  bool occluded(const Ray& ray, F&& hit_prim) const {
    Ray r = ray;
    return walk<true>(r, hit_prim, nullptr);
  }

  /// Cells per axis.
  glm::ivec3 resolution() const { return res_; }
  /// The grid's box (the union of the primitive boxes).
  const AABB& bounds() const { return box_; }
  /// Primitives listed in cell (x, y, z).
  std::span<const int> cell(int x, int y, int z) const {
    const int c = (z * res_.y + y) * res_.x + x;
    return {prims_.data() + offsets_[c], size_t(offsets_[c + 1] - offsets_[c])};
  }

 private:
  template <bool AnyHit, class F>
  bool walk(Ray& ray, F& hit_prim, TraversalStats* stats) const {
    if (prims_.empty()) return false;
    const RayBoxTest test(ray);
    // Clip the ray to the grid box.
    float t0 = ray.tmin, t1 = ray.tmax;
    if (!intersect_slabs(box_, ray, test.inv_dir, t0, t1)) return false;
    // Amanatides-Woo set-up: the cell of the entry point, the t of the next boundary per axis and the t step per cell.
    const Vec3f entry = ray.at(t0);
    int cell[3], step[3], stop[3];
    float next[3], delta[3];
    for (int a = 0; a < 3; ++a) {
      const float rel = (entry[a] - box_.lo[a]) * inv_cell_[a];
      cell[a] = std::clamp(int(std::floor(rel)), 0, res_[a] - 1);
      if (ray.dir[a] > 0) {
        step[a] = 1;
        stop[a] = res_[a];
        next[a] = t0 + (box_.lo[a] + float(cell[a] + 1) * cell_size_[a] - entry[a]) * test.inv_dir[a];
        delta[a] = cell_size_[a] * test.inv_dir[a];
      } else if (ray.dir[a] < 0) {
        step[a] = -1;
        stop[a] = -1;
        next[a] = t0 + (box_.lo[a] + float(cell[a]) * cell_size_[a] - entry[a]) * test.inv_dir[a];
        delta[a] = -cell_size_[a] * test.inv_dir[a];
      } else {
        step[a] = 0;
        stop[a] = -2;
        next[a] = std::numeric_limits<float>::infinity();
        delta[a] = 0;
      }
    }
    bool hit = false;
    for (;;) {
      if (stats) ++stats->nodes;
      const int c = (cell[2] * res_.y + cell[1]) * res_.x + cell[0];
      const int* p = prims_.data() + offsets_[c];
      const int* end = prims_.data() + offsets_[c + 1];
      for (; p != end; ++p) {
        if (stats) ++stats->prims;
        if (hit_prim(*p, ray)) {
          hit = true;
          if constexpr (AnyHit) return true;
        }
      }
      // The axis whose cell boundary comes first.
      const int a = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
      // Stop when the nearest hit (or the ray's end) lies in this cell, or no boundary is ahead (a zero direction).
      if (ray.tmax < next[a] || next[a] == std::numeric_limits<float>::infinity()) break;
      cell[a] += step[a];
      if (cell[a] == stop[a]) break;
      next[a] += delta[a];
    }
    return hit;
  }

  AABB box_;
  glm::ivec3 res_{0};
  Vec3f cell_size_{0.0f}, inv_cell_{0.0f};
  std::vector<int> offsets_;  ///< per cell, into prims_ (cells + 1 entries)
  std::vector<int> prims_;
};

}  // namespace tessera
