#pragma once
// Subdivision rules, apart from topology and data (OpenSubdiv's Sdc layer): sharpness arithmetic and the weights
// (masks) that make the new face, edge and vertex points of each scheme and the limit positions and tangents. The
// refinement driver (subdivide.hpp) gathers each neighbourhood from TopologyTables and applies these weights.
//
// Conventions (as OpenSubdiv's masks): an edge mask weighs the edge's two end vertices and the point of each incident
// face; a vertex mask weighs the vertex, the far end of each incident edge ("ring") and each incident face's point.
// The point of a face is its face point for Catmull-Clark refinement, the vertex opposite the edge for Loop's edge
// rule, and the vertex diagonally opposite the vertex for limit masks on quads.
#include <cstdint>
#include <span>
#include <vector>

namespace tessera {

/// Sharpness at and above which an edge or vertex is infinitely sharp (OpenSubdiv's SHARPNESS_INFINITE).
inline constexpr float kInfiniteSharpness = 10.0f;

/// How semi-sharp edge sharpness decays from level to level.
enum class CreaseMethod {
  uniform,  ///< s -> s - 1 (the notes: "sharp rule s times, then smooth"; OpenSubdiv's default CREASE_UNIFORM)
  chaikin,  ///< s -> 3/4 s + 1/4 (mean of the other semi-sharp edges at the end vertex) - 1 (OpenSubdiv CREASE_CHAIKIN)
};

/// The weight beta of Loop's vertex rule (1 - k beta) v + beta sum(vi).
enum class LoopWeights {
  warren,  ///< beta = 3/(8k) for k > 3, 3/16 for k = 3: the notes' rule (Warren's simplification)
  loop,    ///< beta = (5/8 - (3/8 + 1/4 cos(2 pi / k))^2) / k: Loop's original, as OpenSubdiv
};

/// Catmull-Clark's edge rule next to triangles.
enum class TriangleSubdivision {
  catmark,  ///< the plain Catmull-Clark rule for every polygon (OpenSubdiv's default TRI_SUB_CATMARK)
  smooth,   ///< OpenSubdiv's TRI_SUB_SMOOTH: face weight 0.47 for triangles (Hbr's rounder triangles)
};

/// Which rule a vertex follows (OpenSubdiv's Crease::Rule), from its sharpness and its number of sharp edges.
enum class VertexRule : uint8_t {
  smooth,  ///< no sharp edge
  dart,    ///< one sharp edge: the smooth rule
  crease,  ///< two sharp edges: (6v + v1 + v2)/8
  corner,  ///< a sharp vertex or more than two sharp edges: v stays
};

/// Weights of a new edge point.
struct EdgeMask {
  double end = 0.5;   ///< weight of each end vertex
  double face = 0.0;  ///< weight of each incident face's point
};

/// Weights of a new vertex point (or of a limit position).
struct VertexMask {
  double vertex = 1.0;               ///< weight of the vertex itself
  double ring = 0.0;                 ///< weight of the far end of every incident edge
  double face = 0.0;                 ///< weight of every incident face's point
  double crease = 0.0;               ///< additional weight of the far ends of ring edges crease_ends[0] and [1]
  uint32_t crease_ends[2] = {0, 0};  ///< ring indices of the two sharp edges of a crease
};

/// Weights of the two limit tangents T1, T2 (normal = T1 x T2, OpenSubdiv's orientation): per tangent, the vertex,
/// each ring edge's far end and each ring face's point (the vertex diagonally opposite in a quad).
struct TangentMasks {
  double vertex[2] = {0.0, 0.0};
  std::vector<double> ring[2];
  std::vector<double> face[2];
  /// Zeroes every weight for a vertex with `edges` ring edges and `faces` ring faces.
  void reset(uint32_t edges, uint32_t faces);
};

/// One level of uniform sharpness decay (OpenSubdiv's decrementSharpness): <= 0 stays 0, >= 10 stays infinite,
/// s > 1 becomes s - 1, others 0.
float decrement_sharpness(float sharpness);

/// The sharpness of the child of an edge of sharpness s at one end vertex whose ring edges have sharpness `around`
/// (including s itself), under `method` (OpenSubdiv's Crease::SubdivideEdgeSharpnessAtVertex).
float child_edge_sharpness(CreaseMethod method, float sharpness, std::span<const float> around);

/// The rule of a vertex of sharpness `vertex_sharpness` with `sharp_edges` incident edges of sharpness > 0.
VertexRule vertex_rule(float vertex_sharpness, int sharp_edges);

/// The weight of the parent rule when a vertex's rule changes between levels (OpenSubdiv's
/// ComputeFractionalWeightAtVertex): the mean sharpness of what decays to smooth, clamped to 1.
float transition_weight(CreaseMethod method, float parent_vertex, float child_vertex,
                        std::span<const float> parent_edges, std::span<const float> child_edges);

/// The crease rule (6v + v1 + v2)/8 (the notes' sharp crease) with v1, v2 the far ends of ring edges end0 and end1.
VertexMask crease_vertex_mask(uint32_t end0, uint32_t end1);
/// The corner rule: v stays.
VertexMask corner_vertex_mask();
/// parent_weight * parent + (1 - parent_weight) * child (a semi-sharp transition). At most one may be a crease.
VertexMask blend(const VertexMask& parent, const VertexMask& child, double parent_weight);
/// The limit of a crease vertex (v1 + 4v + v2)/6 (the cubic B-spline along the crease); corners stay.
VertexMask crease_limit_mask(uint32_t end0, uint32_t end1);

/// Catmull-Clark (Catmull and Clark 1978; the notes; OpenSubdiv's Scheme<SCHEME_CATMARK>). Any polygons; splits
/// every n-gon into n quads around its face point (the centroid).
struct CatmarkRules {
  static constexpr bool kFacePoints = true;  ///< face points are made and edge/vertex masks weigh them
  static constexpr bool kLinear = false;     ///< the smooth rules are not linear interpolation

