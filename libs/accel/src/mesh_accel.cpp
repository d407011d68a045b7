// Ray casting of triangle meshes: the binary Bvh collapsed into a wide tree with triangles packed 4 to a block.
#include "tessera/accel/mesh_accel.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/parallel.hpp"
#include "mesh_traversal.hpp"

namespace tessera {

namespace {

/// Builds the wide tree from the binary one and lays it out in MeshAccel's array of cache lines.
///
/// Collapse (Wald et al. 2008, "Getting rid of packets"): a wide node takes its binary node's two children, then
/// repeatedly replaces the interior child of largest area by that child's two children, until it has W.
/// Layout (see MeshAccel::node_ref), depth first: a node, the blocks of its leaf children, then its interior children's
/// subtrees. Embree's allocator gives a similar order; here a node's reference also says how many lines of leaf blocks
/// follow it, so that they are fetched with it.
/// Two passes, each parallel over large subtrees: measure() sizes every subtree, so that place() knows where each
/// child's subtree starts. A subtree starts on a line, so its layout does not depend on where it lies, and the result
/// is the same for any thread count.
template <int W>
class WideTreeBuilder {
 public:
  WideTreeBuilder(std::span<const BvhNode> binary, std::span<const int> order, std::span<const uint32_t> indices,
                  std::span<const Vec3f> positions)
      : bn_(binary),
        order_(order),
        indices_(indices),
        p_(positions),
        parallel_nodes_(
            std::max<int64_t>(1024, int64_t(binary.size()) / (16 * tbb::this_task_arena::max_concurrency()))) {}

  /// Lays the tree out in tree (sized to fit); returns the root's reference and sets wide_nodes. Throws InvalidInput
  /// when the tree would pass the 2 GiB that references address.
  int32_t build(RawVector<MeshAccel::CacheLine>& tree, size_t& wide_nodes) {
    const Subtree root{0, int(bn_.size())};
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
  /// A binary subtree: its root and the end of its nodes (the binary tree is depth first).
  struct Subtree {
    int node, end;
  };
  struct Size {
    size_t bytes, nodes;
  };
  static constexpr size_t kNodeBytes = sizeof(MeshAccel::WideNode<W>);

  bool is_leaf(Subtree s) const { return bn_[size_t(s.node)].count > 0; }
  size_t leaf_bytes(Subtree s) const {
    return size_t(bn_[size_t(s.node)].count + 3) / 4 * sizeof(MeshAccel::TriangleBlock);
  }
  static size_t line_up(size_t bytes) { return (bytes + 63) / 64 * 64; }

  /// The children of the wide node made of interior binary node s; returns their count.
  int widen(Subtree s, Subtree kids[W]) const {
    const int second = bn_[size_t(s.node)].first;
    kids[0] = {s.node + 1, second};
    kids[1] = {second, s.end};
    int k = 2;
    while (k < W) {
      int widest = -1;
      float area = -1;
      for (int i = 0; i < k; ++i)
        if (!is_leaf(kids[i]) && bn_[size_t(kids[i].node)].box.area() > area) {
          area = bn_[size_t(kids[i].node)].box.area();
          widest = i;
        }
      if (widest < 0) break;
      const Subtree split = kids[widest];
      const int split_second = bn_[size_t(split.node)].first;
      kids[widest] = {split.node + 1, split_second};
      kids[k++] = {split_second, split.end};
    }
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
    MeshAccel::WideNode<W> node;
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
    *reinterpret_cast<MeshAccel::WideNode<W>*>(tree_ + line) = node;
    return MeshAccel::node_ref(line, leaf_lines);
  }

  /// Writes leaf s's triangles as blocks of 4 from byte `at` on; returns its reference.
  int32_t place_leaf(Subtree s, size_t at) {
    const BvhNode& n = bn_[size_t(s.node)];
    auto* blocks = reinterpret_cast<MeshAccel::TriangleBlock*>(reinterpret_cast<char*>(tree_) + at);
    for (int k = 0; k < (n.count + 3) / 4 * 4; ++k) {
      MeshAccel::TriangleBlock& b = blocks[k / 4];
      const int lane = k % 4;
      Vec3f v0(0.0f), e1(0.0f), e2(0.0f);
      int index = -1;
      if (k < n.count) {
        const size_t t = size_t(order_[size_t(n.first) + size_t(k)]);
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
    return MeshAccel::leaf_ref(int(at / 32), (n.count + 3) / 4);
  }

  std::span<const BvhNode> bn_;
  std::span<const int> order_;
  std::span<const uint32_t> indices_;
  std::span<const Vec3f> p_;
  // Subtrees of more binary nodes than this do their children in parallel (about 16 tasks per thread, as the binary
  // build's).
  int64_t parallel_nodes_;
  RawVector<uint32_t> subtree_bytes_;  // by binary node: the bytes of the subtree of the wide node made of it
  MeshAccel::CacheLine* tree_ = nullptr;
};

int pick_width(int requested) {
  const bool avx2 = __builtin_cpu_supports("avx2");
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
  BvhSettings capped = settings;
  capped.max_leaf_size = std::min(settings.max_leaf_size, 4 * kMaxLeafBlocks);
  capped.leaf_block = 4;  // the leaves' triangles are tested 4 at a time
  bvh_ = Bvh(
      nt,
      [&](size_t t) {
        AABB box;
        for (int k = 0; k < 3; ++k) box.expand(p[mesh.indices[3 * t + size_t(k)]]);
        return box;
      },
      capped);
  const auto nodes = bvh_.nodes();
  if (nodes.empty()) {
    width_ = 0;
    return;
  }
  root_ = width_ == 8 ? WideTreeBuilder<8>(nodes, bvh_.prim_indices(), mesh.indices, p).build(tree_, wide_nodes_)
                      : WideTreeBuilder<4>(nodes, bvh_.prim_indices(), mesh.indices, p).build(tree_, wide_nodes_);
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
