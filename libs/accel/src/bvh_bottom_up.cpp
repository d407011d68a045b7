// The notes' bottom-up BVH build by locally-ordered agglomerative clustering (Meister and Bittner 2017, PLOC).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

#include "bvh_build.hpp"

namespace tessera::bvh_build {

namespace {

/// Spreads the low 10 bits of v to every third bit (for 30-bit Morton codes).
uint32_t spread_bits(uint32_t v) {
  v = (v | (v << 16)) & 0x030000FF;
  v = (v | (v << 8)) & 0x0300F00F;
  v = (v | (v << 4)) & 0x030C30C3;
  v = (v | (v << 2)) & 0x09249249;
  return v;
}

/// The notes' bottom-up build ("pair the 2 nearest objects, then the boxes containing smaller boxes"), made
/// O(n log n)-ish by PLOC: clusters kept in Morton order, each looks for its nearest cluster (the one whose union box
/// has the least area) within `kRadius` places on either side, and mutual nearest pairs merge, until one is left.
class BottomUpBuilder {
 public:
  BottomUpBuilder(const BvhSettings& s, RawVector<PrimRef>& refs) : s_(s), refs_(refs) {}

  /// Returns the depth; fills nodes (depth-first) and reorders refs_ into leaf order.
  int build(RawVector<BvhNode>& nodes) {
    const int n = int(refs_.size());
    sort_by_morton();
    tree_.reserve(2 * size_t(n));
    for (int i = 0; i < n; ++i) tree_.push_back(TreeNode{refs_[size_t(i)].box.aabb(), -1, -1, i, 1, 0});
    std::vector<int> clusters(static_cast<size_t>(n)), nearest(static_cast<size_t>(n)), next;
    std::iota(clusters.begin(), clusters.end(), 0);
    while (clusters.size() > 1) {
      const int m = int(clusters.size());
      tbb::parallel_for(tbb::blocked_range<int>(0, m, 1024), [&](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i < r.end(); ++i) nearest[size_t(i)] = nearest_in_window(clusters, i);
      });
      next.clear();
      for (int i = 0; i < m; ++i) {
        const int j = nearest[size_t(i)];
        if (nearest[size_t(j)] == i) {
          if (i < j) next.push_back(merge(clusters[size_t(i)], clusters[size_t(j)]));
        } else {
          next.push_back(clusters[size_t(i)]);
        }
      }
      clusters.swap(next);
    }
    // Collapse small subtrees into leaves where the SAH says a leaf is cheaper, then flatten depth-first.
    sah_collapse(clusters[0]);
    RawVector<PrimRef> ordered;
    ordered.reserve(size_t(n));
    const int depth = flatten(clusters[0], nodes, ordered);
    refs_.swap(ordered);
    return depth;
  }

 private:
  struct TreeNode {
    AABB box;
    int left, right;  ///< children (-1 for a primitive)
    int prim;         ///< index into refs_ (leaves)
    int count;        ///< primitives below
    float cost;       ///< SAH cost of the subtree (area-weighted, unnormalized)
  };
  static constexpr int kRadius = 8;

