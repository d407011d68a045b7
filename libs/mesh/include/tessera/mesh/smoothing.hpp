#pragma once
// Laplacian smoothing (the notes: move each vertex toward the average of its neighbours, v = (v1 + ... + vk) / k —
// it evens out the triangles but shrinks the surface), with cotangent weights, and Taubin's lambda|mu smoothing,
// which alternates a shrinking and an inflating step and so keeps the volume.
#include <functional>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

enum class SmoothingMethod {
  laplacian,  ///< uniform weights, the notes' umbrella operator: x += lambda (average of neighbours - x)
  cotangent,  ///< weights (cot alpha + cot beta) / 2 of the angles facing each edge (Desbrun et al. 1999)
  taubin,     ///< uniform weights, a lambda step then a mu step per iteration (taubin 1995)
};

/// Parameters of smooth(); the defaults are Taubin's (lambda = 0.5, mu = -0.53, pass band k_pb ~ 0.1).
struct SmoothingOptions {
  SmoothingMethod method = SmoothingMethod::laplacian;
  int iterations = 10;       ///< steps (Taubin: pairs of steps), >= 0
  double lambda = 0.5;       ///< the shrinking step, in (0, 1]; 1 replaces a vertex by its neighbours' average
  double mu = -0.53;         ///< Taubin's inflating step, < -lambda
  bool fix_boundary = true;  ///< keep boundary and non-manifold vertices where they are
};

/// Smooths the vertex positions in place (Jacobi steps: every vertex moves from the old positions). Neighbours are
/// the vertices sharing a face edge; cotangent weights use the faces fan-triangulated, clamped at 0 (obtuse
/// triangles would make them negative). `progress` (optional) is called after every step with the step count. A mesh
/// that had normals (per vertex or per corner) gets the smoothed shape's area-weighted vertex normals; uvs and colors
/// stay as they are.
/// Throws InvalidInput for out-of-range parameters.
void smooth(PolyMesh& mesh, const SmoothingOptions& options, const std::function<void(int)>& progress = {});

}  // namespace tessera
