#pragma once
// Primitive meshes for fixtures and pictures, all centered at the origin with outward-facing (counterclockwise seen
// from outside) faces.
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// Platonic solids with circumradius 1 (every vertex at distance 1 from the origin). The counting primitives below
/// throw InvalidInput when a count is out of range.
PolyMesh make_tetrahedron();
PolyMesh make_cube();  ///< 8 vertices, 6 quads, circumradius 1 (edge 2/sqrt(3))
PolyMesh make_octahedron();
PolyMesh make_dodecahedron();  ///< 12 pentagons
PolyMesh make_icosahedron();

/// The axis-aligned box [-1, 1]^3 as 6 quads (8 vertices).
PolyMesh make_box();
/// A sphere of radius 1 from latitude/longitude lines: `slices` around (>= 3), `stacks` pole to pole (>= 2); triangle
/// fans at the poles, quads elsewhere; normals per vertex, uvs per face corner (corner_uvs: u = longitude / 2pi,
/// v = 1 at the north pole) so that the seam and the poles stay closed. Throws InvalidInput for bad counts.
PolyMesh make_uv_sphere(int slices, int stacks);
/// A sphere of radius 1 made by projecting a cube's faces, each split n x n (n >= 1) into quads; normals per vertex.
PolyMesh make_quad_sphere(int n);
/// A cylinder of radius 1 around the y axis from y = -1 to 1, `segments` around (>= 3), optional cap polygons.
PolyMesh make_cylinder(int segments, bool caps = true);
/// A cone of base radius 1 at y = -1 with its apex at y = 1, `segments` around (>= 3), optional base cap.
PolyMesh make_cone(int segments, bool cap = true);
/// A torus around the y axis, major radius R, minor radius r (0 < r < R), n >= 3 segments around the ring and m >= 3
/// around the tube; quads, normals per vertex, uvs per face corner (seams stay closed).
PolyMesh make_torus(double major_radius, double minor_radius, int n, int m);
/// A flat nx x ny grid of quads covering [-1, 1]^2 in the xz plane (y = 0, faces facing +y), with per-vertex
/// normals and uvs (u along x, v along z).
PolyMesh make_grid(int nx, int ny);

}  // namespace tessera
