// Ray casting of triangle meshes: the binary Bvh collapsed into a wide tree with triangles packed 4 to a block.
#include "tessera/accel/mesh_accel.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "mesh_traversal.hpp"
#include "mesh_tree.hpp"
#include "tessera/core/cpu.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"

namespace tessera {

namespace {

/// Builds the wide tree from the binary one and lays it out in MeshAccel's array of cache lines.
///
/// Collapse: the SAH-optimal choice of which binary nodes become wide nodes, leaves or neither (Pinto 2010, "Fast
/// SAH-optimal conversion"; Ylitie, Karras and Laine 2017, "Efficient incoherent ray traversal on GPUs through
/// compressed wide BVHs"), by dynamic programming over the binary tree: see cost_tables(). A subtree of up to
/// max_leaf triangles may become one leaf, so the binary tree is built with small leaves and the collapse merges them
/// where the wide tree's cost says so.
/// Layout (mesh_tree.hpp), depth first: a node, the blocks of its leaf children, then its interior children's
/// subtrees. Embree's allocator gives a similar order; here a node's reference also says how many lines of leaf blocks
/// follow it, so that they are fetched with it.
/// Two passes, each parallel over large subtrees: measure() sizes every subtree, so that place() knows where each
/// child's subtree starts. A subtree starts on a line, so its layout does not depend on where it lies, and the result
/// is the same for any thread count.
template <int W>
class WideTreeBuilder {
 public:
  WideTreeBuilder(std::span<const BvhNode> binary, std::span<const int> order, std::span<const uint32_t> indices,
                  std::span<const Vec3f> positions, int max_leaf)
      : bn_(binary),
        order_(order),
        indices_(indices),
        p_(positions),
        max_leaf_(max_leaf),
        parallel_nodes_(
            std::max<int64_t>(1024, int64_t(binary.size()) / (16 * tbb::this_task_arena::max_concurrency()))) {}

  /// Lays the tree out in tree (sized to fit); returns the root's reference and sets wide_nodes. Throws InvalidInput
  /// when the tree would pass the 2 GiB that references address.
  int32_t build(RawVector<mesh_tree::CacheLine>& tree, size_t& wide_nodes) {
    cost_tables();
    const Subtree root = child(0, int(bn_.size()));
    if (is_leaf(root)) {  // a mesh of one leaf
      wide_nodes = 0;
      tree.resize((leaf_bytes(root) + 63) / 64);
      tree_ = tree.data();
      return place_leaf(root, 0);
    }
    subtree_bytes_.resize(bn_.size());
    const Size size = measure(root);
    // 32-byte units are addressed by 26 bits (leaf_ref), lines by 27 (node_ref).
    if (size.bytes >= (size_t(1) << 31))
      throw InvalidInput("MeshAccel: " + std::to_string(order_.size()) + " triangles, more than supported");
    wide_nodes = size.nodes;
    tree.resize((size.bytes + 63) / 64);
    tree_ = tree.data();
    return place(root, 0);
  }

 private:
  /// A binary subtree: its root and the end of its nodes (the binary tree is depth first); as a leaf of the wide
  /// tree, its triangles order_[first, first + count) (count 0: a wide node).
  struct Subtree {
    int node, end;
    int first = 0, count = 0;
  };
  struct Size {
    size_t bytes, nodes;
  };
  static constexpr size_t kNodeBytes = sizeof(mesh_tree::WideNode<W>);

  static constexpr float kNodeCost = MeshAccel::kNodeCost, kBlockCost = MeshAccel::kBlockCost;

  bool is_leaf(Subtree s) const { return s.count > 0; }
  size_t leaf_bytes(Subtree s) const { return size_t(s.count + 3) / 4 * sizeof(mesh_tree::TriangleBlock); }
  float area(int node) const { return bn_[size_t(node)].box.area(); }
  float leaf_cost(int node, int count) const { return area(node) * kBlockCost * float((count + 3) / 4); }
  const float* cost(int node) const { return &cost_[size_t(node) * W]; }

