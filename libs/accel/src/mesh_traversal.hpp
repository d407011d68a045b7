#pragma once
// The wide-BVH traversal of MeshAccel, one template for both widths: included by mesh_accel.cpp (4 wide, SSE, the
// x86-64 baseline) and mesh_accel_avx2.cpp (8 wide, compiled for AVX2). No floating-point contraction in either, so
// both compute bit-identical triangle results (the same operations in the same order as a scalar Moller-Trumbore).
#include <immintrin.h>

#include <cmath>
#include <cstdint>
#include <new>
#include <span>
#include <utility>

#include "mesh_tree.hpp"
#include "tessera/accel/mesh_accel.hpp"

namespace tessera::mesh_traversal {

/// The entry points: 4 wide with SSE (mesh_accel.cpp), 8 wide with AVX2 (mesh_accel_avx2.cpp), over the tree's lines
/// (see mesh_tree::node_ref). intersect fills hit as MeshAccel::intersect documents; intersect_stream fills hits[i] for
/// rays[i] the same way (Hit{} for a miss). far_tree: the tree mostly comes from memory, not from the caches, and what
/// a walk needs later is fetched into L2 instead of L1 (see Traversal).
using Tree = const mesh_tree::CacheLine*;
bool intersect4(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats, bool far_tree);
void intersect_stream4(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits, bool far_tree);
bool occluded4(Tree tree, int32_t root, const Ray& ray, bool far_tree);
bool intersect8(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats, bool far_tree);
void intersect_stream8(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits, bool far_tree);
bool occluded8(Tree tree, int32_t root, const Ray& ray, bool far_tree);

// Everything below is compiled once per including file (an unnamed namespace), so the AVX2 file's copies never replace
// the baseline file's at link time.
namespace {

/// The SIMD types of one node width (4 is also the triangle blocks' width).
template <int W>
struct Lanes;
template <>
struct Lanes<4> {
  typedef float vf __attribute__((vector_size(16)));
  typedef int32_t vi __attribute__((vector_size(16)));
  static int mask(vi m) { return _mm_movemask_ps(reinterpret_cast<__m128>(m)); }
};
template <>
struct Lanes<8> {
  typedef float vf __attribute__((vector_size(32)));
  typedef int32_t vi __attribute__((vector_size(32)));
#ifdef __AVX__
  static int mask(vi m) { return _mm256_movemask_ps(reinterpret_cast<__m256>(m)); }
#endif
};

using v4f = Lanes<4>::vf;
using v4i = Lanes<4>::vi;

/// x in every lane (one broadcast; GCC builds the vector lane by lane from a loop, and the traversal splats the
/// shrinking tmax at every node).
template <int W>
typename Lanes<W>::vf splat(float x) {
  if constexpr (W == 4) {
    return reinterpret_cast<typename Lanes<4>::vf>(_mm_set1_ps(x));
  } else {
    return reinterpret_cast<typename Lanes<8>::vf>(_mm256_set1_ps(x));
  }
}

/// A ray's origin and direction, splatted.
struct RayLanes {
  v4f ox, oy, oz, dx, dy, dz;
  explicit RayLanes(const Ray& r)
      : ox(splat<4>(r.origin.x)),
        oy(splat<4>(r.origin.y)),
        oz(splat<4>(r.origin.z)),
        dx(splat<4>(r.dir.x)),
        dy(splat<4>(r.dir.y)),
        dz(splat<4>(r.dir.z)) {}
};

/// Four triangles against one ray (Moller-Trumbore, operation by operation as a scalar float Moller-Trumbore with glm
/// cross and dot: the same rounding). Returns the mask of lanes that hit with t in [tmin, tmax] and their t, b1, b2.
inline int hit_block(const mesh_tree::TriangleBlock& b, const RayLanes& r, float tmin, float tmax, v4f& t, v4f& b1,
                     v4f& b2) {
  const auto row = [](const float(&v)[4]) { return *reinterpret_cast<const v4f*>(v); };
  const v4f e1x = row(b.e1[0]), e1y = row(b.e1[1]), e1z = row(b.e1[2]);
  const v4f e2x = row(b.e2[0]), e2y = row(b.e2[1]), e2z = row(b.e2[2]);
  // p = dir x e2, det = e1 . p
  const v4f px = r.dy * e2z - e2y * r.dz, py = r.dz * e2x - e2z * r.dx, pz = r.dx * e2y - e2x * r.dy;
  const v4f det = e1x * px + e1y * py + e1z * pz;
  const v4f inv = splat<4>(1.0f) / det;
  const v4f tvx = r.ox - row(b.v0[0]), tvy = r.oy - row(b.v0[1]), tvz = r.oz - row(b.v0[2]);
  b1 = (tvx * px + tvy * py + tvz * pz) * inv;
  // q = tv x e1
  const v4f qx = tvy * e1z - e1y * tvz, qy = tvz * e1x - e1z * tvx, qz = tvx * e1y - e1x * tvy;
  b2 = (r.dx * qx + r.dy * qy + r.dz * qz) * inv;
  t = (e2x * qx + e2y * qy + e2z * qz) * inv;
  const v4f zero = splat<4>(0.0f), one = splat<4>(1.0f);
  // The scalar kernel's rejections, negated literally (a NaN passes a rejection just as it does there).
  const v4i ok = (det != zero) & ~(b1 < zero) & ~(b1 > one) & ~(b2 < zero) & ~(b1 + b2 > one) & (t >= splat<4>(tmin)) &
                 (t <= splat<4>(tmax));
  return Lanes<4>::mask(ok);
}

/// The nearest triangle found so far: its block (in 32-byte units) and lane, and its barycentrics.
struct Nearest {
  int block = -1, lane = 0;
  float b1 = 0, b2 = 0;
};

/// The node of a node reference, and the block at a 32-byte unit.
template <int W>
const mesh_tree::WideNode<W>& node_at(Tree tree, int32_t ref) {
  return *reinterpret_cast<const mesh_tree::WideNode<W>*>(tree + mesh_tree::node_line(ref));
}
inline const mesh_tree::TriangleBlock& block_at(Tree tree, int unit) {
  return *reinterpret_cast<const mesh_tree::TriangleBlock*>(reinterpret_cast<const char*>(tree) + size_t(unit) * 32);
}
constexpr int kBlockUnits = sizeof(mesh_tree::TriangleBlock) / 32;
static_assert(sizeof(mesh_tree::TriangleBlock) % 32 == 0);

/// One ray's walk through the wide tree, a node at a time: an interior node's children tested at once, the hit ones
/// visited nearest entry first (the rest on a stack with their entry distances, skipped when popped beyond the current
/// nearest hit). Nearest hit (AnyHit false: keeps the nearest, shrinks ray().tmax) or any hit (AnyHit true: stops at
/// the first); Stats counts into stats. A one-ray cast steps it to the end; a stream interleaves the steps of several
/// (the same operations in the same order per ray, so both give bit-identical hits).
///
/// Where a walk fetches the nodes it visits later: L1 (_MM_HINT_T0), or L2 (_MM_HINT_T1) for a tree that mostly comes
/// from memory. There, fetches into L1 wait on its few miss buffers; into L2 they do not, and the later load costs an
/// L2 hit. `Children` is where a node's hit children go (fetched as they are pushed); a stream says where its walks'
/// next nodes go (prefetch_current). What a step needs at once (a node's child line and leaf blocks) goes to L1.
///
/// LeavesWithNode: fetching a node also fetches the leaf blocks laid out after it, before the walk knows which of them
/// it will enter. That hides a miss for a walk that has nothing else to do; a stream over a far tree has its other
/// walks to overlap, and there the speculative lines only fill the miss buffers (see nearest_hits).
template <int W, bool AnyHit, bool Stats, int Children, bool LeavesWithNode = true>
class Traversal {
  using vf = typename Lanes<W>::vf;

