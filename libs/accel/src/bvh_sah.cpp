// The top-down BVH build by binned SAH (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"),
// parallel with oneTBB and deterministic (the same tree for any thread count).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <new>
#include <vector>

#include "bvh_build.hpp"

namespace tessera::bvh_build {

namespace {

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

constexpr int kMinTaskPrims = 1024;       // ranges of this many or fewer are never split into parallel tasks
constexpr int kParallelBinning = 65536;   // ranges above this bin in parallel
constexpr int kParallelSplitMin = 16384;  // smaller ranges never bin or partition in parallel
constexpr int kMedianLevel = 36;          // below this level splits are object medians (depth <= 36 + log2 n)

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
    auto side_cost = [&](const Box4(&acc)[3], v4i count) {  // area times leaf_tests(count), per axis
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

}  // namespace

int build_binned_sah(const BvhSettings& settings, RawVector<PrimRef>& refs, RawVector<BvhNode>& nodes) {
  // Uninitialized slots on huge pages: only the nodes written are touched (about n / 2 of the 2 n - 1 for leaves
  // of 4), and with 4 KiB pages their first touches (page faults) cost as much as the binning.
  RawVector<BvhNode> storage(2 * refs.size() - 1);
  BvhNode* slots = storage.data();
  const auto built =
      SahBuilder(settings, refs).build(0, int(refs.size()), range_bounds(refs.data(), int(refs.size())), slots, 0);
  nodes.resize(size_t(built.nodes));
  compact_nodes(slots, 0, nodes.data(), 0);
  return built.depth;
}

}  // namespace tessera::bvh_build
