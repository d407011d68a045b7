// MeshAccel's 8-wide traversal, compiled for AVX2 (chosen at run time by MeshAccel's constructor).
#include "mesh_traversal.hpp"

namespace tessera::mesh_traversal {

bool intersect8(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats, bool far_tree) {
  return nearest_hit<8>(tree, root, ray, hit, stats, far_tree);
}

void intersect_stream8(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits, bool far_tree) {
  nearest_hits<8>(tree, root, rays, hits, far_tree);
}

bool occluded8(Tree tree, int32_t root, const Ray& ray, bool far_tree) { return any_hit<8>(tree, root, ray, far_tree); }

}  // namespace tessera::mesh_traversal
