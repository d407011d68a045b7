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
template <int W>
class Collapser {
 public:
  Collapser(std::span<const BvhNode> binary, const std::vector<int32_t>& leaf_refs,
            RawVector<MeshAccel::WideNode<W>>& out)
      : bn_(binary), leaf_refs_(leaf_refs), out_(out) {}

  /// The reference of binary node b's subtree (a wide node index, or a leaf reference).
  int32_t ref(int b) {
    if (bn_[size_t(b)].count > 0) return leaf_refs_[size_t(b)];
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
  const std::vector<int32_t>& leaf_refs_;
  RawVector<MeshAccel::WideNode<W>>& out_;
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
  // Blocks of 4 triangles, leaf after leaf (leaves come in depth-first order, which is the order of prim_indices).
  std::vector<int32_t> leaf_refs(nodes.size(), 0);
  int64_t block_count = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].count == 0) continue;
    const int blocks = (nodes[i].count + 3) / 4;
    if (block_count + blocks > (int64_t(1) << 26))
      throw InvalidInput("MeshAccel: " + std::to_string(nt) + " triangles, more than supported");
    leaf_refs[i] = leaf_ref(int(block_count), blocks);
    block_count += blocks;
  }
  blocks_.resize(size_t(block_count));
  const auto order = bvh_.prim_indices();
  parallel_for(0, int64_t(nodes.size()), 4096, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const BvhNode& n = nodes[size_t(i)];
      if (n.count == 0) continue;
      const int first_block = leaf_first_block(leaf_refs[size_t(i)]);
      for (int k = 0; k < (n.count + 3) / 4 * 4; ++k) {
        TriangleBlock& b = blocks_[size_t(first_block) + size_t(k / 4)];
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
  if (width_ == 8) {
    nodes8_.reserve(nodes.size() / 2 + 1);
    root_ = Collapser<8>(nodes, leaf_refs, nodes8_).ref(0);
  } else {
    nodes4_.reserve(nodes.size() / 2 + 1);
    root_ = Collapser<4>(nodes, leaf_refs, nodes4_).ref(0);
  }
}

bool MeshAccel::intersect(Ray& ray, Hit& hit, TraversalStats* stats) const {
  if (width_ == 0) return false;
  return width_ == 8 ? mesh_traversal::intersect8(nodes8_.data(), blocks_.data(), root_, ray, hit, stats)
                     : mesh_traversal::intersect4(nodes4_.data(), blocks_.data(), root_, ray, hit, stats);
}

void MeshAccel::intersect(std::span<const Ray> rays, std::span<Hit> hits) const {
  if (hits.size() != rays.size())
    throw InvalidInput("MeshAccel::intersect: " + std::to_string(rays.size()) + " rays but " +
                       std::to_string(hits.size()) + " hits");
  if (width_ == 0) {
    std::fill(hits.begin(), hits.end(), Hit{});
  } else if (width_ == 8) {
    mesh_traversal::intersect_stream8(nodes8_.data(), blocks_.data(), root_, rays, hits);
  } else {
    mesh_traversal::intersect_stream4(nodes4_.data(), blocks_.data(), root_, rays, hits);
  }
}

bool MeshAccel::occluded(const Ray& ray) const {
  if (width_ == 0) return false;
  return width_ == 8 ? mesh_traversal::occluded8(nodes8_.data(), blocks_.data(), root_, ray)
                     : mesh_traversal::occluded4(nodes4_.data(), blocks_.data(), root_, ray);
}

namespace mesh_traversal {

bool intersect4(const MeshAccel::WideNode<4>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray,
                Hit& hit, TraversalStats* stats) {
  return nearest_hit<4>(nodes, blocks, root, ray, hit, stats);
}

void intersect_stream4(const MeshAccel::WideNode<4>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root,
                       std::span<const Ray> rays, std::span<Hit> hits) {
  nearest_hits<4>(nodes, blocks, root, rays, hits);
}

bool occluded4(const MeshAccel::WideNode<4>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root,
               const Ray& ray) {
  return any_hit<4>(nodes, blocks, root, ray);
}

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