 public:
  Traversal(Tree tree, int32_t root, TraversalStats* stats = nullptr) : tree_(tree), root_(root), stats_(stats) {}

  /// Begins the walk of `ray` at the root.
  void start(const Ray& ray) {
    ray_ = ray;
    // Near planes by the direction's sign bit (so -0 counts as negative, as 1 / -0 = -inf); far distances enlarged
    // by 2 gamma(3) (pbrt's conservative rounding), so a ray grazing a box edge is never lost.
    const v4f inv = splat<4>(1.0f) / v4f{ray.dir.x, ray.dir.y, ray.dir.z, 1.0f};  // one division, not three
    for (int a = 0; a < 3; ++a) {
      near_[a] = std::signbit(ray.dir[a]) ? 3 + a : a;
      far_[a] = (near_[a] + 3) % 6;
      origin_[a] = splat<W>(ray.origin[a]);
      inv_[a] = splat<W>(inv[a]);
      inv_far_[a] = splat<W>(inv[a] * RayBoxTest::kRobust);
    }
    tmin_ = splat<W>(ray.tmin);
    sp_ = 0;
    cur_ = root_;
    hit_ = false;
  }

  /// Visits the current node (an interior node's child boxes, or a leaf's triangles) and moves on to the next; false
  /// when the walk is over (the stack is empty, or AnyHit and a hit was found).
  // Inlined into each loop: the one-ray loop then keeps the walk in registers (an out-of-line step cost it 7%).
  [[gnu::always_inline]] bool step() {
    if (cur_ >= 0) {
      if (descend()) return true;
    } else if (test_leaf()) {
      return false;
    }
    // Pop the nearest pending subtree that may still hold a nearer hit.
    do {
      if (sp_ == 0) return false;
      --sp_;
    } while (stack_[sp_].dist > ray_.tmax);
    cur_ = stack_[sp_].ref;
    return true;
  }

