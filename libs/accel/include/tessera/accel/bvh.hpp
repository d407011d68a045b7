#pragma once
// A bounding volume hierarchy over primitives given by their boxes (the notes' "bounding hierarchy"): built top-down by
// binned SAH or bottom-up by agglomerative clustering, flattened into depth-first order, traversed near child first.
//
// The BVH knows only boxes: what a primitive is comes in through the hit_prim callback, so the same structure serves
// meshes, shapes and instances (shapes are kernels fed to one acceleration structure).
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "tessera/core/memory.hpp"
#include "tessera/math/ray.hpp"

namespace tessera {

/// Build settings of a Bvh (the SAH cost model and its limits).
struct BvhSettings {
  float traversal_cost = 1.0f;     ///< SAH cost of visiting an interior node (relative to intersection_cost)
  float intersection_cost = 1.0f;  ///< SAH cost of one primitive test
  int max_leaf_size = 4;           ///< a range of at most this many primitives may become a leaf (SAH permitting)
  int bins = 16;                   ///< SAH bins per axis (binned_sah)
  /// Primitives a leaf tests at once (a SIMD test of several; a power of two): the SAH charges a leaf of n primitives
  /// ceil(n / leaf_block) tests, which favours full blocks (MeshAccel sets 4).
  int leaf_block = 1;
  /// binned_sah: top-down, the split of least SAH cost among the bin boundaries of the three axes.
  /// bottom_up: the notes' bottom-up build, repeatedly merging nearest clusters (see docs/accel.md).
  enum class Build { binned_sah, bottom_up } build = Build::binned_sah;
};

/// A flattened node (32 bytes, aligned so that no node straddles two cache lines). Interior (count 0): the first child
/// follows the node, the second is at `first`; `axis` is the axis along which the first child lies before the second.
/// Leaf: prim_indices()[first, first + count).
struct alignas(32) BvhNode {
  AABB box;
  int32_t first;
  uint16_t count;
  uint16_t axis;
};
static_assert(sizeof(BvhNode) == 32);

/// Counters of one traversal (for cost heat maps and tests).
struct TraversalStats {
  int64_t nodes = 0;  ///< nodes (or grid cells) visited
  int64_t prims = 0;  ///< primitive tests
};

/// A ray prepared for many box tests: inverse direction and the ray's sign per axis.
struct RayBoxTest {
  Vec3f origin, inv_dir;
  int neg[3];

  explicit RayBoxTest(const Ray& ray)
      : origin(ray.origin),
        inv_dir(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z),
        // The sign bit, as inv_dir has it: -0 is negative (1 / -0 = -inf), else an axis-parallel ray along -0 would
        // take the far plane for the near one and miss every box (an orthographic eye ray along -z, say).
        neg{std::signbit(ray.dir.x), std::signbit(ray.dir.y), std::signbit(ray.dir.z)} {}

  /// The slab test against [tmin, tmax], selecting near and far planes by the ray's signs (no swaps). The far distance
  /// is enlarged by 2 gamma(3) (pbrt's conservative rounding) so a ray grazing a box edge is never lost.
  bool hits(const AABB& box, float tmin, float tmax) const {
    const float* b = &box.lo.x;  // lo then hi, 6 floats
    const float tx0 = (b[3 * neg[0] + 0] - origin.x) * inv_dir.x;
    const float tx1 = (b[3 - 3 * neg[0] + 0] - origin.x) * inv_dir.x * kRobust;
    const float ty0 = (b[3 * neg[1] + 1] - origin.y) * inv_dir.y;
    const float ty1 = (b[3 - 3 * neg[1] + 1] - origin.y) * inv_dir.y * kRobust;
    const float tz0 = (b[3 * neg[2] + 2] - origin.z) * inv_dir.z;
    const float tz1 = (b[3 - 3 * neg[2] + 2] - origin.z) * inv_dir.z * kRobust;
    // Comparisons written so that a NaN (0 * inf: origin on a slab plane of a parallel ray) leaves the bound as is.
    tmin = tx0 > tmin ? tx0 : tmin;
    tmin = ty0 > tmin ? ty0 : tmin;
    tmin = tz0 > tmin ? tz0 : tmin;
    tmax = tx1 < tmax ? tx1 : tmax;
    tmax = ty1 < tmax ? ty1 : tmax;
    tmax = tz1 < tmax ? tz1 : tmax;
    return tmin <= tmax;
  }
  static constexpr float kRobust = 1.0f + 2.0f * 3.0f * 0x1p-24f / (1.0f - 3.0f * 0x1p-24f);
};

/// A BVH over primitive boxes.
class Bvh {
 public:
  Bvh() = default;
  /// Builds over prim_bounds (primitive i has box prim_bounds[i]; empty boxes are allowed and never hit). Parallel
  /// (oneTBB) and deterministic: the same tree for any thread count. Throws InvalidInput for bad settings or a
  /// non-finite box.
  explicit Bvh(std::span<const AABB> prim_bounds, const BvhSettings& settings = {});
  /// The same over `count` primitives whose boxes come from prim_box(i) (called once per primitive, in parallel),
  /// without an array of boxes.
  Bvh(size_t count, const std::function<AABB(size_t)>& prim_box, const BvhSettings& settings = {});

