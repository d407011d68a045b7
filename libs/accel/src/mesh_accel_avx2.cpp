// MeshAccel's 8-wide traversal, compiled for AVX2 (chosen at run time by MeshAccel's constructor).
#include "mesh_traversal.hpp"

namespace tessera::mesh_traversal {

bool intersect8(const MeshAccel::WideNode<8>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray,
                Hit& hit, TraversalStats* stats) {
  return nearest_hit<8>(nodes, blocks, root, ray, hit, stats);
}

void intersect_stream8(const MeshAccel::WideNode<8>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root,
                       std::span<const Ray> rays, std::span<Hit> hits) {
  nearest_hits<8>(nodes, blocks, root, rays, hits);
}

bool occluded8(const MeshAccel::WideNode<8>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root,
               const Ray& ray) {
  return any_hit<8>(nodes, blocks, root, ray);
}

}  // namespace tessera::mesh_traversal