  /// cost(n)[i - 1]: the least SAH cost of covering binary subtree n with at most i children of a wide node, each a
  /// leaf or a wide node (Pinto 2010). One child: a binary leaf; a merged leaf when n has at most max_leaf_
  /// triangles; or a wide node, whose cost is its visit plus its children's, split among n's two subtrees. More:
  /// one child, or n's two subtrees sharing them. leaf_count_ keeps each subtree's triangles, up to max_leaf_ + 1.
  void cost_tables() {
    cost_.resize(bn_.size() * W);
    leaf_count_.resize(bn_.size());
    fill_costs(0, int(bn_.size()));
  }
  /// The tables of subtree [n, end): its two halves in parallel when large, else one backward pass (children come
  /// after their parent, depth first).
  void fill_costs(int n, int end) {
    if (end - n > parallel_nodes_) {
      const int second = bn_[size_t(n)].first;
      tbb::parallel_invoke([&] { fill_costs(n + 1, second); }, [&] { fill_costs(second, end); });
      fill_cost(size_t(n));
    } else {
      for (int i = end; i-- > n;) fill_cost(size_t(i));
    }
  }
  void fill_cost(size_t n) {
    const BvhNode& b = bn_[n];
    float* c = &cost_[n * W];
    if (b.count > 0) {
      leaf_count_[n] = std::min<int>(b.count, max_leaf_ + 1);
      std::fill(c, c + W, leaf_cost(int(n), b.count));
      return;
    }
    leaf_count_[n] = std::min(leaf_count_[n + 1] + leaf_count_[size_t(b.first)], max_leaf_ + 1);
    float shared[W + 1];  // shared[i]: the two subtrees sharing i slots
    for (int i = 2; i <= W; ++i) shared[i] = forest(int(n), i);
    c[0] = area(int(n)) * kNodeCost + shared[W];
    if (leaf_count_[n] <= max_leaf_) c[0] = std::min(c[0], leaf_cost(int(n), leaf_count_[n]));
    for (int i = 2; i <= W; ++i) c[i - 1] = std::min(c[0], shared[i]);
  }

  /// The least cost of covering interior node n's two subtrees with `slots` children (INFINITY for fewer than 2);
  /// split gets the first subtree's share.
  float forest(int n, int slots, int* split = nullptr) const {
    const float* a = cost(n + 1);
    const float* b = cost(bn_[size_t(n)].first);
    float best = INFINITY;
    for (int k = 1; k < slots; ++k)
      if (a[k - 1] + b[slots - k - 1] < best) {
        best = a[k - 1] + b[slots - k - 1];
        if (split) *split = k;
      }
    return best;
  }

  /// Subtree n (nodes up to end) as one child: a leaf when a binary leaf or when merging it is its least cost.
  Subtree child(int n, int end) const {
    const BvhNode& b = bn_[size_t(n)];
    if (b.count > 0) return {n, end, b.first, b.count};
    if (leaf_count_[size_t(n)] > max_leaf_ || leaf_cost(n, leaf_count_[size_t(n)]) > cost(n)[0]) return {n, end};
    int first = n;  // a subtree's triangles are contiguous in order_, from its leftmost leaf on
    while (bn_[size_t(first)].count == 0) ++first;
    return {n, end, bn_[size_t(first)].first, leaf_count_[size_t(n)]};
  }

  /// Appends the children that cover interior node n's two subtrees with at most `slots` of them, as the tables chose.
  void split_among(int n, int end, int slots, Subtree* kids, int& k) const {
    int share = 1;
    forest(n, slots, &share);
    const int second = bn_[size_t(n)].first;
    add(n + 1, second, share, kids, k);
    add(second, end, slots - share, kids, k);
  }
  void add(int n, int end, int slots, Subtree* kids, int& k) const {
    if (slots == 1 || bn_[size_t(n)].count > 0 || cost(n)[0] <= forest(n, slots))
      kids[k++] = child(n, end);
    else
      split_among(n, end, slots, kids, k);
  }
  static size_t line_up(size_t bytes) { return (bytes + 63) / 64 * 64; }

