#pragma once
// Fractal mountains (the notes, after Carpenter): random midpoint displacement with a range that shrinks every level.
//   1D: split every segment, move its midpoint to a random height; the range is 1/2 at the first level, then 1/4,
//       1/8, ... (roughness 0.5; a larger roughness keeps more of the range per level and gives rougher terrain).
//   2D: split every triangle into four through its edge midpoints and move the midpoints up or down. A midpoint is
//       made once per edge and shared by both triangles beside it, so the surface has no cracks.
//   Grids: diamond-square, the same idea on a (2^n + 1)^2 height map.
// Every random number comes from a PCG32 stream keyed by the seed and the point it displaces, so a terrain is the
// same for a given seed on every run and every thread count.
#include <cstdint>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// Settings shared by the midpoint-displacement generators.
struct TerrainOptions {
  int depth = 6;               ///< subdivision levels (1D and grids: 2^depth segments per side)
  double initial_range = 0.5;  ///< width of the first level's displacement interval (the notes: 1/2)
  double roughness = 0.5;      ///< range factor from one level to the next, in (0, 1) (the notes: halving, 0.5)
  uint64_t seed = 1;           ///< the random stream; equal seeds give equal terrains
};

/// The deepest level of each generator: 1D 24, triangles 10, grids 12. Deeper throws InvalidInput.
inline constexpr int kMaxTerrainDepth1D = 24, kMaxTerrainDepthTriangles = 10, kMaxTerrainDepthGrid = 12;

/// The 1D mountain profile: 2^depth + 1 heights at x = i / 2^depth, both ends at height 0; the midpoints of level k
/// (k = 0 first) move by a uniform amount in [-r_k/2, r_k/2], r_k = initial_range * roughness^k.
/// Throws InvalidInput for bad options.
std::vector<double> midpoint_displacement_1d(const TerrainOptions& options);

/// The 2D mountain on the equilateral triangle with side 1 in the xz plane (y up, corners at height 0), subdivided
/// `depth` times: 4^depth triangles, (2^depth + 1)(2^depth + 2)/2 vertices, faces counterclockwise seen from above,
/// per-vertex colors by height. Throws InvalidInput for bad options.
PolyMesh triangle_mountain(const TerrainOptions& options);

/// Diamond-square height map of (2^depth + 1)^2 samples, corners at height 0 (row 0 is z = 0).
/// Throws InvalidInput for bad options.
Image<float> diamond_square(const TerrainOptions& options);

/// A height map as a mesh over [0, 1]^2 in the xz plane (height along y, times `height_scale`): two triangles per
/// grid cell, counterclockwise seen from above, per-vertex colors by height. Throws InvalidInput for maps under 2x2.
PolyMesh height_map_mesh(const Image<float>& heights, double height_scale = 1);

/// The height map as a picture: terrain_color() of the height normalized to the map's own [min, max].
ImageRGB height_map_picture(const Image<float>& heights);

/// Terrain colors along t in [0, 1]: deep water, shore, grass, rock, snow.
Vec3f terrain_color(double t);

}  // namespace tessera
