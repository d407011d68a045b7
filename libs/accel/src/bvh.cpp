// BVH construction: binned SAH top-down (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies")
// and the notes' bottom-up build by locally-ordered agglomerative clustering (Meister and Bittner 2017, PLOC).
#include "tessera/accel/bvh.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <memory>
#include <new>
#include <numeric>
#include <string>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {

namespace {

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

/// The surface areas of three boxes, lane a for box a (lane 3 unused): Box4::area's arithmetic on the transposed
/// extents. An empty box's extents are all negative and a valid one's none, so clamping them at 0 gives area 0 as
/// Box4::area does.
inline v4f areas(const Box4 (&b)[3]) {
  const v4f e0 = vmax(b[0].hi - b[0].lo, v4f{}), e1 = vmax(b[1].hi - b[1].lo, v4f{}),
            e2 = vmax(b[2].hi - b[2].lo, v4f{});
  const v4f xy = __builtin_shufflevector(e0, e1, 0, 4, 1, 5), zw = __builtin_shufflevector(e0, e1, 2, 6, 3, 7);
  const v4f x = __builtin_shufflevector(xy, e2, 0, 1, 4, 4), y = __builtin_shufflevector(xy, e2, 2, 3, 5, 5),
            z = __builtin_shufflevector(zw, e2, 0, 1, 6, 6);
  return 2.0f * (x * y + y * z + z * x);
}

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

/// Box and centroid bounds of a range of references.
struct RangeBounds {
  Box4 box, centroids;
  void add(const PrimRef& r) {
    box.expand(r.box);
    centroids.expand_point(r.centroid2());
  }
  void add(const RangeBounds& o) {
    box.expand(o.box);
    centroids.expand(o.centroids);
  }
};

/// The tests a leaf of n primitives costs: whole blocks of settings.leaf_block.
float leaf_tests(const BvhSettings& s, int n) {
  return float(unsigned(n + s.leaf_block - 1) >> std::countr_zero(unsigned(s.leaf_block)));
}

constexpr int kMinTaskPrims = 1024;       // ranges of this many or fewer are never split into parallel tasks
constexpr int kParallelBinning = 65536;   // ranges above this bin in parallel
constexpr int kParallelSplitMin = 16384;  // smaller ranges never bin or partition in parallel
constexpr int kMaxBins = 64;
constexpr int kMaxLeafCount = 65535;  // BvhNode::count is 16 bits
constexpr int kMedianLevel = 36;      // below this level splits are object medians (depth <= 36 + log2 n)

/// Min/max are exact in any order, so the parallel reductions below give the same tree for any thread count.
RangeBounds range_bounds(const PrimRef* refs, int n) {
  auto body = [refs](const tbb::blocked_range<int>& r, RangeBounds acc) {
    for (int i = r.begin(); i < r.end(); ++i) acc.add(refs[i]);
    return acc;
  };
  if (n < kParallelBinning) return body(tbb::blocked_range<int>(0, n), RangeBounds{});
  return tbb::parallel_reduce(tbb::blocked_range<int>(0, n, 8192), RangeBounds{}, body,
                              [](RangeBounds a, const RangeBounds& b) {
                                a.add(b);
                                return a;
                              });
}

/// Moves the references of refs[begin, end) for which is_left holds before the others; returns the first of the others
/// and accumulates both sides' centroid bounds.
///
/// Where the sides change often, branch-free in blocks (Edelkamp and Weiss 2016, "BlockQuicksort"): a branch on an
/// unpredictable side costs a misprediction, so a block of 64 from each end is classified first, recording the
/// misplaced references' offsets without a branch, and then as many pairs as both blocks have are swapped. Each
/// reference adds its centroid to its side's bounds with masks. The rest goes through the plain two-ended loop, where
/// counting a reference twice does no harm (the bounds are minima and maxima). Measured: bunny builds 9% faster;
/// blocks on a torus listed row by row (long runs) would cost 7%, hence the test of the first 64 references.
template <class IsLeft>
int partition(PrimRef* refs, int begin, int end, const IsLeft& is_left, RangeBounds& left, RangeBounds& right) {
  constexpr int kBlock = 64;
  constexpr int kMixed = 4;  // side changes among the first kBlock references that make the blocks pay
  const v4f inf = splat(std::numeric_limits<float>::infinity());
  v4f left_lo = inf, left_hi = -inf, right_lo = inf, right_hi = -inf;
  auto classify = [&](const PrimRef& r) {
    const bool l = is_left(r);
    const v4i mask = v4i{} - int(l);  // all ones for a left reference
    const v4i c = v4i(r.centroid2()), far_lo = v4i(inf), far_hi = v4i(-inf);
    left_lo = vmin(left_lo, v4f((c & mask) | (far_lo & ~mask)));
    left_hi = vmax(left_hi, v4f((c & mask) | (far_hi & ~mask)));
    right_lo = vmin(right_lo, v4f((c & ~mask) | (far_lo & mask)));
    right_hi = vmax(right_hi, v4f((c & ~mask) | (far_hi & mask)));
    return l;
  };
  uint8_t misplaced_l[kBlock], misplaced_r[kBlock];
  int start_l = 0, start_r = 0, count_l = 0, count_r = 0;
  int lo = begin, hi = end;  // [begin, lo) holds left references, [hi, end) right ones
  // Sides in long runs (meshes often list neighbouring triangles together) are predicted well by the plain loop, which
  // then costs half as much: the blocks are for ranges whose first references change side often.
  int changes = 0;
  if (end - begin >= 2 * kBlock)
    for (int k = begin + 1, previous = is_left(refs[begin]); k < begin + kBlock; ++k) {
      const int side = is_left(refs[k]);
      changes += side != previous;
      previous = side;
    }
  while (changes >= kMixed && hi - lo >= 2 * kBlock) {
    if (count_l == 0) {
      start_l = 0;
      for (int k = 0; k < kBlock; ++k) {
        misplaced_l[count_l] = uint8_t(k);
        count_l += !classify(refs[lo + k]);
      }
    }
    if (count_r == 0) {
      start_r = 0;
      for (int k = 0; k < kBlock; ++k) {
        misplaced_r[count_r] = uint8_t(k);
        count_r += classify(refs[hi - 1 - k]);
      }
    }
    const int pairs = std::min(count_l, count_r);
    for (int k = 0; k < pairs; ++k)
      std::swap(refs[lo + misplaced_l[start_l + k]], refs[hi - 1 - misplaced_r[start_r + k]]);
    count_l -= pairs;
    count_r -= pairs;
    start_l += pairs;
    start_r += pairs;
    if (count_l == 0) lo += kBlock;
    if (count_r == 0) hi -= kBlock;
  }
  // Local bounds: `left` and `right` might alias the references written by the swaps (both hold vectors), which would
  // keep them in memory, a chain of stores and loads through every step.
  Box4 lc{left_lo, left_hi}, rc{right_lo, right_hi};
  int i = lo, j = hi - 1;
  for (;;) {
    while (i <= j && is_left(refs[i])) lc.expand_point(refs[i++].centroid2());
    while (i <= j && !is_left(refs[j])) rc.expand_point(refs[j--].centroid2());
    if (i >= j) break;
    std::swap(refs[i], refs[j]);
    lc.expand_point(refs[i++].centroid2());
    rc.expand_point(refs[j--].centroid2());
  }
  left.centroids.expand(lc);
  right.centroids.expand(rc);
  return i;
}

/// partition() in parallel, with the same result. Both loops of partition() swap the k-th right reference before mid
/// (counting from begin) with the k-th left reference from mid on (counting back from end), so this does the same
/// by rank: blocks of a fixed size count their left references, which gives mid and each block's misplaced
/// references; then the blocks before mid swap theirs with their partners in parallel. About 1.5 times the work of
/// partition(), for ranges that would otherwise leave threads idle.
template <class IsLeft>
int parallel_partition(PrimRef* refs, int begin, int end, const IsLeft& is_left, RangeBounds& left,
                       RangeBounds& right) {
  constexpr int kBlock = 16384;
  const int blocks = (end - begin + kBlock - 1) / kBlock;
  auto block_begin = [&](int b) { return begin + b * kBlock; };
  auto block_end = [&](int b) { return std::min(end, begin + (b + 1) * kBlock); };
  struct Count {
    int lefts = 0;
    RangeBounds left, right;
  };
  std::vector<Count> counts(static_cast<size_t>(blocks));
  tbb::parallel_for(0, blocks, [&](int b) {
    Count& c = counts[size_t(b)];
    for (int i = block_begin(b); i < block_end(b); ++i) {
      if (is_left(refs[i])) {
        ++c.lefts;
        c.left.centroids.expand_point(refs[i].centroid2());
      } else {
        c.right.centroids.expand_point(refs[i].centroid2());
      }
    }
  });
  int mid = begin;
  for (const Count& c : counts) {
    mid += c.lefts;
    left.centroids.expand(c.left.centroids);
    right.centroids.expand(c.right.centroids);
  }
  // The misplaced references: right ones before mid, ranked from begin (low_before[b] lie in blocks before b), and
  // left ones from mid on, ranked from end (high_after[b] lie in blocks b and later).
  std::vector<int> low_before(static_cast<size_t>(blocks) + 1, 0), high_after(static_cast<size_t>(blocks) + 1, 0);
  for (int b = 0; b < blocks; ++b) {
    const int lo = block_begin(b), hi = block_end(b);
    int lefts_before_mid = counts[size_t(b)].lefts;
    if (hi > mid) {
      lefts_before_mid = 0;
      for (int i = lo; i < std::min(hi, mid); ++i) lefts_before_mid += is_left(refs[i]);
    }
    low_before[size_t(b) + 1] = low_before[size_t(b)] + std::max(0, std::min(hi, mid) - lo) - lefts_before_mid;
    high_after[size_t(b)] = counts[size_t(b)].lefts - lefts_before_mid;
  }
  for (int b = blocks - 1; b >= 0; --b) high_after[size_t(b)] += high_after[size_t(b) + 1];
  auto has_misplaced = [&](int b) { return low_before[size_t(b) + 1] > low_before[size_t(b)]; };
  // Where each block's first partner lies (all found before any swap, which would change what the search reads).
  std::vector<int> partner(static_cast<size_t>(blocks), end);
  tbb::parallel_for(0, blocks, [&](int b) {
    if (!has_misplaced(b)) return;
    const int rank = low_before[size_t(b)];
    int h = blocks - 1;
    while (high_after[size_t(h)] <= rank) --h;  // the block holding the rank-th left reference counted from end
    int j = block_end(h) - 1;
    for (int skip = rank - high_after[size_t(h) + 1];; --j)
      if (is_left(refs[j]) && skip-- == 0) break;
    partner[size_t(b)] = j;
  });
  tbb::parallel_for(0, blocks, [&](int b) {
    if (!has_misplaced(b)) return;
    int j = partner[size_t(b)];
    for (int i = block_begin(b); i < std::min(block_end(b), mid); ++i) {
      if (is_left(refs[i])) continue;
      while (!is_left(refs[j])) --j;  // the references between partners are right ones that stay
      std::swap(refs[i], refs[j--]);
    }
  });
  return mid;
}

/// Per-axis SAH bins (only the first `bins` of each axis are used and initialized; plain vectors, so that nothing
/// else is written: a split of a few primitives would otherwise spend its time clearing 192 boxes). Bin b of axis a
/// is slot a * kMaxBins + b of each array, so that one index addresses its box and its count.
struct Bins {
  v4f lo[3 * kMaxBins], hi[3 * kMaxBins];
  int count[3 * kMaxBins];
  explicit Bins(int bins) {
    for (int a = 0; a < 3; ++a)
      for (int b = a * kMaxBins; b < a * kMaxBins + bins; ++b) {
        lo[b] = splat(std::numeric_limits<float>::infinity());
        hi[b] = splat(-std::numeric_limits<float>::infinity());
        count[b] = 0;
      }
  }
  Bins() = default;  // uninitialized: only for parallel_reduce's identity copies, which are assigned before use
  void add(const Bins& o, int bins) {
    for (int a = 0; a < 3; ++a)
      for (int b = a * kMaxBins; b < a * kMaxBins + bins; ++b) {
        lo[b] = vmin(lo[b], o.lo[b]);
        hi[b] = vmax(hi[b], o.hi[b]);
        count[b] += o.count[b];
      }
  }
  /// Adds a box to the slot (axis * kMaxBins + bin).
  void add(unsigned slot, const Box4& box) {
    lo[slot] = vmin(lo[slot], box.lo);
    hi[slot] = vmax(hi[slot], box.hi);
    ++count[slot];
  }
  /// Bin b's counts on the three axes (lane a: axis a).
  v4i counts(int b) const { return v4i{count[b], count[kMaxBins + b], count[2 * kMaxBins + b], 0}; }
  Box4 box(int a, int b) const { return Box4{lo[a * kMaxBins + b], hi[a * kMaxBins + b]}; }
};

/// A split: axis, first bin of the right side (-1: none, the centroids coincide), SAH cost, the binning origin and
/// scale, and the boxes of the two sides (from the bins).
struct Split {
  int axis = 0, bin = -1;
  float cost = std::numeric_limits<float>::infinity();
  float lo = 0, scale = 0;
  Box4 left, right;
};

class SahBuilder {
 public:
  SahBuilder(const BvhSettings& s, RawVector<PrimRef>& refs)
      : s_(s),
        refs_(refs),
        threads_(tbb::this_task_arena::max_concurrency()),
        task_prims_(std::max<int64_t>(kMinTaskPrims, int64_t(refs.size()) / (16 * threads_))) {}

