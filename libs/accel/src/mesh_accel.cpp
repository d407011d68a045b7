// Ray casting of triangle meshes: the binary Bvh collapsed into a wide tree with triangles packed 4 to a block.
#include "tessera/accel/mesh_accel.hpp"

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/parallel.hpp"
#include "mesh_traversal.hpp"

namespace tessera {

namespace {

/// Collapses the binary tree into a wide one (Wald et al. 2008, "Getting rid of packets"): a node takes its two
/// children, then repeatedly replaces the interior child of largest area by that child's two children, until it has W.
/// The children are wide node indices (>= 0) or ~b for the binary leaf b; Layout then places them.
template <int W>
class Collapser {
 public:
  Collapser(std::span<const BvhNode> binary, RawVector<MeshAccel::WideNode<W>>& out) : bn_(binary), out_(out) {}

  /// The reference of binary node b's subtree (a wide node index, or ~b for a leaf).
  int32_t ref(int b) {
    if (bn_[size_t(b)].count > 0) return ~b;
    int kids[W] = {b + 1, bn_[size_t(b)].first};
    int k = 2;
    while (k < W) {
      int widest = -1;
      float area = -1;
      for (int i = 0; i < k; ++i) {
        const BvhNode& c = bn_[size_t(kids[i])];
        if (c.count == 0 && c.box.area() > area) {
          area = c.box.area();
          widest = i;
        }
      }
      if (widest < 0) break;
      const int split = kids[widest];
      kids[widest] = split + 1;
      kids[k++] = bn_[size_t(split)].first;
    }
    const int self = int(out_.size());
    out_.emplace_back();
    MeshAccel::WideNode<W>& node = out_.back();
    for (int i = 0; i < W; ++i) {
      const AABB box = i < k ? bn_[size_t(kids[i])].box : AABB{};
      for (int a = 0; a < 3; ++a) {
        node.box[a][i] = box.lo[a];
        node.box[3 + a][i] = box.hi[a];
      }
      node.child[i] = 0;
    }
    for (int i = 0; i < k; ++i) {
      const int32_t r = ref(kids[i]);
      out_[size_t(self)].child[i] = r;  // out_ may have grown: index again
    }
    return self;
  }

 private:
  std::span<const BvhNode> bn_;
  RawVector<MeshAccel::WideNode<W>>& out_;
};

/// Lays the collapsed tree out in MeshAccel's array of cache lines (see MeshAccel::node_ref), depth first: a node,
/// the blocks of its leaf children, then its interior children's subtrees. Embree's allocator gives a similar order;
/// here a node's reference also says how many lines of leaf blocks follow it, so that they are fetched with it.
template <int W>
class Layout {
 public:
  Layout(std::span<const BvhNode> binary, const RawVector<MeshAccel::WideNode<W>>& nodes,
         RawVector<MeshAccel::CacheLine>& tree, std::vector<int>& leaf_unit)
      : bn_(binary), nodes_(nodes), tree_(tree), leaf_unit_(leaf_unit) {}

  /// Places the subtree of collapsed reference r (a node index, or ~b for binary leaf b) from byte end_ on; returns
  /// its final reference.
  int32_t place(int32_t r) {
    if (r < 0) return place_leaf(~r);
    constexpr size_t kNodeLines = sizeof(MeshAccel::WideNode<W>) / 64;
    const size_t line = (end_ + 63) / 64;
    end_ = (line + kNodeLines) * 64;
    MeshAccel::WideNode<W> node = nodes_[size_t(r)];
    const size_t leaves_begin = end_;
    for (int i = 0; i < W; ++i)
      if (node.child[i] < 0) node.child[i] = place_leaf(~node.child[i]);
    const int leaf_lines = int(std::min<size_t>(15, (end_ - leaves_begin + 63) / 64));
    for (int i = 0; i < W; ++i)
      if (node.child[i] >= 0 && node.box[0][i] <= node.box[3][i]) node.child[i] = place(node.child[i]);
    *reinterpret_cast<MeshAccel::WideNode<W>*>(tree_.data() + line) = node;
    return MeshAccel::node_ref(line, leaf_lines);
  }

  /// Bytes used.
  size_t end() const { return end_; }

 private:
  int32_t place_leaf(int b) {
    const int blocks = (bn_[size_t(b)].count + 3) / 4;
    leaf_unit_[size_t(b)] = int(end_ / 32);
    const int32_t ref = MeshAccel::leaf_ref(int(end_ / 32), blocks);
    end_ += size_t(blocks) * sizeof(MeshAccel::TriangleBlock);
    return ref;
  }

