#pragma once
// Primitive meshes for fixtures and pictures, all centered at the origin with outward-facing (counterclockwise seen
// from outside) faces.
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// Platonic solids with circumradius 1 (every vertex at distance 1 from the origin).
PolyMesh make_tetrahedron();
PolyMesh make_cube();          ///< 8 vertices, 6 quads, circumradius 1 (edge 2/sqrt(3))
PolyMesh make_octahedron();
PolyMesh make_dodecahedron();  ///< 12 pentagons
PolyMesh make_icosahedron();

/// The axis-aligned box [-1, 1]^3 as 6 quads (8 vertices).
PolyMesh make_box();
/// A sphere of radius 1 from latitude/longitude lines: `slices` around (>= 3), `stacks` pole to pole (>= 2); triangle
/// fans at the poles, quads elsewhere; uvs and normals per vertex.
PolyMesh make_uv_sphere(int slices, int stacks);
/// A sphere of radius 1 made by projecting a cube's faces, each split n x n (n >= 1) into quads.
PolyMesh make_quad_sphere(int n);
/// A cylinder of radius 1 around the y axis from y = -1 to 1, `segments` around (>= 3), optional cap polygons.
PolyMesh make_cylinder(int segments, bool caps = true);
/// A cone of base radius 1 at y = -1 with its apex at y = 1, `segments` around (>= 3), optional base cap.
PolyMesh make_cone(int segments, bool cap = true);
/// A torus around the y axis, major radius R, minor radius r, n segments around the ring and m around the tube.
PolyMesh make_torus(double major_radius, double minor_radius, int n, int m);
/// A flat nx x ny grid of quads covering [-1, 1]^2 in the xz plane (y = 0, normals +y), with uvs.
PolyMesh make_grid(int nx, int ny);

}  // namespace tessera