  /// Builds the subtree of refs[begin, end), whose bounds are rb, into the 2 n - 1 slots from `self` on (enough for
  /// any binary tree over n primitives), depth-first: its root at self, the left subtree from self + 1, the right one
  /// right after the left (serial ranges) or from self + 2 n_left (ranges built as parallel tasks, which thus write
  /// disjoint slots, and no node is ever moved). An interior node's `first` is the slot of its second child;
  /// compact_nodes() removes the gaps (one per parallel range, unwritten, so its pages are never touched) afterwards.
  /// Returns the depth and the node count of the subtree.
  struct Built {
    int depth, nodes;
  };
  Built build(int begin, int end, const RangeBounds& rb, BvhNode* slots, int self, int level = 0) const {
    const int n = end - begin;
    new (slots + self) BvhNode{rb.box.aabb(), begin, uint16_t(0), uint16_t(0)};
    BvhNode& node = slots[self];
    const bool fits = n <= s_.max_leaf_size;
    // A range of one block is a leaf without binning when a traversal step costs at least a test: every split costs
    // more than C_trav >= C_isect, the cost of the leaf.
    const bool one_block = fits && n <= s_.leaf_block && s_.traversal_cost >= s_.intersection_cost;
    const Split split = n > 1 && !one_block ? find_split(begin, n, rb) : Split{};
    if (n == 1 || (fits && s_.intersection_cost * leaf_tests(s_, n) <= split.cost)) {
      node.count = uint16_t(n);
      return {1, 1};
    }
    int mid;
    int axis = split.axis;
    RangeBounds left, right;
    PrimRef* refs = refs_.data();
    if (level >= kMedianLevel || split.bin < 0) {
      // The object median on the longest centroid axis: guards the depth bound on adversarial inputs, and halves a
      // range too large for a leaf whose centroids all coincide.
      const v4f ce = rb.centroids.hi - rb.centroids.lo;
      axis = ce[0] >= ce[1] && ce[0] >= ce[2] ? 0 : (ce[1] >= ce[2] ? 1 : 2);
      mid = begin + n / 2;
      std::nth_element(refs + begin, refs + mid, refs + end, [axis](const PrimRef& a, const PrimRef& b) {
        const float ca = a.centroid2(axis), cb = b.centroid2(axis);
        return ca < cb || (ca == cb && a.index() < b.index());
      });
      left = range_bounds(refs + begin, mid - begin);
      right = range_bounds(refs + mid, end - mid);
    } else {
      // Partition by bin, accumulating the centroid bounds of both sides on the way (boxes come from the bins).
      auto is_left = [&](const PrimRef& r) { return bin_of(r.centroid2(axis), split.lo, split.scale) < split.bin; };
      mid = large_share(n) ? parallel_partition(refs, begin, end, is_left, left, right)
                           : partition(refs, begin, end, is_left, left, right);
      left.box = split.left;
      right.box = split.right;
    }
    node.axis = uint16_t(axis);
    Built l, r;
    if (n > task_prims_) {
      node.first = self + 2 * (mid - begin);
      tbb::parallel_invoke([&] { l = build(begin, mid, left, slots, self + 1, level + 1); },
                           [&] { r = build(mid, end, right, slots, node.first, level + 1); });
    } else {
      l = build(begin, mid, left, slots, self + 1, level + 1);
      node.first = self + 1 + l.nodes;
      r = build(mid, end, right, slots, node.first, level + 1);
    }
    return {1 + std::max(l.depth, r.depth), 1 + l.nodes + r.nodes};
  }

