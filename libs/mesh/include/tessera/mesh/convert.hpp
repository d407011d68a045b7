#pragma once
// PolyMesh <-> TriMesh: what renderers draw is triangles with per-vertex properties only, so face-varying uvs and
// normals (texture seams, creases) split their vertices.
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// Triangulates (see triangulate()) and splits seams (split_seams), so the result has per-vertex properties only.
/// Without face-varying data the vertex numbering is unchanged.
TriMesh to_tri_mesh(const PolyMesh& mesh);

/// Makes face-varying uvs and normals per-vertex (what PLY and OFF can hold): every vertex whose corners carry
/// different values becomes one vertex per distinct (uv, normal) pair; faces keep their sizes. Per-vertex properties
/// are copied; creases and corners on split vertices go to the first copy. Without face-varying data the mesh is
/// returned unchanged.
PolyMesh split_seams(const PolyMesh& mesh);

/// A TriMesh as a PolyMesh of triangles with the same vertices and per-vertex properties.
PolyMesh to_poly_mesh(const TriMesh& mesh);

}  // namespace tessera
