#pragma once
// Subdivision surfaces: one refinement driver over TopologyTables fed by the masks of each scheme (rules.hpp), as
// OpenSubdiv keeps Sdc rules apart from Far/Vtr refinement. Midpoint (face) subdivision, Loop, Catmull-Clark, with
// boundaries, sharp and semi-sharp creases and corners (the notes; DeRose, Kass and Truong 1998).
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/subdiv/rules.hpp"

namespace tessera {

class Progress;

enum class SubdivisionScheme {
  midpoint,       ///< face subdivision: triangles 1 -> 4 on a triangle mesh, else n-gons -> n quads; vertices stay
  loop,           ///< Loop: triangles 1 -> 4
  catmull_clark,  ///< Catmull-Clark: n-gons -> n quads
};

/// How boundary vertices are treated (boundary edges are always infinitely sharp creases).
enum class BoundaryInterpolation {
  edge_only,        ///< boundary vertices follow the crease rule (6v + v1 + v2)/8 (the notes)
  edge_and_corner,  ///< as edge_only, but a vertex with one face (a corner of the boundary) stays where it is
};

/// Settings of subdivide(). The defaults are the notes' rules; crease method and triangle rule as OpenSubdiv's.
struct SubdivisionOptions {
  SubdivisionScheme scheme = SubdivisionScheme::catmull_clark;
  int levels = 1;  ///< refinement steps, 0..12
  BoundaryInterpolation boundary = BoundaryInterpolation::edge_only;
  CreaseMethod crease_method = CreaseMethod::uniform;            ///< decay of semi-sharp creases
  LoopWeights loop_weights = LoopWeights::warren;                ///< the notes' beta, or Loop's original
  TriangleSubdivision triangles = TriangleSubdivision::catmark;  ///< Catmull-Clark next to triangles
  Progress* progress = nullptr;                                  ///< advanced by one per level when set
};

/// Subdivides `mesh` options.levels times (uniformly, every face). The result's vertices are the vertex points (the
/// original vertices keep their indices), then the face points (quad splits only), then the edge points, one per
/// edge in order of first appearance (OpenSubdiv's default order); per-vertex uvs and colors are refined with the
/// same masks; face-varying uvs (corner_uvs, texture seams) are refined linearly inside every face, as OpenSubdiv's
/// FVAR_LINEAR_ALL (face point = average of the face's corner uvs, edge point = midpoint, vertex = its corner's uv),
/// so seams stay where they are and a linear map stays linear; creases and corners carry the remaining sharpness,
/// so subdividing twice equals two levels. Normals (per vertex or per corner) are dropped: they do not subdivide
/// (recompute them, or take the limit normals). Parallel and deterministic.
/// Throws InvalidInput (bad faces, a crease that names no edge, NaN sharpness, Loop on non-triangles, levels out of
/// range, corner_uvs not one per corner) and TopologyError (non-manifold edges or vertices).
PolyMesh subdivide(const PolyMesh& mesh, const SubdivisionOptions& options);

/// Catmull-Clark, Loop and midpoint subdivision with the default options (see subdivide()).
PolyMesh catmull_clark_subdivide(const PolyMesh& mesh, int levels = 1);
PolyMesh loop_subdivide(const PolyMesh& mesh, int levels = 1);
PolyMesh midpoint_subdivide(const PolyMesh& mesh, int levels = 1);

/// A geodesic sphere (the notes: face subdivision of an octahedron or icosahedron): `levels` midpoint 1 -> 4 splits
/// of the triangle mesh `base`, every vertex projected onto the unit sphere around the origin after each split.
/// Throws InvalidInput when base is not a triangle mesh or has a vertex at the origin.
PolyMesh geodesic_sphere(const PolyMesh& base, int levels);

}  // namespace tessera
