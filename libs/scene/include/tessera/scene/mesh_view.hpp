#pragma once
// Helpers for drawing one mesh through the rasterizer, shared by `tessera raster`, the scene rasterizer and the
// examples' mesh view: facets split apart (flat shading whatever the file's normals), the polygon edges of a
// wireframe, and the camera distance that frames a bounding sphere.
#include <cstdint>
#include <utility>
#include <vector>

#include "tessera/math/camera.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// How a mesh's shadows are drawn: a shadow map fitted to the mesh (the notes' 2-pass z-buffer), or the mesh's
/// stencil shadow volume counted in front of the surface (z-pass) or behind it (z-fail: right with the eye in shadow,
/// needs a perspective camera, its far plane at infinity).
enum class ShadowMethod { map, zpass, zfail };

/// Every triangle with its own three corners (positions, and the colors and uvs where the mesh has them), each corner's
/// normal the triangle's unit face normal (b - a) x (c - a) (counterclockwise is the front). A degenerate triangle,
/// which covers no pixel, gets (0, 0, 1). Flat shading then shows the facets, where OpenGL's flat model would light
/// each triangle at its last vertex's normal.
TriMesh split_faceted(const TriMesh& mesh);

/// The polygon edges (not the triangulation's diagonals), each once as (smaller, larger) vertex index, sorted.
std::vector<std::pair<uint32_t, uint32_t>> polygon_edges(const PolyMesh& mesh);

/// The distance from a sphere's center at which the sphere of `radius` fills a view cone of half-angle `half_angle`
/// (radians) times `margin`: margin * radius / sin(half_angle). At margin 1 the cone touches the sphere; above 1 the
/// sphere lies inside with room to spare (its angular radius is asin(sin(half_angle) / margin)).
double sphere_fit_distance(double radius, double half_angle, double margin);

/// `camera` (its fovy kept) looking at the sphere (center, radius) from `direction` (any length, from the center
/// toward the eye) at sphere_fit_distance(radius, fovy / 2, margin); near and far 1.5 radii either side of the
/// center, near at least 1/1000 of the distance.
Camera frame_sphere(Camera camera, const Vec3& center, double radius, const Vec3& direction, double margin);

}  // namespace tessera