  /// Asks the caches (L1 with _MM_HINT_T0, L2 with _MM_HINT_T1) for the node or leaf that the next step visits.
  template <int Hint>
  void prefetch_current() const {
    if (cur_ >= 0) {
      prefetch<Hint>(cur_);
    } else {
      // All the leaf's blocks (measured 4% faster streams on the 1M torus than the first block alone).
      prefetch_lines<Hint>(&block_at(tree_, mesh_tree::leaf_first_unit(cur_)),
                           size_t(mesh_tree::leaf_block_count(cur_)) * sizeof(mesh_tree::TriangleBlock));
    }
  }

  /// The tree walked.
  Tree tree() const { return tree_; }
  /// The ray, its tmax shrunk to the nearest hit so far.
  const Ray& ray() const { return ray_; }
  /// Whether a hit was found, and (nearest hit) which.
  bool hit() const { return hit_; }
  const Nearest& nearest() const { return nearest_; }

 private:
  struct Entry {
    int32_t ref;
    float dist;
  };

  /// Fetches every cache line of [p, p + bytes) (blocks need not start a line) into L1 (_MM_HINT_T0) or L2
  /// (_MM_HINT_T1; inline assembly, because GCC 12 emitted no prefetcht1 at all for _mm_prefetch in these loops).
  template <int Hint>
  static void prefetch_lines(const void* p, size_t bytes) {
    static_assert(Hint == _MM_HINT_T0 || Hint == _MM_HINT_T1);
    const uintptr_t begin = reinterpret_cast<uintptr_t>(p);
    for (uintptr_t line = begin & ~uintptr_t(63); line < begin + bytes; line += 64)
      if constexpr (Hint == _MM_HINT_T0)
        _mm_prefetch(reinterpret_cast<const char*>(line), _MM_HINT_T0);
      else
        asm volatile("prefetcht1 %0" : : "m"(*reinterpret_cast<const char*>(line)));
  }

