// MeshAccel's 8-wide traversal, compiled for AVX2 (chosen at run time by MeshAccel's constructor).
#include "mesh_traversal.hpp"

namespace tessera::mesh_traversal {

bool intersect8(const MeshAccel::WideNode<8>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray,
                Nearest& nearest, TraversalStats* stats) {
  return nearest_hit<8>(nodes, blocks, root, ray, nearest, stats);
}

bool occluded8(const MeshAccel::WideNode<8>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray) {
  return traverse<8, true, false>(nodes, blocks, root, ray, nullptr, nullptr);
}

}  // namespace tessera::mesh_traversal
