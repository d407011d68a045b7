#pragma once
// PolyMesh <-> TriMesh: what renderers draw is triangles with per-vertex properties only, so face-varying uvs and
// normals (texture seams, creases) split their vertices.
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// Triangulates (see triangulate()) and splits every vertex whose corners carry different face-varying uvs or
/// normals into one vertex per distinct (uv, normal) pair, so the result has per-vertex properties only.
/// Per-vertex properties are copied. Without face-varying data the vertex numbering is unchanged.
TriMesh to_tri_mesh(const PolyMesh& mesh);

/// A TriMesh as a PolyMesh of triangles with the same vertices and per-vertex properties.
PolyMesh to_poly_mesh(const TriMesh& mesh);

}  // namespace tessera
