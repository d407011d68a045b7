// Bvh: the constructor that checks the settings and boxes and runs one of the two builders (bvh_sah.cpp,
// bvh_bottom_up.cpp), and the tree's SAH cost.
#include "tessera/accel/bvh.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <string>

#include "bvh_build.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {

using bvh_build::kMaxBins;
using bvh_build::kMaxLeafCount;
using bvh_build::leaf_tests;
using bvh_build::PrimRef;

Bvh::Bvh(std::span<const AABB> prim_bounds, const BvhSettings& settings)
    : Bvh(
          prim_bounds.size(), [prim_bounds](size_t i) { return prim_bounds[i]; }, settings) {}

Bvh::Bvh(size_t count, const std::function<AABB(size_t)>& prim_box, const BvhSettings& settings) : settings_(settings) {
  if (!(settings.max_leaf_size >= 1 && settings.max_leaf_size <= kMaxLeafCount))
    throw InvalidInput("BvhSettings: max_leaf_size must be in [1, 65535], got " +
                       std::to_string(settings.max_leaf_size));
  if (!(settings.bins >= 2 && settings.bins <= kMaxBins))
    throw InvalidInput("BvhSettings: bins must be in [2, 64], got " + std::to_string(settings.bins));
  if (!(settings.leaf_block >= 1 && settings.leaf_block <= 64 && std::has_single_bit(unsigned(settings.leaf_block))))
    throw InvalidInput("BvhSettings: leaf_block must be a power of two in [1, 64], got " +
                       std::to_string(settings.leaf_block));
  if (!(settings.traversal_cost >= 0 && settings.intersection_cost > 0))
    throw InvalidInput("BvhSettings: costs must be traversal >= 0 and intersection > 0");
  if (count > size_t(PrimRef::kMaxIndex))
    throw InvalidInput("Bvh: " + std::to_string(count) + " primitives, more than the " +
                       std::to_string(PrimRef::kMaxIndex) + " supported");
  // The references straight from the boxes, in parallel (on huge pages when large, as all the build's reference
  // arrays); empty boxes (never hit) are squeezed out afterwards, and the first non-finite box is reported.
  RawVector<PrimRef> refs(count);
  std::atomic<size_t> first_bad{count};
  std::atomic<bool> any_empty{false};
  parallel_for(0, int64_t(count), 16384, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const AABB b = prim_box(size_t(i));
      refs[size_t(i)] = PrimRef(b, int(i));
      if (b.empty()) {
        any_empty = true;
      } else if (!std::isfinite(b.lo.x) || !std::isfinite(b.lo.y) || !std::isfinite(b.lo.z) || !std::isfinite(b.hi.x) ||
                 !std::isfinite(b.hi.y) || !std::isfinite(b.hi.z)) {
        size_t seen = first_bad.load();
        while (size_t(i) < seen && !first_bad.compare_exchange_weak(seen, size_t(i))) {
        }
      }
    }
  });
  if (first_bad < count)
    throw InvalidInput("Bvh: primitive " + std::to_string(first_bad.load()) +
                       " has a non-finite box (planes cannot go in a BVH)");
  if (any_empty) {
    const auto is_empty = [](const PrimRef& r) {
      return r.box.lo[0] > r.box.hi[0] || r.box.lo[1] > r.box.hi[1] || r.box.lo[2] > r.box.hi[2];
    };
    refs.erase(std::remove_if(refs.begin(), refs.end(), is_empty), refs.end());
  }
  if (refs.empty()) return;
  if (settings.build == BvhSettings::Build::bottom_up) {
    depth_ = bvh_build::build_bottom_up(settings_, refs, nodes_);
    if (depth_ > kMaxDepth) {  // a degenerate input can chain clusters: fall back to the top-down build
      nodes_.clear();
    }
  }
  if (nodes_.empty()) depth_ = bvh_build::build_binned_sah(settings_, refs, nodes_);
  TESSERA_CHECK_LE(depth_, kMaxDepth);
  prim_indices_.resize(refs.size());
  parallel_for(0, int64_t(refs.size()), 65536, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) prim_indices_[size_t(i)] = refs[size_t(i)].index();
  });
}

float Bvh::sah_cost() const {
  if (nodes_.empty()) return 0;
  const float inv_root = 1.0f / nodes_[0].box.area();
  double cost = 0;
  for (const BvhNode& n : nodes_)
    cost += double(n.box.area() * inv_root) *
            (n.count > 0 ? settings_.intersection_cost * leaf_tests(settings_, n.count) : settings_.traversal_cost);
  return float(cost);
}

}  // namespace tessera
