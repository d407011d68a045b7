#include "tessera/subdiv/limit.hpp"

#include <algorithm>

#include "finite.hpp"
#include "sharpness.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/math/power_of_two.hpp"
#include "tessera/subdiv/topology.hpp"

namespace tessera {
namespace {

template <class Rules>
LimitSurface limit_with(const TopologyTables& t, const detail::LevelSharpness& sharpness, const Rules& rules,
                        const std::vector<Vec3>& p) {
  LimitSurface out;
  out.positions.resize(t.vertex_count());
  out.normals.resize(t.vertex_count());
  parallel_for(0, int64_t(t.vertex_count()), 1024, [&](int64_t b, int64_t e) {
    std::vector<float> ring_sharpness(t.max_valence());
    std::vector<Vec3> ring(t.max_valence()), diagonal(t.max_valence());
    TangentMasks tangents;
    for (int64_t vi = b; vi < e; ++vi) {
      const auto v = uint32_t(vi);
      const uint32_t edges = t.ring_edge_count(v), faces = t.ring_face_count(v);
      if (edges == 0) {
        out.positions[v] = p[v];
        out.normals[v] = Vec3(0.0);
        continue;
      }
      for (uint32_t i = 0; i < edges; ++i) ring[i] = p[t.ring_neighbor(v, i)];
      for (uint32_t i = 0; i < faces; ++i)
        diagonal[i] = p[t.corner_vertex(t.next_corner(t.next_corner(t.ring_corners(v)[i])))];

      VertexMask mask;
      switch (sharpness.rule(v, ring_sharpness)) {
        case VertexRule::smooth:
        case VertexRule::dart:
          mask = rules.smooth_limit(faces);
          Rules::smooth_limit_tangents(faces, tangents);
          break;
        case VertexRule::crease: {
          uint32_t ends[2];
          detail::crease_ends(std::span<const float>(ring_sharpness.data(), edges), ends);
          mask = crease_limit_mask(ends[0], ends[1]);
          Rules::crease_limit_tangents(edges, faces, ends[0], ends[1], tangents);
          break;
        }
        case VertexRule::corner:
          mask = corner_vertex_mask();
          Rules::corner_limit_tangents(edges, faces, tangents);
          break;
      }

      Vec3 position = p[v] * mask.vertex;
      for (uint32_t i = 0; i < edges; ++i) position += ring[i] * mask.ring;
      for (uint32_t i = 0; i < faces; ++i) position += diagonal[i] * mask.face;
      if (mask.crease != 0.0) position += (ring[mask.crease_ends[0]] + ring[mask.crease_ends[1]]) * mask.crease;
      out.positions[v] = position;

      Vec3 tangent[2];
      for (int k = 0; k < 2; ++k) {
        tangent[k] = p[v] * tangents.vertex[k];
        for (uint32_t i = 0; i < edges; ++i) tangent[k] += ring[i] * tangents.ring[k][i];
        for (uint32_t i = 0; i < faces; ++i) tangent[k] += diagonal[i] * tangents.face[k][i];
      }
      const Vec3 n = glm::cross(tangent[0], tangent[1]);
      const double len = glm::length(n);
      out.normals[v] = len > 0.0 ? n / len : Vec3(0.0);
    }
  });
  return out;
}

bool all_faces_of_size(const PolyMesh& mesh, uint32_t size) {
  for (size_t f = 0; f < mesh.face_count(); ++f)
    if (mesh.face_size(f) != size) return false;
  return true;
}

}  // namespace

LimitSurface limit_surface(const PolyMesh& mesh, const SubdivisionOptions& options) {
  if (options.scheme == SubdivisionScheme::midpoint)
    throw InvalidInput("limit_surface: midpoint subdivision has no smooth limit (its limit is the mesh itself)");
  const bool catmark = options.scheme == SubdivisionScheme::catmull_clark;
  if (!all_faces_of_size(mesh, catmark ? 4 : 3))
    throw InvalidInput(catmark ? "limit_surface: Catmull-Clark limit masks need quads (subdivide once first)"
                               : "limit_surface: Loop limit masks need triangles");
  const TopologyTables topology(mesh.face_offsets, mesh.face_vertices, mesh.vertex_count());
  const detail::LevelSharpness sharpness(topology, mesh, options.boundary);
  // Tangents of coordinates beyond 2^128 would overflow their cross product's length (and below 2^-128 underflow it):
  // such meshes are evaluated scaled by a power of two (rescale_exponent, tessera/math/power_of_two.hpp).
  const int e = rescale_exponent(std::span<const Vec3>(mesh.positions));
  std::vector<Vec3> scaled;
  if (e) {
    scaled = mesh.positions;
    scale_by_power_of_two(scaled, -e);
  }
  const std::vector<Vec3>& p = e ? scaled : mesh.positions;
  LimitSurface out = catmark ? limit_with(topology, sharpness, CatmarkRules{options.triangles}, p)
                             : limit_with(topology, sharpness, LoopRules{options.loop_weights}, p);
  scale_by_power_of_two(out.positions, e);
  detail::require_finite(out.positions, "limit_surface", "vertex");
  detail::require_finite(out.normals, "limit_surface", "normal");
  return out;
}

}  // namespace tessera
