#pragma once
// The marching-cubes case tables (Lorensen & Cline 1987; the corner and edge numbering of Paul Bourke's
// "Polygonising a scalar field", which vtkMarchingCubes and scikit-image's method='lorensen' share).
//
// Corners: 0 (0,0,0), 1 (1,0,0), 2 (1,1,0), 3 (0,1,0), 4 (0,0,1), 5 (1,0,1), 6 (1,1,1), 7 (0,1,1). Bit c of a case
// index is set when corner c is inside (value >= iso). Edges: 0 = 0-1, 1 = 1-2, 2 = 2-3, 3 = 3-0, 4 = 4-5, 5 = 5-6,
// 6 = 6-7, 7 = 7-4, 8 = 0-4, 9 = 1-5, 10 = 2-6, 11 = 3-7.
//
// The tables are not typed in: they are generated from the cube's geometry. For each case the iso-surface crosses
// the cube faces in segments (one per face with two crossing edges; two on an ambiguous face, whose pairing is the
// face rule); the segments chain into closed polygons, oriented so that triangles face the outside (value < iso),
// and each polygon is fanned from its lowest-numbered edge, except that the classic table splits polygons along the
// diagonals that Lorensen & Cline's hand-made table chose (written out in mc_table.cpp; see docs/volume.md).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tessera/math/types.hpp"

namespace tessera::mc {

/// Corner positions on the unit cube.
const std::array<glm::ivec3, 8>& corners();
/// The two corners of each edge.
const std::array<std::array<int, 2>, 12>& edges();
/// The four corners of each face in cyclic order: z=0, z=1, y=0, y=1, x=0, x=1.
const std::array<std::array<int, 4>, 6>& faces();

/// Edge index kCenter + k stands for the k-th center vertex of a cell (the centroid of one polygon's vertices), used
/// by topological mode; a cell has at most kMaxCenters of them.
inline constexpr int kCenter = 12;
inline constexpr int kMaxCenters = 4;

/// One case's triangles: indices into the 12 edges (or kCenter), three per triangle, counterclockwise from outside.
struct CaseTriangles {
  std::vector<std::array<uint8_t, 3>> triangles;
  std::vector<uint16_t> center_edges;  ///< per center vertex kCenter + k, the edges averaged into it
};

/// Bit f set when face f of `cube_case` is ambiguous (its two inside corners are diagonal).
int ambiguous_faces(int cube_case);

/// Triangulates a case. Bit f of `join` says that on ambiguous face f the inside corners are joined (the segments cut
/// off the outside corners); otherwise they are separated. `split_shared_faces` puts a center vertex in polygons that
/// hold both segments of one face, so that no diagonal can be shared with the neighbouring cell (keeps the mesh
/// manifold). Other polygons are split along those of `diagonals` (pairs of edges) that join two of their vertices
/// and fanned from their lowest edge otherwise. Source: the construction above; cases 0-255 (throws InvalidInput
/// outside).
CaseTriangles triangulate_case(int cube_case, int join, bool split_shared_faces,
                               std::span<const std::array<int, 2>> diagonals = {});

/// The classic 256-case table: every ambiguous face separates its inside corners, and polygons are split along the
/// classic table's diagonals, so each case gives the same triangles as Lorensen & Cline's table (vtkMarchingCubes).
const std::array<CaseTriangles, 256>& classic_table();

/// Case indices of the 15 base configurations of Lorensen and Cline (Figure 3 of the paper), in their order.
const std::array<int, 15>& base_cases();

}  // namespace tessera::mc
