#pragma once
// Limit positions and normals of subdivision surfaces: where each vertex converges after infinitely many steps, from
// the eigenvectors of the subdivision matrix (limit masks), and the normal T1 x T2 from the two limit tangents.
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/subdiv/subdivide.hpp"

namespace tessera {

/// Limit positions and unit normals, one per vertex of the mesh they were computed for.
struct LimitSurface {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  ///< zero for isolated vertices
};

/// The limit positions and normals of the vertices of `mesh` under options.scheme, with its creases and corners
/// (OpenSubdiv's Far::PrimvarRefiner::Limit at the same level; semi-sharp features use the rule they have now).
/// Precondition: Catmull-Clark needs quads (subdivide once first), Loop triangles.
/// Throws InvalidInput for other faces or the midpoint scheme, TopologyError for non-manifold meshes.
LimitSurface limit_surface(const PolyMesh& mesh, const SubdivisionOptions& options);

}  // namespace tessera