  /// Fetches a node (and the leaf blocks that follow it, when LeavesWithNode), or a leaf's first block, for a later
  /// step.
  template <int Hint = Children>
  void prefetch(int32_t ref) const {
    if (ref >= 0)
      prefetch_lines<Hint>(&node_at<W>(tree_, ref), sizeof(mesh_tree::WideNode<W>) + 64 * size_t(leaf_lines(ref)));
    else
      prefetch_lines<Hint>(&block_at(tree_, mesh_tree::leaf_first_unit(ref)), sizeof(mesh_tree::TriangleBlock));
  }

  /// The lines of leaf blocks fetched with node ref.
  static int leaf_lines(int32_t ref) { return LeavesWithNode ? mesh_tree::node_leaf_lines(ref) : 0; }

  /// Tests the children of interior node cur_ and moves to the nearest hit one (the others on the stack); false when
  /// none is hit.
  [[gnu::always_inline]] bool descend() {
    const mesh_tree::WideNode<W>& n = node_at<W>(tree_, cur_);
    // The children's line is needed only once the box test is done: fetch it with the boxes, not after them. So are
    // the blocks of the leaf children, which follow the node: fetched now, they arrive with the node instead of one
    // miss later (measured 10-30% more incoherent rays on a 1M mesh; the node test takes a fraction of a miss).
    _mm_prefetch(reinterpret_cast<const char*>(n.child), _MM_HINT_T0);
    for (int l = 0; l < leaf_lines(cur_); ++l)
      _mm_prefetch(reinterpret_cast<const char*>(&n + 1) + 64 * l, _MM_HINT_T0);
    if constexpr (Stats) ++stats_->nodes;
    const auto row = [&n](int r) { return *reinterpret_cast<const vf*>(n.box[r]); };
    // max(a, b) as a > b ? a : b: a NaN (0 * inf, origin on a slab plane of a parallel ray) leaves b.
    vf t0 = (row(near_[0]) - origin_[0]) * inv_[0], tn = t0 > tmin_ ? t0 : tmin_;
    t0 = (row(near_[1]) - origin_[1]) * inv_[1], tn = t0 > tn ? t0 : tn;
    t0 = (row(near_[2]) - origin_[2]) * inv_[2], tn = t0 > tn ? t0 : tn;
    const vf tmax = splat<W>(ray_.tmax);
    vf t1 = (row(far_[0]) - origin_[0]) * inv_far_[0], tf = t1 < tmax ? t1 : tmax;
    t1 = (row(far_[1]) - origin_[1]) * inv_far_[1], tf = t1 < tf ? t1 : tf;
    t1 = (row(far_[2]) - origin_[2]) * inv_far_[2], tf = t1 < tf ? t1 : tf;
    unsigned mask = unsigned(Lanes<W>::mask(tn <= tf));
    if (mask == 0) return false;
    const int a = __builtin_ctz(mask);
    mask &= mask - 1;
    if (mask == 0) {
      cur_ = n.child[a];
      return true;
    }
    // Children that go on the stack are fetched at once (as Embree does): most are popped later, and their misses
    // then overlap the work on the nearer subtree instead of following it (10% more incoherent rays on a 1M mesh).
    const int b = __builtin_ctz(mask);
    mask &= mask - 1;
    if (mask == 0) {
      // Two: the nearer now, the other on the stack.
      prefetch(n.child[a]);
      prefetch(n.child[b]);
      if (tn[a] <= tn[b]) {
        stack_[sp_++] = Entry{n.child[b], tn[b]};
        cur_ = n.child[a];
      } else {
        stack_[sp_++] = Entry{n.child[a], tn[a]};
        cur_ = n.child[b];
      }
      return true;
    }
    // Three or more: push all, sorted so that the nearest is on top (insertion sort; ties keep lane order).
    int sp = sp_;
    const int base = sp;
    stack_[sp++] = Entry{n.child[a], tn[a]};
    stack_[sp++] = Entry{n.child[b], tn[b]};
    do {
      const int c = __builtin_ctz(mask);
      mask &= mask - 1;
      stack_[sp++] = Entry{n.child[c], tn[c]};
    } while (mask);
    for (int i = base; i < sp; ++i) prefetch(stack_[i].ref);
    for (int i = base + 1; i < sp; ++i) {
      const Entry e = stack_[i];
      int j = i;
      for (; j > base && stack_[j - 1].dist < e.dist; --j) stack_[j] = stack_[j - 1];
      stack_[j] = e;
    }
    cur_ = stack_[--sp].ref;
    sp_ = sp;
    return true;
  }