  void sort_by_morton() {
    AABB cb;
    for (const PrimRef& r : refs_) {
      const v4f c = r.centroid2();
      cb.expand(Vec3f(c[0], c[1], c[2]));
    }
    const Vec3f ext = cb.extent();
    std::vector<std::pair<uint32_t, int>> keys(refs_.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, refs_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) {
        uint32_t code = 0;
        for (int a = 0; a < 3; ++a) {
          const float u = ext[a] > 0 ? (refs_[i].centroid2(a) - cb.lo[a]) / ext[a] : 0.0f;
          code |= spread_bits(uint32_t(std::clamp(u * 1024.0f, 0.0f, 1023.0f))) << (2 - a);
        }
        keys[i] = {code, int(i)};
      }
    });
    tbb::parallel_sort(keys.begin(), keys.end());  // pairs are distinct, so the order is unique
    RawVector<PrimRef> sorted(refs_.size());
    for (size_t i = 0; i < keys.size(); ++i) sorted[i] = refs_[size_t(keys[i].second)];
    refs_.swap(sorted);
  }

  int nearest_in_window(const std::vector<int>& clusters, int i) const {
    const int m = int(clusters.size());
    const AABB& bi = tree_[size_t(clusters[size_t(i)])].box;
    float best = std::numeric_limits<float>::infinity();
    int best_j = i == 0 ? 1 : i - 1;
    for (int j = std::max(0, i - kRadius); j <= std::min(m - 1, i + kRadius); ++j) {
      if (j == i) continue;
      AABB u = bi;
      u.expand(tree_[size_t(clusters[size_t(j)])].box);
      const float d = u.area();
      if (d < best) {  // ties keep the smaller j, so mutual pairs are well defined
        best = d;
        best_j = j;
      }
    }
    return best_j;
  }

  int merge(int a, int b) {
    TreeNode node{tree_[size_t(a)].box, a, b, -1, tree_[size_t(a)].count + tree_[size_t(b)].count, 0};
    node.box.expand(tree_[size_t(b)].box);
    tree_.push_back(node);
    return int(tree_.size()) - 1;
  }

  /// Fills cost bottom-up and turns subtrees into leaves (left = -2 marks a collapsed subtree) where cheaper.
  float sah_collapse(int id) {
    TreeNode& t = tree_[size_t(id)];
    if (t.left < 0) return t.cost = s_.intersection_cost * t.box.area();
    const float children = sah_collapse(t.left) + sah_collapse(tree_[size_t(id)].right);
    TreeNode& u = tree_[size_t(id)];
    const float area = u.box.area();
    const float as_leaf = s_.intersection_cost * leaf_tests(s_, u.count) * area;
    u.cost = s_.traversal_cost * area + children;
    if (u.count <= s_.max_leaf_size && as_leaf <= u.cost) {
      u.cost = as_leaf;
      u.prim = -2;  // collapsed
    }
    return u.cost;
  }

  void gather(int id, RawVector<PrimRef>& ordered) const {
    const TreeNode& t = tree_[size_t(id)];
    if (t.left < 0) {
      ordered.push_back(refs_[size_t(t.prim)]);
      return;
    }
    gather(t.left, ordered);
    gather(t.right, ordered);
  }

  int flatten(int id, RawVector<BvhNode>& nodes, RawVector<PrimRef>& ordered) const {
    const TreeNode& t = tree_[size_t(id)];
    const int self = int(nodes.size());
    nodes.push_back(BvhNode{t.box, int(ordered.size()), 0, 0});
    if (t.left < 0 || t.prim == -2) {
      gather(id, ordered);
      nodes[size_t(self)].count = uint16_t(t.count);
      return 1;
    }
    // Order the children along the axis that separates their centers most (for near-child-first traversal).
    int first = t.left, second = t.right;
    const Vec3f d = tree_[size_t(second)].box.center() - tree_[size_t(first)].box.center();
    const Vec3f ad = glm::abs(d);
    const int axis = ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2);
    if (d[axis] < 0) std::swap(first, second);
    nodes[size_t(self)].axis = uint16_t(axis);
    const int dl = flatten(first, nodes, ordered);
    nodes[size_t(self)].first = int(nodes.size());
    const int dr = flatten(second, nodes, ordered);
    return 1 + std::max(dl, dr);
  }

  const BvhSettings& s_;
  RawVector<PrimRef>& refs_;
  std::vector<TreeNode> tree_;
};

}  // namespace

int build_bottom_up(const BvhSettings& settings, RawVector<PrimRef>& refs, RawVector<BvhNode>& nodes) {
  return BottomUpBuilder(settings, refs).build(nodes);
}

}  // namespace tessera::bvh_build