  /// The children of the wide node made of interior binary node s; returns their count.
  int widen(Subtree s, Subtree kids[W]) const {
    int k = 0;
    split_among(s.node, s.end, W, kids, k);
    return k;
  }

  /// Calls f(i) for each interior child i, in parallel when s is large (each child writes its own subtree).
  template <class F>
  void each_interior(Subtree s, const Subtree* kids, int k, const F& f) const {
    if (s.end - s.node > parallel_nodes_) {
      tbb::parallel_for(0, k, [&](int i) {
        if (!is_leaf(kids[i])) f(i);
      });
    } else {
      for (int i = 0; i < k; ++i)
        if (!is_leaf(kids[i])) f(i);
    }
  }

  /// The bytes and wide nodes of interior subtree s laid out from a line on; keeps the bytes for place().
  Size measure(Subtree s) {
    Subtree kids[W];
    const int k = widen(s, kids);
    Size sub[W] = {};
    each_interior(s, kids, k, [&](int i) { sub[i] = measure(kids[i]); });
    Size size{kNodeBytes, 1};
    for (int i = 0; i < k; ++i)
      if (is_leaf(kids[i])) size.bytes += leaf_bytes(kids[i]);
    for (int i = 0; i < k; ++i)
      if (!is_leaf(kids[i])) {
        size.bytes = line_up(size.bytes) + sub[i].bytes;
        size.nodes += sub[i].nodes;
      }
    subtree_bytes_[size_t(s.node)] = uint32_t(size.bytes);  // exact below 4 GiB: build() refuses 2 GiB and more
    return size;
  }

  /// Writes interior subtree s from line `line` on; returns its reference.
  int32_t place(Subtree s, size_t line) {
    Subtree kids[W];
    const int k = widen(s, kids);
    mesh_tree::WideNode<W> node;
    for (int i = 0; i < W; ++i) {
      const AABB box = i < k ? bn_[size_t(kids[i].node)].box : AABB{};
      for (int a = 0; a < 3; ++a) {
        node.box[a][i] = box.lo[a];
        node.box[3 + a][i] = box.hi[a];
      }
      node.child[i] = 0;
    }
    const size_t leaves_begin = line * 64 + kNodeBytes;
    size_t end = leaves_begin;
    for (int i = 0; i < k; ++i)
      if (is_leaf(kids[i])) {
        node.child[i] = place_leaf(kids[i], end);
        end += leaf_bytes(kids[i]);
      }
    const int leaf_lines = int(std::min<size_t>(15, (end - leaves_begin + 63) / 64));
    size_t first_line[W];
    for (int i = 0; i < k; ++i)
      if (!is_leaf(kids[i])) {
        first_line[i] = line_up(end) / 64;
        end = first_line[i] * 64 + subtree_bytes_[size_t(kids[i].node)];
      }
    each_interior(s, kids, k, [&](int i) { node.child[i] = place(kids[i], first_line[i]); });
    *reinterpret_cast<mesh_tree::WideNode<W>*>(tree_ + line) = node;
    return mesh_tree::node_ref(line, leaf_lines);
  }

  /// Writes leaf s's triangles as blocks of 4 from byte `at` on; returns its reference.
  int32_t place_leaf(Subtree s, size_t at) {
    auto* blocks = reinterpret_cast<mesh_tree::TriangleBlock*>(reinterpret_cast<char*>(tree_) + at);
    for (int k = 0; k < (s.count + 3) / 4 * 4; ++k) {
      mesh_tree::TriangleBlock& b = blocks[k / 4];
      const int lane = k % 4;
      Vec3f v0(0.0f), e1(0.0f), e2(0.0f);
      int index = -1;
      if (k < s.count) {
        const size_t t = size_t(order_[size_t(s.first) + size_t(k)]);
        v0 = p_[indices_[3 * t]];
        e1 = p_[indices_[3 * t + 1]] - v0;
        e2 = p_[indices_[3 * t + 2]] - v0;
        index = int(t);
      }
      for (int a = 0; a < 3; ++a) {
        b.v0[a][lane] = v0[a];
        b.e1[a][lane] = e1[a];
        b.e2[a][lane] = e2[a];
      }
      b.index[lane] = index;
    }
    return mesh_tree::leaf_ref(int(at / 32), (s.count + 3) / 4);
  }