  /// Tests the triangles of leaf cur_: true when AnyHit and one is hit; else keeps the nearest hit.
  [[gnu::always_inline]] bool test_leaf() {
    const int first = mesh_tree::leaf_first_unit(cur_), count = mesh_tree::leaf_block_count(cur_);
    // Splatted here from ray_, not kept in the walk: six fewer registers live across the node tests (no spills).
    const RayLanes lanes(ray_);
    for (int k = first; k < first + count * kBlockUnits; k += kBlockUnits) {
      v4f t, b1, b2;
      const mesh_tree::TriangleBlock& block = block_at(tree_, k);
      int m = hit_block(block, lanes, ray_.tmin, ray_.tmax, t, b1, b2);
      if constexpr (Stats) {
        const v4i used = *reinterpret_cast<const v4i*>(block.index) >= v4i{0, 0, 0, 0};
        stats_->prims += __builtin_popcount(unsigned(Lanes<4>::mask(used)));
      }
      if (m == 0) continue;
      if constexpr (AnyHit) {
        hit_ = true;
        return true;
      } else {
        // The nearest lane; among equal t the last, as the scalar loop that accepts t <= tmax would keep. Without
        // branches (a loop over the hit lanes mispredicted): the least t of the hit lanes, then the last lane with it.
        const v4f th = (v4i{1, 2, 4, 8} & m) != 0 ? t : splat<4>(INFINITY);
        v4f least = __builtin_shufflevector(th, th, 1, 0, 3, 2);
        least = th < least ? th : least;
        const v4f swapped = __builtin_shufflevector(least, least, 2, 3, 0, 1);
        least = least < swapped ? least : swapped;
        const int lane = 31 - __builtin_clz(unsigned(Lanes<4>::mask(th == least)));
        const float best = t[lane];
        ray_.tmax = best;
        nearest_ = Nearest{k, lane, b1[lane], b2[lane]};
        hit_ = true;
      }
    }
    return false;
  }

