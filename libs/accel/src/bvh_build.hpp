#pragma once
// Private to accel: what the two BVH builders (bvh_sah.cpp, bvh_bottom_up.cpp) and Bvh's constructor (bvh.cpp) share:
// the SSE box arithmetic, the 32-byte primitive reference, the SAH's leaf cost and the builders' entry points.
#include <bit>
#include <cstdint>
#include <limits>

#include "tessera/accel/bvh.hpp"
#include "tessera/core/memory.hpp"

namespace tessera::bvh_build {

/// Four floats in one SSE register (GCC/Clang vector extension): the builder's box arithmetic, 3 lanes used.
typedef float v4f __attribute__((vector_size(16)));
typedef int v4i __attribute__((vector_size(16)));

inline v4f vmin(v4f a, v4f b) { return a < b ? a : b; }
inline v4f vmax(v4f a, v4f b) { return a > b ? a : b; }
inline v4f splat(float x) { return v4f{x, x, x, x}; }

/// A box as two registers (empty: lo = +inf, hi = -inf).
struct Box4 {
  v4f lo = splat(std::numeric_limits<float>::infinity()), hi = splat(-std::numeric_limits<float>::infinity());
  void expand(const Box4& b) {
    lo = vmin(lo, b.lo);
    hi = vmax(hi, b.hi);
  }
  void expand_point(v4f p) {
    lo = vmin(lo, p);
    hi = vmax(hi, p);
  }
  float area() const {
    const v4f e = hi - lo;
    if (!(e[0] >= 0 && e[1] >= 0 && e[2] >= 0)) return 0;
    return 2.0f * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  }
  AABB aabb() const { return AABB{Vec3f(lo[0], lo[1], lo[2]), Vec3f(hi[0], hi[1], hi[2])}; }
};

/// A primitive during the build in 32 bytes (half a cache line): its box, with its index in the unused fourth lane of
/// both corners (Embree's trick). The index is stored with its exponent field raised by 64, so that the lane holds a
/// float in [2^-63, 2^127) whose sums and differences are never denormal (a denormal makes SSE arithmetic on the whole
/// register slow); the box arithmetic never reads the lane.
struct alignas(32) PrimRef {
  Box4 box;
  PrimRef() = default;
  PrimRef(const AABB& b, int index) {
    const float tag = std::bit_cast<float>(uint32_t(index) + kIndexBias);
    box = Box4{v4f{b.lo.x, b.lo.y, b.lo.z, tag}, v4f{b.hi.x, b.hi.y, b.hi.z, tag}};
  }
  int index() const { return int(std::bit_cast<uint32_t>(box.lo[3]) - kIndexBias); }
  v4f centroid2() const { return box.lo + box.hi; }  // twice the centroid: enough for binning
  /// centroid2()[axis] from two scalar loads (a lane picked by a variable index from a register goes through memory).
  float centroid2(int axis) const { return box.lo[axis] + box.hi[axis]; }
  static constexpr uint32_t kIndexBias = 64u << 23;
  static constexpr int kMaxIndex = (190 << 23) - 1;  // keeps the exponent field at most 253 (sums stay finite)
};
static_assert(sizeof(PrimRef) == 32);

/// The tests a leaf of n primitives costs: whole blocks of settings.leaf_block.
inline float leaf_tests(const BvhSettings& s, int n) {
  return float(unsigned(n + s.leaf_block - 1) >> std::countr_zero(unsigned(s.leaf_block)));
}

constexpr int kMaxBins = 64;          // BvhSettings::bins at most
constexpr int kMaxLeafCount = 65535;  // BvhNode::count is 16 bits

/// Top-down binned SAH (bvh_sah.cpp): fills `nodes` (empty on entry) depth-first and reorders `refs` (not empty) into
/// leaf order; returns the depth, which is at most Bvh::kMaxDepth. Parallel, and the same tree for any thread count.
int build_binned_sah(const BvhSettings& settings, RawVector<PrimRef>& refs, RawVector<BvhNode>& nodes);

/// The notes' bottom-up build by PLOC (bvh_bottom_up.cpp), with the same contract, except that the depth may exceed
/// Bvh::kMaxDepth on degenerate inputs (the caller then builds top-down instead).
int build_bottom_up(const BvhSettings& settings, RawVector<PrimRef>& refs, RawVector<BvhNode>& nodes);

}  // namespace tessera::bvh_build
