#pragma once
// Ray casting of a triangle mesh: a Bvh over its triangles collapsed into a wide BVH with SIMD node and triangle tests.
#include <span>
#include <vector>

#include "tessera/accel/bvh.hpp"
#include "tessera/accel/shapes.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

namespace detail {
/// One 64-byte line of a MeshAccel's tree: storage only. The wide nodes and triangle blocks laid out in these lines
/// are private to accel (src/mesh_tree.hpp).
struct alignas(64) MeshTreeLine {
  unsigned char bytes[64];
};
}  // namespace detail

/// A triangle mesh ready for ray casting (a float copy of its geometry; the TriMesh need not outlive it).
///
/// The binary BVH (bvh()) is built by the settings' method and then collapsed into a wide tree (4 or 8 children per
/// node, their boxes stored so that one SIMD slab test covers all of them; which binary nodes become wide nodes and
/// which subtrees become leaves is the SAH-optimal choice) whose leaves hold the triangles packed 4 to a block for a
/// SIMD Moller-Trumbore test. The width follows the CPU at run time: 8 with AVX2, else 4 (SSE).
class MeshAccel {
 public:
  MeshAccel() = default;
  /// Builds the BVH (parallel, deterministic). Throws InvalidInput for an index out of range or a non-finite vertex.
  /// Leaves hold at most settings.max_leaf_size triangles, capped at 128. The binary tree's leaves hold at most 4
  /// (one block); the collapse merges subtrees into larger leaves where the wide tree's SAH cost says so. simd_width 4
  /// or 8 forces the wide tree's width (8 needs AVX2); 0 picks the widest this CPU runs.
  explicit MeshAccel(const TriMesh& mesh, const BvhSettings& settings = default_settings(), int simd_width = 0);

  /// The default build settings for meshes: leaves of up to 8 triangles (two blocks of 4, where the collapse finds
  /// them cheaper than a wide node), the binary SAH counting blocks (leaf_block 4).
  static BvhSettings default_settings() {
    BvhSettings s;
    s.max_leaf_size = 8;
    s.leaf_block = 4;
    return s;
  }

  /// Nearest hit with t in [ray.tmin, ray.tmax]; on a hit shrinks ray.tmax to it and fills hit: t, point, the unit
  /// geometric normal (b - a) x (c - a) of the triangle, prim = triangle index, uv = barycentrics (b1, b2) of
  /// vertices 1 and 2 of the triangle. stats (optional) counts wide nodes visited and triangles tested.
  bool intersect(Ray& ray, Hit& hit, TraversalStats* stats = nullptr) const;
  /// The nearest hits of many rays: hits[i] as intersect(rays[i], hits[i]) fills it (bit for bit), Hit{} (prim -1)
  /// for a miss. Several rays are walked at once, interleaved node by node, so that their cache misses overlap: faster
  /// on incoherent rays over large meshes, slower on coherent rays (their nodes are in cache; the switching costs).
  /// Throws InvalidInput when the spans' sizes differ.
  void intersect(std::span<const Ray> rays, std::span<Hit> hits) const;
  /// Any hit with t in [ray.tmin, ray.tmax] (shadow rays).
  bool occluded(const Ray& ray) const;

  /// The binary tree the wide one was collapsed from (its boxes, depth and leaf order).
  const Bvh& bvh() const { return bvh_; }
  /// The mesh's triangle count.
  size_t triangle_count() const { return triangle_count_; }
  /// The wide tree's width (4 or 8; 0 when the mesh is empty) and node count.
  int simd_width() const { return width_; }
  size_t wide_node_count() const { return wide_nodes_; }

  /// The SAH costs the collapse weighs: a wide node's visit and one block test, for a ray that hits their boxes. A
  /// visit costs about three tests: its loads wait on the previous visit, and ordering the hit children branches
  /// (measured: with 1 : 1, 0.5 or 0.25 incoherent casts were 1-3% slower on the bunny and on tori of 16.8K and 67K
  /// triangles; see docs/accel.md).
  static constexpr float kNodeCost = 1.0f, kBlockCost = 0.35f;
  /// The wide tree's SAH cost, which the collapse minimizes for the binary tree bvh(): the sum over its nodes of
  /// kNodeCost and over its leaves of kBlockCost per block, each weighted by its box's area over the root box's (the
  /// expected cost of a random line through the root box that visits every box it crosses). 0 for an empty mesh.
  double sah_cost() const;

 private:
  Bvh bvh_;
  size_t triangle_count_ = 0;
  int width_ = 0;
  int32_t root_ = 0;  // the wide tree's root reference (a leaf for meshes of one leaf)
  size_t wide_nodes_ = 0;
  RawVector<detail::MeshTreeLine> tree_;  // nodes and blocks (src/mesh_tree.hpp); uninitialized growth on huge pages

  /// Whether the tree mostly comes from memory, not from the caches: its walks then fetch for later steps into L2.
  /// The crossover measured on an AMD EPYC (1 MiB L2 per core) lay between trees of 15 and 29 MiB (tori of 270K and
  /// 540K triangles); see docs/accel.md, "Far trees".
  bool far_tree() const { return tree_.size() * sizeof(detail::MeshTreeLine) >= (size_t(24) << 20); }
};

/// The smooth normal at a mesh hit: the vertex normals interpolated by the barycentrics (hit.prim, hit.uv as MeshAccel
/// fills them) and normalized, or hit.normal when the mesh has no per-vertex normals.
Vec3f shading_normal(const TriMesh& mesh, const Hit& hit);

}  // namespace tessera