  TriangleSubdivision triangles = TriangleSubdivision::catmark;

  /// Smooth edge point (v0 + v1 + f0 + f1)/4 with f the face points; sizes of the two faces for the triangle option.
  EdgeMask smooth_edge(uint32_t faces, uint32_t size0, uint32_t size1) const;
  /// Smooth vertex point v' = ((k-2) v + R + F)/k with R the mean of the neighbours (edge ENDS) and F of the face
  /// points: the notes' (E + F + v(k-2))/k once E is read as the neighbours, = textbook (F + 2 Rmid + (k-3) v)/k.
  static VertexMask smooth_vertex(uint32_t valence);
  /// Smooth limit position (k^2 v + 4 sum(ei) + sum(fi)) / (k (k+5)) on quads (fi: diagonal vertices).
  static VertexMask smooth_limit(uint32_t valence);
  /// Limit tangents of smooth, crease (ends in ring order) and corner vertices on quads (OpenSubdiv's masks).
  static void smooth_limit_tangents(uint32_t valence, TangentMasks& masks);
  static void crease_limit_tangents(uint32_t edges, uint32_t faces, uint32_t end0, uint32_t end1, TangentMasks& masks);
  static void corner_limit_tangents(uint32_t edges, uint32_t faces, TangentMasks& masks);
};

/// Loop subdivision (Loop 1987; the notes). Triangles only; splits every triangle into 4 at the edge midpoints.
struct LoopRules {
  static constexpr bool kFacePoints = false;  ///< edge masks weigh the vertex opposite the edge in each triangle
  static constexpr bool kLinear = false;

  LoopWeights weights = LoopWeights::warren;

  /// beta of the vertex rule for valence k under `weights`.
  double beta(uint32_t valence) const;
  /// Smooth edge point 3/8 (v1 + v2) + 1/8 (v3 + v4) (the notes).
  static EdgeMask smooth_edge(uint32_t faces, uint32_t size0, uint32_t size1);
  /// Smooth vertex point (1 - k beta) v + beta sum(vi) (the notes).
  VertexMask smooth_vertex(uint32_t valence) const;
  /// Smooth limit position (1 - k chi) v + chi sum(vi), chi = 1 / (k + 3 / (8 beta)) (Hoppe et al. 1994).
  VertexMask smooth_limit(uint32_t valence) const;
  /// Limit tangents (cos, sin weights; OpenSubdiv's masks for creases and corners).
  static void smooth_limit_tangents(uint32_t valence, TangentMasks& masks);
  static void crease_limit_tangents(uint32_t edges, uint32_t faces, uint32_t end0, uint32_t end1, TangentMasks& masks);
  static void corner_limit_tangents(uint32_t edges, uint32_t faces, TangentMasks& masks);
};

/// Face (midpoint) subdivision (the notes): new points at edge midpoints (and face centroids for polygons); old
/// vertices stay. Every mask is linear interpolation, so creases change nothing.
struct MidpointRules {
  static constexpr bool kFacePoints = true;
  static constexpr bool kLinear = true;

  static EdgeMask smooth_edge(uint32_t, uint32_t, uint32_t) { return {}; }
  static VertexMask smooth_vertex(uint32_t) { return {}; }
};

}  // namespace tessera