  std::span<const BvhNode> bn_;
  std::span<const int> order_;
  std::span<const uint32_t> indices_;
  std::span<const Vec3f> p_;
  int max_leaf_;               // triangles a merged leaf may hold
  RawVector<float> cost_;      // by binary node: cost_tables()
  RawVector<int> leaf_count_;  // by binary node: its triangles, up to max_leaf_ + 1
  // Subtrees of more binary nodes than this do their children in parallel (about 16 tasks per thread, as the binary
  // build's).
  int64_t parallel_nodes_;
  RawVector<uint32_t> subtree_bytes_;  // by binary node: the bytes of the subtree of the wide node made of it
  mesh_tree::CacheLine* tree_ = nullptr;
};

/// The SAH cost of the subtree under node reference ref (see MeshAccel::sah_cost), in units of area.
template <int W>
double subtree_cost(const mesh_tree::CacheLine* tree, int32_t ref) {
  const auto& node = *reinterpret_cast<const mesh_tree::WideNode<W>*>(tree + mesh_tree::node_line(ref));
  double cost = 0;
  for (int i = 0; i < W; ++i) {
    const AABB box{{node.box[0][i], node.box[1][i], node.box[2][i]}, {node.box[3][i], node.box[4][i], node.box[5][i]}};
    if (box.empty()) continue;
    const int32_t c = node.child[i];
    cost += c < 0 ? double(box.area()) * MeshAccel::kBlockCost * mesh_tree::leaf_block_count(c)
                  : double(box.area()) * MeshAccel::kNodeCost + subtree_cost<W>(tree, c);
  }
  return cost;
}

int pick_width(int requested) {
  const bool avx2 = cpu_features().avx2;
  if (requested == 0) return avx2 ? 8 : 4;
  if (requested == 4 || (requested == 8 && avx2)) return requested;
  throw InvalidInput("MeshAccel: SIMD width must be 0, 4 or 8 (8 needs AVX2), got " + std::to_string(requested));
}

}  // namespace

MeshAccel::MeshAccel(const TriMesh& mesh, const BvhSettings& settings, int simd_width)
    : triangle_count_(mesh.triangle_count()), width_(pick_width(simd_width)) {
  const size_t nv = mesh.positions.size(), nt = mesh.triangle_count();
  // Fresh arrays of tens of megabytes for large meshes: uninitialized and on huge pages (page faults dominated).
  // Checked in parallel; the serial scan that names the first bad vertex or triangle runs only on bad input.
  RawVector<Vec3f> p(nv);
  std::atomic<bool> bad{false};
  parallel_for(0, int64_t(nv), 16384, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      p[size_t(i)] = Vec3f(mesh.positions[size_t(i)]);
      const Vec3f& v = p[size_t(i)];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) bad = true;
    }
  });
  parallel_for(0, int64_t(3 * nt), 65536, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      if (mesh.indices[size_t(i)] >= nv) bad = true;
  });
  if (bad) {
    for (size_t i = 0; i < nv; ++i)
      if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
        throw InvalidInput("MeshAccel: vertex " + std::to_string(i) + " is not finite");
    for (size_t i = 0; i < 3 * nt; ++i)
      if (mesh.indices[i] >= nv)
        throw InvalidInput("MeshAccel: triangle " + std::to_string(i / 3) + " uses vertex " +
                           std::to_string(mesh.indices[i]) + " of " + std::to_string(nv));
  }
  // Two phases a user may wait seconds for on millions of triangles: the binary tree, then its collapse and layout.
  Progress progress("building BVH", 2);
  // The binary tree's leaves are single blocks at most; the collapse merges subtrees into leaves of up to max_leaf.
  const int max_leaf = std::min(settings.max_leaf_size, 4 * mesh_tree::kMaxLeafBlocks);
  BvhSettings capped = settings;
  capped.max_leaf_size = std::min(settings.max_leaf_size, 4);
  capped.leaf_block = 4;  // the leaves' triangles are tested 4 at a time
  bvh_ = Bvh(
      nt,
      [&](size_t t) {
        AABB box;
        for (int k = 0; k < 3; ++k) box.expand(p[mesh.indices[3 * t + size_t(k)]]);
        return box;
      },
      capped);
  progress.advance();
  const auto nodes = bvh_.nodes();
  if (nodes.empty()) {
    width_ = 0;
    return;
  }
  const auto order = bvh_.prim_indices();
  root_ = width_ == 8 ? WideTreeBuilder<8>(nodes, order, mesh.indices, p, max_leaf).build(tree_, wide_nodes_)
                      : WideTreeBuilder<4>(nodes, order, mesh.indices, p, max_leaf).build(tree_, wide_nodes_);
}