  std::span<const BvhNode> bn_;
  const RawVector<MeshAccel::WideNode<W>>& nodes_;
  RawVector<MeshAccel::CacheLine>& tree_;
  std::vector<int>& leaf_unit_;
  size_t end_ = 0;
};

/// Collapses the binary tree, lays it out in tree (sized to fit) and returns the root's reference; leaf_unit[b] gets
/// the first 32-byte unit of binary leaf b's blocks.
template <int W>
int32_t build_wide(std::span<const BvhNode> binary, size_t block_count, RawVector<MeshAccel::CacheLine>& tree,
                   std::vector<int>& leaf_unit, size_t& wide_nodes) {
  RawVector<MeshAccel::WideNode<W>> nodes;
  nodes.reserve(binary.size() / 2 + 1);
  const int32_t root = Collapser<W>(binary, nodes).ref(0);
  wide_nodes = nodes.size();
  // At most: every node, a line of padding after each node's leaves, and the blocks.
  tree.resize(nodes.size() * (sizeof(MeshAccel::WideNode<W>) / 64 + 1) +
              (block_count * sizeof(MeshAccel::TriangleBlock) + 63) / 64 + 1);
  Layout<W> layout(binary, nodes, tree, leaf_unit);
  const int32_t ref = layout.place(root);
  tree.resize((layout.end() + 63) / 64);
  return ref;
}

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
  RawVector<Vec3f> p(nv);
  for (size_t i = 0; i < nv; ++i) {
    p[i] = Vec3f(mesh.positions[i]);
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
      throw InvalidInput("MeshAccel: vertex " + std::to_string(i) + " is not finite");
  }
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + size_t(k)];
      if (v >= nv)
        throw InvalidInput("MeshAccel: triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) + " of " +
                           std::to_string(nv));
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
  size_t block_count = 0;
  for (const BvhNode& n : nodes) block_count += size_t(n.count + 3) / 4;
  // 32-byte units are addressed by 26 bits (leaf_ref), lines by 27 (node_ref).
  if (block_count * sizeof(TriangleBlock) + nodes.size() * 2 * sizeof(WideNode<8>) >= (size_t(1) << 31))
    throw InvalidInput("MeshAccel: " + std::to_string(nt) + " triangles, more than supported");
  std::vector<int> leaf_unit(nodes.size(), -1);
  root_ = width_ == 8 ? build_wide<8>(nodes, block_count, tree_, leaf_unit, wide_nodes_)
                      : build_wide<4>(nodes, block_count, tree_, leaf_unit, wide_nodes_);
  // The blocks of 4 triangles, where the layout put each leaf.
  const auto order = bvh_.prim_indices();
  parallel_for(0, int64_t(nodes.size()), 4096, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const BvhNode& n = nodes[size_t(i)];
      if (n.count == 0) continue;
      auto* blocks = reinterpret_cast<TriangleBlock*>(reinterpret_cast<char*>(tree_.data()) +
                                                      size_t(leaf_unit[size_t(i)]) * 32);
      for (int k = 0; k < (n.count + 3) / 4 * 4; ++k) {
        TriangleBlock& b = blocks[k / 4];
        const int lane = k % 4;
        Vec3f v0(0.0f), e1(0.0f), e2(0.0f);
        int index = -1;
        if (k < n.count) {
          const size_t t = size_t(order[size_t(n.first) + size_t(k)]);
          v0 = p[mesh.indices[3 * t]];
          e1 = p[mesh.indices[3 * t + 1]] - v0;
          e2 = p[mesh.indices[3 * t + 2]] - v0;
          index = int(t);
        }
        for (int a = 0; a < 3; ++a) {
          b.v0[a][lane] = v0[a];
          b.e1[a][lane] = e1[a];
          b.e2[a][lane] = e2[a];
        }
        b.index[lane] = index;
      }
    }
  });
}

bool MeshAccel::intersect(Ray& ray, Hit& hit, TraversalStats* stats) const {
  if (width_ == 0) return false;
  return width_ == 8 ? mesh_traversal::intersect8(tree_.data(), root_, ray, hit, stats)
                     : mesh_traversal::intersect4(tree_.data(), root_, ray, hit, stats);
}

void MeshAccel::intersect(std::span<const Ray> rays, std::span<Hit> hits) const {
  if (hits.size() != rays.size())
    throw InvalidInput("MeshAccel::intersect: " + std::to_string(rays.size()) + " rays but " +
                       std::to_string(hits.size()) + " hits");
  if (width_ == 0) {
    std::fill(hits.begin(), hits.end(), Hit{});
  } else if (width_ == 8) {
    mesh_traversal::intersect_stream8(tree_.data(), root_, rays, hits);
  } else {
    mesh_traversal::intersect_stream4(tree_.data(), root_, rays, hits);
  }
}

bool MeshAccel::occluded(const Ray& ray) const {
  if (width_ == 0) return false;
  return width_ == 8 ? mesh_traversal::occluded8(tree_.data(), root_, ray)
                     : mesh_traversal::occluded4(tree_.data(), root_, ray);
}

namespace mesh_traversal {

bool intersect4(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats) {
  return nearest_hit<4>(tree, root, ray, hit, stats);
}

void intersect_stream4(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits) {
  nearest_hits<4>(tree, root, rays, hits);
}

bool occluded4(Tree tree, int32_t root, const Ray& ray) { return any_hit<4>(tree, root, ray); }

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