 private:
  static int bin_of(float c, float lo, float scale) { return int((c - lo) * scale); }

  /// The least-cost split among the bin boundaries of the three axes.
  Split find_split(int begin, int n, const RangeBounds& rb) const {
    const int nb = std::min(s_.bins, std::max(4, n));  // a handful of primitives needs no more bins than itself
    const v4f clo = rb.centroids.lo, cext = rb.centroids.hi - rb.centroids.lo;
    v4f scale;  // slightly below bins / extent, so the largest centroid falls in the last bin
    for (int a = 0; a < 3; ++a) scale[a] = cext[a] > 0 ? float(nb) * (1.0f - 1e-5f) / cext[a] : 0.0f;
    scale[3] = 0;
    const PrimRef* refs = refs_.data() + begin;
    const v4f last = splat(float(nb - 1));
    auto bin_one = [&](const PrimRef& p, Bins& into) {
      // Clamped before the truncation, which gives the bins of clamping after it (SSE2 has no integer min/max).
      const v4i slot = __builtin_convertvector(vmin(vmax((p.centroid2() - clo) * scale, v4f{}), last), v4i) +
                       v4i{0, kMaxBins, 2 * kMaxBins, 0};
      for (int a = 0; a < 3; ++a) into.add(unsigned(slot[a]), p.box);
    };
    auto bin_into = [&](int first, int last_index, Bins& acc) {
      if (last_index - first < 256) {
        for (int i = first; i < last_index; ++i) bin_one(refs[i], acc);
        return;
      }
      // Neighbouring primitives mostly fall in the same bins: alternating two sets of bins halves the chains of
      // read-modify-writes through the same memory.
      Bins odd(nb);
      int i = first;
      for (; i + 1 < last_index; i += 2) {
        bin_one(refs[i], acc);
        bin_one(refs[i + 1], odd);
      }
      if (i < last_index) bin_one(refs[i], acc);
      acc.add(odd, nb);
    };
    Bins bins(nb);
    if (n < kParallelBinning && !large_share(n)) {
      bin_into(0, n, bins);
    } else {
      bins = tbb::parallel_reduce(
          tbb::blocked_range<int>(0, n, 8192), Bins(nb),
          [&](const tbb::blocked_range<int>& r, Bins acc) {
            bin_into(r.begin(), r.end(), acc);
            return acc;
          },
          [nb](Bins a, const Bins& b) {
            a.add(b, nb);
            return a;
          });
    }
    // The three axes are swept at once, one lane each (their areas from the transposed extents): first from the
    // right, for the right sides' costs and counts, then from the left. Each lane keeps its first least cost, so the
    // candidates win in the order (axis, bin) below, as in a scalar sweep; the arithmetic is the scalar one's.
    const v4f k = splat(s_.intersection_cost * (1.0f / rb.box.area())), trav = splat(s_.traversal_cost);
    const v4i round_up = v4i{} + (s_.leaf_block - 1);
    const int block_shift = std::countr_zero(unsigned(s_.leaf_block));
    auto side_cost = [&](const Box4 (&acc)[3], v4i count) {  // area times leaf_tests(count), per axis
      return areas(acc) * __builtin_convertvector((count + round_up) >> block_shift, v4f);
    };
    v4f right_cost[kMaxBins];
    v4i right_count[kMaxBins];
    Box4 acc[3];
    v4i cnt{};
    for (int b = nb - 1; b > 0; --b) {
      for (int a = 0; a < 3; ++a) acc[a].expand(bins.box(a, b));
      cnt += bins.counts(b);
      right_cost[b] = side_cost(acc, cnt);
      right_count[b] = cnt;
    }
    v4f best_cost = splat(std::numeric_limits<float>::infinity());
    v4i best_bin = v4i{} - 1;
    for (int a = 0; a < 3; ++a) acc[a] = Box4{};
    cnt = v4i{};
    for (int b = 1; b < nb; ++b) {
      for (int a = 0; a < 3; ++a) acc[a].expand(bins.box(a, b - 1));
      cnt += bins.counts(b - 1);
      // SAH: C = C_trav + C_isect (A_L N_L + A_R N_R) / A.
      const v4f cost = trav + k * (side_cost(acc, cnt) + right_cost[b]);
      const v4i better = (cnt != 0) & (right_count[b] != 0) & (cost < best_cost);
      best_cost = better ? cost : best_cost;
      best_bin = better ? b : best_bin;
    }
    Split best;
    for (int a = 0; a < 3; ++a)
      if (cext[a] > 0 && best_bin[a] >= 0 && best_cost[a] < best.cost) {
        best.axis = a;
        best.bin = best_bin[a];
        best.cost = best_cost[a];
      }
    if (best.bin >= 0) {
      best.lo = clo[best.axis];
      best.scale = scale[best.axis];
      for (int b = 0; b < best.bin; ++b) best.left.expand(bins.box(best.axis, b));
      for (int b = best.bin; b < nb; ++b) best.right.expand(bins.box(best.axis, b));
    }
    return best;
  }

