#pragma once
// Marching cubes (Lorensen & Cline 1987, the notes' chapter on iso-surfaces): an indexed triangle mesh of the iso
// surface value == iso of a volume.
//
// Rule for samples equal to the iso value: a voxel is inside when value >= iso, and an edge is cut when exactly one
// end is inside. The cut parameter t = (iso - a) / (b - a) is clamped into [kEdgeNudge, 1 - kEdgeNudge], so a vertex
// never lands exactly on a voxel: vertices on different edges are distinct points, and since no three points in the
// interiors of distinct cube edges are collinear, no triangle has zero area.
#include "tessera/core/memory.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/volume/volume.hpp"

namespace tessera {

/// How far (as a fraction of the edge) a vertex is kept from the voxels at the edge's ends.
inline constexpr double kEdgeNudge = 1e-5;

/// Settings of marching_cubes().
struct MarchingCubesOptions {
  float iso = 0.0f;          ///< the iso value; inside is value >= iso
  bool topological = false;  ///< resolve ambiguous faces by the asymptotic decider (Nielson & Hamann 1991)
  bool normals = true;       ///< per-vertex normals from the interpolated central-difference gradient
  int slab_layers = 8;       ///< cell layers per parallel work item (any value gives the same mesh)
  /// Only the cell layers [first_layer, end_layer) of z (end_layer -1: to the last): a brick of a volume split among
  /// MPI ranks, whose slices beyond its layers are there for the normals' central differences. The brick's top plane
  /// gets its vertices too, the same as the next brick's bottom plane (welded when the bricks' meshes are joined).
  int first_layer = 0, end_layer = -1;
};

/// Float voxels held elsewhere (a numpy array, a mapped file), laid out as Volume's (x fastest, then y, then z), with
/// the volume's placement: what marching cubes reads, so that such voxels need not be copied into a Volume first.
struct VoxelGrid {
  const float* voxels = nullptr;  ///< dims.x * dims.y * dims.z values
  glm::ivec3 dims{0};
  Vec3 spacing{1.0}, origin{0.0};
  /// The grid's slice 0 is slice z_offset of the volume that `origin` places (a brick of a split volume): vertices
  /// come out where that volume's own extraction puts them, bit for bit.
  int z_offset = 0;

  /// The grid of a volume (valid while it lives).
  static VoxelGrid of(const Volume<float>& volume) {
    return {volume.voxels().data(), volume.dims(), volume.spacing(), volume.origin(), 0};
  }
};

/// Extracts the iso-surface as a triangle mesh in world coordinates (origin + spacing * voxel). Each cut edge gives
/// one shared vertex; triangles are counterclockwise seen from the outside (value < iso), and normals point outside.
/// Classic mode uses mc::classic_table(); topological mode decides every ambiguous face by its bilinear saddle value
/// and splits polygons that would share a diagonal with a neighbour, so closed surfaces are closed 2-manifolds.
/// Parallel over slabs of z layers; the result is identical for any thread count. Volumes under 2 voxels along an
/// axis give an empty mesh.
PolyMesh marching_cubes(const Volume<float>& volume, const MarchingCubesOptions& options = {});
/// marching_cubes() of voxels held elsewhere. Throws InvalidInput for null voxels, dims < 1 or over kMaxVoxels, or a
/// spacing that is not positive.
PolyMesh marching_cubes(const VoxelGrid& grid, const MarchingCubesOptions& options = {});

/// An iso-surface as marching cubes outputs it: float positions and normals (as VTK's and scikit-image's are) and
/// 3 indices per triangle; half the bytes of a PolyMesh, whose dvec3 arrays and face offsets the extraction spends
/// most of its time writing.
struct IsoSurface {
  RawVector<Vec3f> positions;
  RawVector<Vec3f> normals;  ///< per vertex, or empty
  RawVector<uint32_t> indices;

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return indices.size() / 3; }
  /// The same surface as a TriMesh (double positions and normals).
  TriMesh to_tri_mesh() const;
};

/// marching_cubes() into an IsoSurface: the same vertices (rounded to float), normals and triangles, in the same
/// order; identical for any thread count.
IsoSurface extract_iso_surface(const Volume<float>& volume, const MarchingCubesOptions& options = {});

}  // namespace tessera