double MeshAccel::sah_cost() const {
  if (width_ == 0) return 0;
  if (root_ < 0) return kBlockCost * mesh_tree::leaf_block_count(root_);
  const double root_area = bvh_.nodes()[0].box.area();
  const double below = width_ == 8 ? subtree_cost<8>(tree_.data(), root_) : subtree_cost<4>(tree_.data(), root_);
  return kNodeCost + below / root_area;
}

bool MeshAccel::intersect(Ray& ray, Hit& hit, TraversalStats* stats) const {
  if (width_ == 0) return false;
  return width_ == 8 ? mesh_traversal::intersect8(tree_.data(), root_, ray, hit, stats, far_tree())
                     : mesh_traversal::intersect4(tree_.data(), root_, ray, hit, stats, far_tree());
}

void MeshAccel::intersect(std::span<const Ray> rays, std::span<Hit> hits) const {
  if (hits.size() != rays.size())
    throw InvalidInput("MeshAccel::intersect: " + std::to_string(rays.size()) + " rays but " +
                       std::to_string(hits.size()) + " hits");
  if (width_ == 0) {
    std::fill(hits.begin(), hits.end(), Hit{});
  } else if (width_ == 8) {
    mesh_traversal::intersect_stream8(tree_.data(), root_, rays, hits, far_tree());
  } else {
    mesh_traversal::intersect_stream4(tree_.data(), root_, rays, hits, far_tree());
  }
}

bool MeshAccel::occluded(const Ray& ray) const {
  if (width_ == 0) return false;
  return width_ == 8 ? mesh_traversal::occluded8(tree_.data(), root_, ray, far_tree())
                     : mesh_traversal::occluded4(tree_.data(), root_, ray, far_tree());
}

namespace mesh_traversal {

bool intersect4(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats, bool far_tree) {
  return nearest_hit<4>(tree, root, ray, hit, stats, far_tree);
}

void intersect_stream4(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits, bool far_tree) {
  nearest_hits<4>(tree, root, rays, hits, far_tree);
}

bool occluded4(Tree tree, int32_t root, const Ray& ray, bool far_tree) { return any_hit<4>(tree, root, ray, far_tree); }

}  // namespace mesh_traversal

Vec3f shading_normal(const TriMesh& mesh, const Hit& hit) {
  if (mesh.normals.size() != mesh.positions.size() || hit.prim < 0) return hit.normal;
  const size_t t = size_t(hit.prim);
  const Vec3 n = (1.0 - hit.uv.x - hit.uv.y) * mesh.normals[mesh.indices[3 * t]] +
                 double(hit.uv.x) * mesh.normals[mesh.indices[3 * t + 1]] +
                 double(hit.uv.y) * mesh.normals[mesh.indices[3 * t + 2]];
  const double len = glm::length(n);
  return len > 0 ? Vec3f(n / len) : hit.normal;
}

}  // namespace tessera
