#pragma once
// Bicubic Bezier patches (the notes' "Cubic Bezier Patches - Bezier inside Bezier") and their tessellation.
//
// A patch has 16 control points in 4 rows of 4, P[4 i + j], and S(u, v) = sum_i sum_j B_i(u) B_j(v) P[4 i + j] with
// the cubic Bernstein basis (the .bpt convention, data/MANIFEST.md). Row i is the Bezier curve G_{i+1} of the notes;
// the notes' t runs along every curve (v here) and s chooses between them (u here): Q(s, t) = S(s, t).
#include <array>
#include <span>
#include <vector>

#include "tessera/curves/bezier.hpp"
#include "tessera/math/types.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

/// A bicubic Bezier patch.
struct BezierPatch {
  std::array<Vec3, 16> points{};  ///< P[4 i + j]: row i (along u), column j (along v)

  /// Control point of row i, column j (0..3 each).
  const Vec3& at(int i, int j) const { return points[size_t(4 * i + j)]; }
  Vec3& at(int i, int j) { return points[size_t(4 * i + j)]; }
  /// Row i as a cubic Bezier curve in v (the notes' curve G_{i+1}).
  Bezier3 row(int i) const { return cubic(at(i, 0), at(i, 1), at(i, 2), at(i, 3)); }
};

/// S(u, v) by the notes' four steps: (1) the four row curves G_1..G_4, (2) their points G_k(t) at t = v, (3) the cubic
/// through those four points as control points, (4) that curve at s = u.
Vec3 evaluate_four_curves(const BezierPatch& patch, double u, double v);

/// S(u, v) by the tensor-product Bernstein sum sum_i sum_j B_i(u) B_j(v) P_ij (agrees with the four steps to
/// round-off).
Vec3 evaluate_bernstein(const BezierPatch& patch, double u, double v);

/// A point of a patch with its partial derivatives.
struct PatchSample {
  Vec3 position;
  Vec3 du;  ///< ∂S/∂u = 3 sum_i B²_i(u) sum_j B_j(v) (P_{i+1,j} - P_ij), exactly zero along a collapsed column
  Vec3 dv;  ///< ∂S/∂v, exactly zero along a collapsed row (e.g. the teapot lid's tip)
};

/// S(u, v) and its partials (the derivatives through the hodographs of the rows and of the u curve).
PatchSample evaluate_with_partials(const BezierPatch& patch, double u, double v);

/// The unit normal du x dv at (u, v). Where it vanishes (a row or column of control points collapsed to one point,
/// as at the teapot's lid and bottom) it is the limit direction, taken at a nearby point toward the patch center.
/// Zero only for a patch with no area near (u, v).
Vec3 patch_normal(const BezierPatch& patch, double u, double v);

/// Per-patch sample count for `tolerance` (> 0): the smallest n with the Filip–Magedson–Markot (1986) bound
/// (1/8n²)(M_uu + 2 M_uv + M_vv) <= tolerance on the distance between the patch and its n x n triangulated grid, with
/// M_uu = 6 max |Δ²_u P|, M_uv = 9 max |Δ_u Δ_v P|, M_vv = 6 max |Δ²_v P|; clamped to [1, max_steps].
int flatness_steps(const BezierPatch& patch, double tolerance, int max_steps = 256);

/// Which side of the patches the normals and counterclockwise triangles face.
enum class PatchOrientation {
  as_given,  ///< du x dv, as the data is wound
  flipped,   ///< dv x du
  outward,   ///< as given or flipped, whichever makes the signed volume about the control points' centroid positive:
             ///< outward for closed (or nearly closed, like the teapot) models, arbitrary for an open sheet
};

/// How to tessellate patches.
struct PatchTessellation {
  int steps = 8;         ///< uniform: every patch on an (steps+1) x (steps+1) grid of (u, v) (DESIGN.md section 4)
  double tolerance = 0;  ///< > 0: adaptive, each patch gets flatness_steps(patch, tolerance, steps) instead
  PatchOrientation orientation = PatchOrientation::as_given;
};

/// Tessellates patches into one TriMesh: per patch, (n+1)² vertices with position, unit normal and uv = (u, v), and
/// 2n² triangles counterclockwise around the normal, patch after patch (uniform: n = steps), in parallel over patches.
/// Shared patch borders are not welded (their vertices coincide to round-off) and collapsed rows keep their zero-area
/// triangles, so the counts are exact. Throws InvalidInput unless steps is in 1..1024 and tolerance >= 0, or when the
/// mesh would exceed 2^32 vertices.
TriMesh tessellate(std::span<const BezierPatch> patches, const PatchTessellation& options = {});

/// The control nets as a polygon mesh: per patch its 16 points and 9 quads (for pictures of the construction).
PolyMesh control_net(std::span<const BezierPatch> patches);

}  // namespace tessera