  /// Nearest hit: calls hit_prim(int prim, Ray& ray) -> bool for the primitives whose boxes the ray reaches, near
  /// subtrees first; hit_prim tests primitive prim and on a hit shrinks ray.tmax and returns true. Returns whether any
  /// call returned true. stats (optional) counts the nodes visited and primitives tested.
  template <class F>
  bool intersect(Ray& ray, F&& hit_prim, TraversalStats* stats = nullptr) const {
    return traverse_leaves<false>(
        ray,
        [&](int first, int count, Ray& r) {
          bool hit = false;
          for (int i = first; i < first + count; ++i) hit |= hit_prim(prim_indices_[i], r);
          return hit;
        },
        stats);
  }

  /// Any hit in [ray.tmin, ray.tmax] (shadow rays): stops at the first hit_prim that returns true.
  template <class F>
  bool occluded(const Ray& ray, F&& hit_prim) const {
    Ray r = ray;
    return traverse_leaves<true>(
        r,
        [&](int first, int count, Ray& rr) {
          for (int i = first; i < first + count; ++i)
            if (hit_prim(prim_indices_[i], rr)) return true;
          return false;
        },
        nullptr);
  }

  /// The flattened nodes, depth-first (node 0 is the root; empty when there are no primitives).
  std::span<const BvhNode> nodes() const { return nodes_; }
  /// Primitive indices in leaf order.
  std::span<const int> prim_indices() const { return prim_indices_; }
  /// The number of node levels (1 for a single leaf, 0 when empty).
  int depth() const { return depth_; }
  /// The SAH cost of the tree with the settings' costs (sum over nodes of area ratio times node cost).
  float sah_cost() const;
  /// The root box (empty when there are no primitives).
  AABB bounds() const { return nodes_.empty() ? AABB{} : nodes_[0].box; }

  static constexpr int kMaxDepth = 64;  ///< builds keep the depth below this (the traversal stack size)

 private:
  /// The traversal underneath intersect/occluded, one call per leaf reached: leaf(first, count, ray) -> bool tests the
  /// slots [first, first + count) of prim_indices() (callers that store primitives in leaf order use the slots
  /// directly). AnyHit stops at the first leaf that reports a hit.
  template <bool AnyHit, class L>
  bool traverse_leaves(Ray& ray, L&& leaf, TraversalStats* stats) const {
    if (nodes_.empty()) return false;
    const RayBoxTest test(ray);
    int stack[kMaxDepth];
    int sp = 0;
    int node = 0;
    bool hit = false;
    for (;;) {
      const BvhNode& n = nodes_[node];
      if (stats) ++stats->nodes;
      if (test.hits(n.box, ray.tmin, ray.tmax)) {
        if (n.count > 0) {
          if (stats) stats->prims += n.count;
          if (leaf(int(n.first), int(n.count), ray)) {
            hit = true;
            if constexpr (AnyHit) return true;
          }
        } else {
          // Near child first: the first child lies before the second along `axis`, so a ray going down that axis
          // visits the second first.
          if (test.neg[n.axis]) {
            stack[sp++] = node + 1;
            node = n.first;
          } else {
            stack[sp++] = n.first;
            node = node + 1;
          }
          continue;
        }
      }
      if (sp == 0) break;
      node = stack[--sp];
    }
    return hit;
  }

  RawVector<BvhNode> nodes_;  // uninitialized growth on huge pages: written in full by the constructor
  RawVector<int> prim_indices_;
  int depth_ = 0;
  BvhSettings settings_;
};

}  // namespace tessera