  /// Whether a range of n references is so large a share of all that the tasks of other ranges cannot keep the
  /// threads busy meanwhile (the root, on 2 threads): then it bins and partitions with all threads. The parallel forms
  /// give the same result as the serial ones, so the tree does not depend on the thread count.
  bool large_share(int n) const { return n >= kParallelSplitMin && int64_t(n) * threads_ >= 2 * int64_t(refs_.size()); }

  const BvhSettings& s_;
  RawVector<PrimRef>& refs_;
  int threads_;
  // Ranges above this build their halves as parallel tasks: about 16 tasks per thread, fine enough to balance 16
  // threads on a small mesh (bunny +15% there, against 4096 always) without the overhead of small tasks on 1 or 2.
  // The compacted tree does not depend on where the tasks split.
  int64_t task_prims_;
};

/// Copies the tree that SahBuilder::build left in gapped slots from `slot` on into out[next...] (depth-first, gaps
/// removed, second-child links renumbered); returns the next free index of out.
int compact_nodes(const BvhNode* slots, int slot, BvhNode* out, int next) {
  const int self = next;
  out[self] = slots[slot];
  if (out[self].count > 0) return next + 1;
  next = compact_nodes(slots, slot + 1, out, next + 1);
  out[self].first = next;
  return compact_nodes(slots, slots[slot].first, out, next);
}

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

Bvh::Bvh(std::span<const AABB> prim_bounds, const BvhSettings& settings)
    : Bvh(prim_bounds.size(), [prim_bounds](size_t i) { return prim_bounds[i]; }, settings) {}

Bvh::Bvh(size_t count, const std::function<AABB(size_t)>& prim_box, const BvhSettings& settings)
    : settings_(settings) {
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
      } else if (!std::isfinite(b.lo.x) || !std::isfinite(b.lo.y) || !std::isfinite(b.lo.z) ||
                 !std::isfinite(b.hi.x) || !std::isfinite(b.hi.y) || !std::isfinite(b.hi.z)) {
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
    depth_ = BottomUpBuilder(settings_, refs).build(nodes_);
    if (depth_ > kMaxDepth) {  // a degenerate input can chain clusters: fall back to the top-down build
      nodes_.clear();
    }
  }
  if (nodes_.empty()) {
    // Uninitialized slots on huge pages: only the nodes written are touched (about n / 2 of the 2 n - 1 for leaves
    // of 4), and with 4 KiB pages their first touches (page faults) cost as much as the binning.
    RawVector<BvhNode> storage(2 * refs.size() - 1);
    BvhNode* slots = storage.data();
    const auto built =
        SahBuilder(settings_, refs).build(0, int(refs.size()), range_bounds(refs.data(), int(refs.size())), slots, 0);
    depth_ = built.depth;
    nodes_.resize(size_t(built.nodes));
    compact_nodes(slots, 0, nodes_.data(), 0);
  }
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