  Tree tree_;
  int32_t root_;
  TraversalStats* stats_;
  Ray ray_;
  vf origin_[3], inv_[3], inv_far_[3], tmin_;
  int near_[3], far_[3];
  int sp_ = 0;
  int32_t cur_ = 0;
  bool hit_ = false;
  Nearest nearest_;
  Entry stack_[Bvh::kMaxDepth * W];  // last: a stream's walks then touch their state and stack top in few lines
};

/// Fills hit from a finished nearest-hit walk (see MeshAccel::intersect); false (hit untouched) for a miss.
template <int W, bool Stats, int Children, bool LeavesWithNode>
[[gnu::always_inline]] inline bool fill_hit(const Traversal<W, false, Stats, Children, LeavesWithNode>& walk,
                                            Hit& hit) {
  if (!walk.hit()) return false;
  const Nearest& nearest = walk.nearest();
  const mesh_tree::TriangleBlock& b = block_at(walk.tree(), nearest.block);
  const int l = nearest.lane;
  const Vec3f e1(b.e1[0][l], b.e1[1][l], b.e1[2][l]), e2(b.e2[0][l], b.e2[1][l], b.e2[2][l]);
  const Ray& ray = walk.ray();
  hit.t = ray.tmax;
  hit.point = ray.at(ray.tmax);
  hit.normal = glm::normalize(glm::cross(e1, e2));
  hit.uv = Vec2f(nearest.b1, nearest.b2);
  hit.prim = b.index[l];
  return true;
}

/// The nearest hit of one ray (see MeshAccel::intersect), with or without counting (separate instantiations, so the
/// counting costs nothing when off). A far tree's children are fetched into L2. Measured on an AMD EPYC, 1M torus:
/// incoherent rays about 5% faster (-5% to +17% over three sets of interleaved runs), coherent primary rays 4% slower
/// (their nodes are mostly in the caches, as a small tree's are: 5% slower there).
template <int W, bool Stats, int Children>
bool nearest_hit(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats) {
  Traversal<W, false, Stats, Children> walk(tree, root, stats);
  walk.start(ray);
  while (walk.step()) {
  }
  ray.tmax = walk.ray().tmax;
  return fill_hit(walk, hit);
}

template <int W>
bool nearest_hit(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats, bool far_tree) {
  if (stats) return nearest_hit<W, true, _MM_HINT_T0>(tree, root, ray, hit, stats);
  return far_tree ? nearest_hit<W, false, _MM_HINT_T1>(tree, root, ray, hit, nullptr)
                  : nearest_hit<W, false, _MM_HINT_T0>(tree, root, ray, hit, nullptr);
}

/// Whether any triangle is hit with t in [ray.tmin, ray.tmax].
template <int W, int Children>
bool any_hit(Tree tree, int32_t root, const Ray& ray) {
  Traversal<W, true, false, Children> walk(tree, root);
  walk.start(ray);
  while (walk.step()) {
  }
  return walk.hit();
}

template <int W>
bool any_hit(Tree tree, int32_t root, const Ray& ray, bool far_tree) {
  return far_tree ? any_hit<W, _MM_HINT_T1>(tree, root, ray) : any_hit<W, _MM_HINT_T0>(tree, root, ray);
}

/// The nearest hits of a stream of rays: kInFlight walks interleaved a node at a time, each asking the caches for its
/// next node before the others take their turns, so that several misses are pending at once instead of one per ray.
/// Next: where to (_MM_HINT_T1, L2, for a far tree: measured on an AMD EPYC, 1M torus, 15-20% more rays; on trees in
/// the caches 5-20% fewer). The children stay fetched into L1 (into L2 too: 5-10% fewer rays on the torus).
/// Over a far tree a node comes without its leaf blocks (a leaf's blocks are fetched when a walk is about to enter
/// it): those walks were bound by the miss buffers, not by latency (a third of the time stalled on issuing the
/// prefetches of nodes), and the speculative leaf lines took buffers from the nodes that the walks do visit. Measured
/// on the 1M torus: 10-15% more rays; the bunny, whose tree sits in the caches, is 5-10% slower without them.
template <int W, int Next>
void nearest_hits(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits) {
  constexpr int kInFlight = 12;
  using Walk = Traversal<W, false, false, _MM_HINT_T0, Next != _MM_HINT_T1>;
  alignas(Walk) unsigned char storage[kInFlight][sizeof(Walk)];
  Walk* walks[kInFlight];
  size_t index[kInFlight];
  size_t next = 0;
  int active = 0;
  for (; active < kInFlight && next < rays.size(); ++active, ++next) {
    walks[active] = new (storage[active]) Walk(tree, root);
    walks[active]->start(rays[next]);
    index[active] = next;
  }
  // Round robin over the active walks; a finished walk's slot takes the next ray, or is closed by the last active one.
  for (int k = 0; active > 0;) {
    Walk& walk = *walks[k];
    if (walk.step()) {
      walk.template prefetch_current<Next>();
    } else {
      Hit& hit = hits[index[k]];
      hit = Hit{};
      fill_hit(walk, hit);
      if (next < rays.size()) {
        walk.start(rays[next]);
        walk.template prefetch_current<Next>();
        index[k] = next++;
      } else {
        --active;
        std::swap(walks[k], walks[active]);
        std::swap(index[k], index[active]);
        if (k >= active) k = 0;
        continue;
      }
    }
    if (++k == active) k = 0;
  }
}

template <int W>
void nearest_hits(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits, bool far_tree) {
  if (far_tree)
    nearest_hits<W, _MM_HINT_T1>(tree, root, rays, hits);
  else
    nearest_hits<W, _MM_HINT_T0>(tree, root, rays, hits);
}

}  // namespace
}  // namespace tessera::mesh_traversal
