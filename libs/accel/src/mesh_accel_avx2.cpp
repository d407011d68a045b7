// MeshAccel's 8-wide traversal, compiled for AVX2 (chosen at run time by MeshAccel's constructor).
#include "mesh_traversal.hpp"

namespace tessera::mesh_traversal {

bool intersect8(Tree tree, int32_t root, Ray& ray, Hit& hit, TraversalStats* stats) {
  return nearest_hit<8>(tree, root, ray, hit, stats);
}

void intersect_stream8(Tree tree, int32_t root, std::span<const Ray> rays, std::span<Hit> hits, bool far_tree) {
  if (far_tree)
    nearest_hits<8, _MM_HINT_T1>(tree, root, rays, hits);
  else
    nearest_hits<8, _MM_HINT_T0>(tree, root, rays, hits);
}

bool occluded8(Tree tree, int32_t root, const Ray& ray) { return any_hit<8>(tree, root, ray); }

}  // namespace tessera::mesh_traversal
