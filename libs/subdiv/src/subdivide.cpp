// The refinement driver: topology and data flow of one uniform refinement step, for any scheme's rules.
#include "tessera/subdiv/subdivide.hpp"

#include <cmath>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "finite.hpp"
#include "sharpness.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/math/power_of_two.hpp"
#include "tessera/subdiv/topology.hpp"

namespace tessera {
namespace {

constexpr int64_t kGrain = 2048;
constexpr int64_t kAhead = 8;  // elements between a prefetch and its use
constexpr int kMaxLevels = 12;

// One level of one scheme. Child vertices: vertex points [0, V), face points [V, V + F) for quad splits, then edge
// points, one per parent edge. Rules supplies the weights; everything topological happens here.
template <class Rules>
class LevelRefiner {
 public:
  LevelRefiner(const TopologyTables& topology, const detail::LevelSharpness& sharpness, const Rules& rules,
               CreaseMethod method, bool quad_split)
      : t_(topology), sharp_(sharpness), rules_(rules), method_(method), quads_(quad_split) {
    if constexpr (!Rules::kLinear) {
      smooth_edge_ = rules_.smooth_edge(2, 4, 4);
      smooth_vertex_.resize(size_t(t_.max_valence()) + 1);
      for (uint32_t k = 1; k <= t_.max_valence(); ++k) smooth_vertex_[k] = rules_.smooth_vertex(k);
    }
  }

  size_t child_vertex_count() const { return first_edge_point() + t_.edge_count(); }

  // Computes every child point of one vertex-interpolated property (positions, uvs, colors).
  template <class T>
  void refine(std::span<const T> parent, std::span<T> child) const {
    const auto n = uint32_t(t_.vertex_count());
    if (quads_) {
      parallel_for(0, int64_t(t_.face_count()), kGrain, [&](int64_t b, int64_t e) {
        for (int64_t f = b; f < e; ++f) {
          T sum(0.0);
          for (uint32_t v : t_.face(f)) sum += parent[v];
          child[n + f] = sum * (1.0 / double(t_.face_size(f)));
        }
      });
    }
    // The gathers are bound by the latency of scattered loads: fetch the topology and the points a few elements
    // ahead.
    parallel_for(0, int64_t(t_.edge_count()), kGrain, [&](int64_t b, int64_t e) {
      std::vector<float> buffer(t_.max_valence());
      for (int64_t edge = b; edge < e; ++edge) {
        if (edge + 3 * kAhead < e) t_.prefetch_edge(uint32_t(edge + 3 * kAhead));
        if (edge + 2 * kAhead < e) t_.prefetch_edge_second_face(uint32_t(edge + 2 * kAhead));
        if (edge + kAhead < e) prefetch_edge_points<T>(uint32_t(edge + kAhead), parent, child);
        child[edge_point(uint32_t(edge))] = edge_point_value<T>(uint32_t(edge), parent, child, buffer);
      }
    });
    parallel_for(0, int64_t(n), kGrain, [&](int64_t b, int64_t e) {
      std::vector<float> buffer(2 * size_t(t_.max_valence()));
      for (int64_t v = b; v < e; ++v) {
        if (v + kAhead < e) prefetch_vertex_points<T>(uint32_t(v + kAhead), parent, child);
        child[v] = vertex_point_value<T>(uint32_t(v), parent, child, buffer);
      }
    });
  }

  size_t child_face_count() const { return quads_ ? t_.corner_count() : 4 * t_.face_count(); }

  // The child faces: n quads per n-gon (vertex point, edge point, face point, previous edge point), or 4 triangles
  // per triangle (three corners, then the middle one). allocate_child_faces() sizes the arrays, child_faces() fills
  // them.
  void allocate_child_faces(PolyMesh& child) const {
    const size_t faces = child_face_count();
    resize_fresh(child.face_offsets, faces + 1);
    resize_fresh(child.face_vertices, (quads_ ? 4 : 3) * faces);
  }
  void child_faces(PolyMesh& child) const {
    const size_t faces = child_face_count();
    const uint32_t size = quads_ ? 4 : 3;
    parallel_for(0, int64_t(faces + 1), 16 * kGrain, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) child.face_offsets[i] = uint32_t(size * i);
    });
    uint32_t* out = child.face_vertices.data();
    parallel_for(0, int64_t(t_.face_count()), kGrain, [&](int64_t b, int64_t e) {
      for (int64_t f = b; f < e; ++f) {
        const uint32_t o = t_.face_offset(f), n = t_.face_size(f);
        if (quads_) {
          for (uint32_t j = 0; j < n; ++j) {
            uint32_t* q = out + 4 * size_t(o + j);
            q[0] = t_.corner_vertex(o + j);
            q[1] = edge_point(t_.corner_edge(o + j));
            q[2] = uint32_t(t_.vertex_count() + f);
            q[3] = edge_point(t_.corner_edge(o + (j + n - 1) % n));
          }
        } else {
          const uint32_t e0 = edge_point(t_.corner_edge(o)), e1 = edge_point(t_.corner_edge(o + 1)),
                         e2 = edge_point(t_.corner_edge(o + 2));
          const uint32_t tri[12] = {t_.corner_vertex(o),
                                    e0,
                                    e2,
                                    t_.corner_vertex(o + 1),
                                    e1,
                                    e0,
                                    t_.corner_vertex(o + 2),
                                    e2,
                                    e1,
                                    e0,
                                    e1,
                                    e2};
          std::copy(std::begin(tri), std::end(tri), out + 12 * size_t(f));
        }
      }
    });
  }

  // Face-varying values (uvs) refined linearly inside each face, as OpenSubdiv's FVAR_LINEAR_ALL: face point =
  // average of the face's corners, edge point = midpoint of the edge's two corners, vertex = its own corner. Every
  // child corner lies inside one parent face, so the values on either side of a seam never mix.
  template <class T>
  void refine_face_varying(std::span<const T> parent, std::vector<T>& child) const {
    resize_fresh(child, (quads_ ? 4 : 3) * child_face_count());
    parallel_for(0, int64_t(t_.face_count()), kGrain, [&](int64_t b, int64_t e) {
      for (int64_t f = b; f < e; ++f) {
        const uint32_t o = t_.face_offset(f), n = t_.face_size(f);
        const auto mid = [&](uint32_t j) { return (parent[o + j] + parent[o + (j + 1) % n]) * 0.5; };
        if (quads_) {
          T center(0.0);
          for (uint32_t j = 0; j < n; ++j) center += parent[o + j];
          center *= 1.0 / double(n);
          for (uint32_t j = 0; j < n; ++j) {
            T* q = child.data() + 4 * size_t(o + j);
            q[0] = parent[o + j];
            q[1] = mid(j);
            q[2] = center;
            q[3] = mid((j + n - 1) % n);
          }
        } else {
          const T m0 = mid(0), m1 = mid(1), m2 = mid(2);
          const T tri[12] = {parent[o], m0, m2, parent[o + 1], m1, m0, parent[o + 2], m2, m1, m0, m1, m2};
          std::copy(std::begin(tri), std::end(tri), child.data() + 12 * size_t(f));
        }
      }
    });
  }

  // The creases and corners of the child level: the two halves of every tagged edge and every tagged vertex, with
  // their subdivided sharpness (boundaries and boundary corners are implied by the topology at every level).
  void child_tags(PolyMesh& child) const {
    std::vector<float> around(t_.max_valence());
    auto sharpness_at = [&](uint32_t v, float s) {
      const uint32_t n = t_.ring_edge_count(v);
      for (uint32_t i = 0; i < n; ++i) around[i] = sharp_.edge(t_.ring_edge(v, i));
      return child_edge_sharpness(method_, s, std::span<const float>(around.data(), n));
    };
    for (uint32_t e : sharp_.tagged_edge_ids()) {
      const auto [a, b] = t_.edge_vertices(e);
      const float s = sharp_.edge(e);
      if (const float sa = sharpness_at(a, s); sa > 0.0f) child.creases.push_back({a, edge_point(e), sa});
      if (const float sb = sharpness_at(b, s); sb > 0.0f) child.creases.push_back({edge_point(e), b, sb});
    }
    for (const VertexCorner& c : sharp_.corner_tags())
      if (const float s = decrement_sharpness(c.sharpness); s > 0.0f) child.corners.push_back({c.v, s});
  }

 private:
  uint32_t first_edge_point() const { return uint32_t(t_.vertex_count() + (quads_ ? t_.face_count() : 0)); }
  uint32_t edge_point(uint32_t e) const { return first_edge_point() + e; }

  // The sharpness of v's ring edges one level down, as seen from v (for Chaikin they depend on the end vertex).
  std::span<const float> ring_sharpness(uint32_t v, std::vector<float>& buffer) const {
    const uint32_t n = t_.ring_edge_count(v);
    for (uint32_t i = 0; i < n; ++i) buffer[i] = sharp_.edge(t_.ring_edge(v, i));
    return {buffer.data(), n};
  }

  // Does edge e (sharpness s > 0) keep a crease in both halves? (OpenSubdiv: the child vertex rule is Crease.)
  bool child_is_crease(uint32_t e, float s, std::vector<float>& buffer) const {
    if (method_ == CreaseMethod::uniform || s >= kInfiniteSharpness) return decrement_sharpness(s) > 0.0f;
    for (uint32_t v : t_.edge_vertices(e))
      if (child_edge_sharpness(method_, s, ring_sharpness(v, buffer)) <= 0.0f) return false;
    return true;
  }

  EdgeMask edge_mask(uint32_t e, std::vector<float>& buffer) const {
    if constexpr (Rules::kLinear) return {};
    const auto k = t_.edge_corners(e);
    const uint32_t faces = k[1] == TopologyTables::kNone ? 1 : 2;
    const float s = sharp_.edge(e);
    if (s > 0.0f && child_is_crease(e, s, buffer)) return {};
    const EdgeMask smooth = rules_.smooth_edge(faces, t_.face_size(t_.corner_face(k[0])),
                                               faces == 2 ? t_.face_size(t_.corner_face(k[1])) : 0);
    if (s <= 0.0f) return smooth;
    // Semi-sharp edge decaying to smooth: blend the crease (midpoint) and smooth rules by the sharpness.
    return {.end = s * 0.5 + (1.0 - s) * smooth.end, .face = (1.0 - s) * smooth.face};
  }

  // Asks the caches for the points of edge e's and vertex v's masks (one step after the topology that finds them).
  template <class T>
  void prefetch_edge_points(uint32_t e, std::span<const T> parent, std::span<const T> child) const {
    const auto [k0, k1] = t_.edge_corners(e);
    prefetch_line(&parent[t_.corner_vertex(k0)]);
    prefetch_line(&parent[t_.corner_vertex(t_.next_corner(k0))]);
    for (uint32_t k : {k0, k1}) {
      if (k == TopologyTables::kNone) continue;
      if constexpr (Rules::kFacePoints)
        prefetch_line(&child[t_.vertex_count() + t_.corner_face(k)]);
      else
        prefetch_line(&parent[t_.corner_vertex(t_.prev_corner(k))]);
    }
  }
  template <class T>
  void prefetch_vertex_points(uint32_t v, std::span<const T> parent, std::span<const T> child) const {
    for (uint32_t u : t_.ring_neighbors(v)) prefetch_line(&parent[u]);
    if constexpr (Rules::kFacePoints)
      for (uint32_t k : t_.ring_corners(v)) prefetch_line(&child[t_.vertex_count() + t_.corner_face(k)]);
  }

  // The smooth mask of an interior edge between the faces of corners k0 and k1 (the same for every edge unless
  // Catmull-Clark weighs triangles differently).
  EdgeMask interior_smooth_edge(uint32_t k0, uint32_t k1) const {
    if constexpr (std::is_same_v<Rules, CatmarkRules>) {
      if (rules_.triangles != TriangleSubdivision::catmark)
        return rules_.smooth_edge(2, t_.face_size(t_.corner_face(k0)), t_.face_size(t_.corner_face(k1)));
    }
    return smooth_edge_;
  }

  template <class T>
  T edge_point_value(uint32_t e, std::span<const T> parent, std::span<const T> child,
                     std::vector<float>& buffer) const {
    const auto [k0, k1] = t_.edge_corners(e);
    const bool smooth = !Rules::kLinear && k1 != TopologyTables::kNone && !sharp_.tagged_edge(e);
    const EdgeMask m = smooth ? interior_smooth_edge(k0, k1) : edge_mask(e, buffer);
    T value = (parent[t_.corner_vertex(k0)] + parent[t_.corner_vertex(t_.next_corner(k0))]) * m.end;
    if (m.face != 0.0) {
      for (uint32_t k : {k0, k1}) {
        if (k == TopologyTables::kNone) continue;
        if constexpr (Rules::kFacePoints)
          value += child[t_.vertex_count() + t_.corner_face(k)] * m.face;
        else
          value += parent[t_.corner_vertex(t_.prev_corner(k))] * m.face;
      }
    }
    return value;
  }

  VertexMask vertex_mask(uint32_t v, std::vector<float>& buffer) const {
    if constexpr (Rules::kLinear) return {};
    const uint32_t faces = t_.ring_face_count(v), edges = t_.ring_edge_count(v);
    if (!sharp_.may_be_sharp(v) && faces > 0) return smooth_vertex_[faces];
    if (edges == 0) return corner_vertex_mask();
    const std::span<float> parent(buffer.data(), edges), child(buffer.data() + edges, edges);
    const VertexRule parent_rule = sharp_.rule(v, parent);
    if (parent_rule == VertexRule::smooth || parent_rule == VertexRule::dart) return rules_.smooth_vertex(faces);
    uint32_t ends[2];
    VertexMask parent_mask = corner_vertex_mask();
    if (parent_rule == VertexRule::crease) {
      detail::crease_ends(parent, ends);
      parent_mask = crease_vertex_mask(ends[0], ends[1]);
    }
    // Semi-sharp features that decay at this level blend the parent's rule with the child's.
    const float parent_vertex = sharp_.vertex(v), child_vertex = decrement_sharpness(parent_vertex);
    int sharp_children = 0;
    for (uint32_t i = 0; i < edges; ++i) {
      child[i] = child_edge_sharpness(method_, parent[i], parent);
      sharp_children += child[i] > 0.0f;
    }
    const VertexRule child_rule = vertex_rule(child_vertex, sharp_children);
    if (child_rule == parent_rule) return parent_mask;
    VertexMask child_mask = corner_vertex_mask();
    if (child_rule == VertexRule::smooth || child_rule == VertexRule::dart) {
      child_mask = rules_.smooth_vertex(faces);
    } else if (child_rule == VertexRule::crease) {
      detail::crease_ends(child, ends);
      child_mask = crease_vertex_mask(ends[0], ends[1]);
    }
    return blend(parent_mask, child_mask, transition_weight(method_, parent_vertex, child_vertex, parent, child));
  }

  template <class T>
  T vertex_point_value(uint32_t v, std::span<const T> parent, std::span<const T> child,
                       std::vector<float>& buffer) const {
    const VertexMask m = vertex_mask(v, buffer);
    T value = parent[v] * m.vertex;
    if (m.ring != 0.0 || m.face != 0.0) {
      T ring(0.0), faces(0.0);
      const std::span<const uint32_t> corners = t_.ring_corners(v), neighbors = t_.ring_neighbors(v);
      for (size_t i = 0; i < corners.size(); ++i) {
        ring += parent[neighbors[i]];
        if constexpr (Rules::kFacePoints) faces += child[t_.vertex_count() + t_.corner_face(corners[i])];
      }
      if (t_.is_boundary_vertex(v)) ring += parent[t_.ring_neighbor(v, t_.ring_edge_count(v) - 1)];
      value += ring * m.ring + faces * m.face;
    }
    if (m.crease != 0.0)
      value +=
          (parent[t_.ring_neighbor(v, m.crease_ends[0])] + parent[t_.ring_neighbor(v, m.crease_ends[1])]) * m.crease;
    return value;
  }

  const TopologyTables& t_;
  const detail::LevelSharpness& sharp_;
  const Rules& rules_;
  CreaseMethod method_;
  bool quads_;
  EdgeMask smooth_edge_;                   // the smooth mask of an interior edge between quads (or triangles)
  std::vector<VertexMask> smooth_vertex_;  // the smooth mask of an interior vertex by valence
};

template <class Rules>
PolyMesh refine_with(const TopologyTables& topology, const detail::LevelSharpness& sharpness, const Rules& rules,
                     const PolyMesh& mesh, const SubdivisionOptions& options, bool quads) {
  const LevelRefiner<Rules> refiner(topology, sharpness, rules, options.crease_method, quads);
  PolyMesh child;
  // resize() zero-fills serially: the face arrays' fill runs beside the (parallel) position passes.
  parallel_for(0, 2, 1, [&](int64_t b, int64_t e) {
    for (int64_t job = b; job < e; ++job) {
      if (job == 1) {
        refiner.allocate_child_faces(child);
        continue;
      }
      resize_fresh(child.positions, refiner.child_vertex_count());
      refiner.template refine<Vec3>(mesh.positions, child.positions);
      if (!mesh.uvs.empty()) {
        resize_fresh(child.uvs, refiner.child_vertex_count());
        refiner.template refine<Vec2>(mesh.uvs, child.uvs);
      }
      if (!mesh.colors.empty()) {
        resize_fresh(child.colors, refiner.child_vertex_count());
        refiner.template refine<Vec3>(mesh.colors, child.colors);
      }
    }
  });
  refiner.child_faces(child);
  refiner.child_tags(child);
  if (!mesh.corner_uvs.empty()) refiner.template refine_face_varying<Vec2>(mesh.corner_uvs, child.corner_uvs);
  return child;
}

PolyMesh refine_once(const TopologyTables& topology, const PolyMesh& mesh, const SubdivisionOptions& options,
                     bool quads) {
  const detail::LevelSharpness sharpness(topology, mesh, options.boundary);
  switch (options.scheme) {
    case SubdivisionScheme::catmull_clark:
      return refine_with(topology, sharpness, CatmarkRules{options.triangles}, mesh, options, quads);
    case SubdivisionScheme::loop:
      return refine_with(topology, sharpness, LoopRules{options.loop_weights}, mesh, options, quads);
    case SubdivisionScheme::midpoint:
      return refine_with(topology, sharpness, MidpointRules{}, mesh, options, quads);
  }
  throw InvalidInput("subdivide: unknown scheme");
}

// Refuses, before refining, a request whose last level would not fit in the memory budget. Each level multiplies the
// faces by 4 (a quad scheme first splits every n-gon into n quads); a triangle mesh has about half as many vertices
// as faces, a quad mesh about as many. Per face the last level stores its corners (index, face-varying UVs), its
// offset and its share of the per-vertex arrays; the estimate is three times that, for the parent level and its
// topology tables alive beside the child and for the writer's buffers (Spot, 5 levels: Loop 1.3 GiB estimated,
// 1.0 GiB peak measured; Catmull-Clark 926 MiB estimated, 825 MiB measured).
void check_memory(const PolyMesh& mesh, const SubdivisionOptions& options, bool quads) {
  const uint64_t corners = quads ? 4 : 3;
  const uint64_t first = quads ? mesh.face_vertices.size() : mesh.face_count() * 4;
  uint64_t faces = first;
  for (int level = 1; level < options.levels; ++level) faces = saturating_product({faces, 4});
  const uint64_t per_corner = sizeof(uint32_t) + (mesh.corner_uvs.empty() ? 0 : sizeof(Vec2));
  const uint64_t per_vertex =
      sizeof(Vec3) + (mesh.uvs.empty() ? 0 : sizeof(Vec2)) + (mesh.colors.empty() ? 0 : sizeof(Vec3));
  const uint64_t per_face = corners * per_corner + sizeof(uint32_t) + (quads ? per_vertex : per_vertex / 2);
  MemoryBudget::check(
      saturating_product({faces, per_face, 3}),
      fmt::format("subdivide: {} levels of {} faces ({} faces)", options.levels, mesh.face_count(), faces));
}

}  // namespace

PolyMesh subdivide(const PolyMesh& mesh, const SubdivisionOptions& options) {
  if (options.levels < 0 || options.levels > kMaxLevels)
    throw InvalidInput(fmt::format("subdivide: levels must be in 0..{}, got {}", kMaxLevels, options.levels));
  if (options.scheme == SubdivisionScheme::loop && !mesh.is_triangle_mesh())
    throw InvalidInput("subdivide: Loop subdivision needs a triangle mesh (triangulate it first)");
  if ((!mesh.uvs.empty() && mesh.uvs.size() != mesh.vertex_count()) ||
      (!mesh.colors.empty() && mesh.colors.size() != mesh.vertex_count()))
    throw InvalidInput("subdivide: per-vertex uvs and colors must have one entry per vertex");
  if (!mesh.corner_uvs.empty() && mesh.corner_uvs.size() != mesh.face_vertices.size())
    throw InvalidInput("subdivide: face-varying uvs must have one entry per face corner");
  if (options.levels == 0) {
    PolyMesh copy = mesh;
    copy.normals.clear();
    copy.corner_normals.clear();
    return copy;
  }
  const bool quads = options.scheme == SubdivisionScheme::catmull_clark ||
                     (options.scheme == SubdivisionScheme::midpoint && !mesh.is_triangle_mesh());
  check_memory(mesh, options, quads);
  if (const int e = rescale_exponent(std::span<const Vec3>(mesh.positions))) {
    PolyMesh scaled = mesh;
    scale_by_power_of_two(scaled.positions, -e);
    PolyMesh out = subdivide(scaled, options);
    scale_by_power_of_two(out.positions, e);
    detail::require_finite(out.positions, "subdivide", "vertex");
    return out;
  }
  // Only the cage's tables are built from its faces; every later level's are derived from its parent's.
  auto topology = std::make_unique<TopologyTables>(mesh.face_offsets, mesh.face_vertices, mesh.vertex_count());
  PolyMesh current;  // the level `topology` describes from level 1 on
  for (int level = 0; level < options.levels; ++level) {
    PolyMesh child = refine_once(*topology, level == 0 ? mesh : current, options, quads);
    if (level + 1 < options.levels)
      topology = std::make_unique<TopologyTables>(
          *topology, quads ? TopologyTables::Split::quads : TopologyTables::Split::triangles, child.face_offsets,
          child.face_vertices);
    current = std::move(child);  // the vectors keep their storage, which the new tables view
    if (options.progress) options.progress->advance();
  }
  detail::require_finite(current.positions, "subdivide", "vertex");
  detail::require_finite(current.uvs, "subdivide", "texture coordinate");
  detail::require_finite(current.corner_uvs, "subdivide", "face-varying texture coordinate");
  detail::require_finite(current.colors, "subdivide", "color");
  return current;
}

PolyMesh catmull_clark_subdivide(const PolyMesh& mesh, int levels) {
  return subdivide(mesh, {.scheme = SubdivisionScheme::catmull_clark, .levels = levels});
}

PolyMesh loop_subdivide(const PolyMesh& mesh, int levels) {
  return subdivide(mesh, {.scheme = SubdivisionScheme::loop, .levels = levels});
}

PolyMesh midpoint_subdivide(const PolyMesh& mesh, int levels) {
  return subdivide(mesh, {.scheme = SubdivisionScheme::midpoint, .levels = levels});
}

PolyMesh geodesic_sphere(const PolyMesh& base, int levels) {
  if (!base.is_triangle_mesh()) throw InvalidInput("geodesic_sphere: the base must be a triangle mesh");
  auto project = [](PolyMesh& mesh) {
    for (Vec3& p : mesh.positions) {
      const double r = glm::length(p);
      if (!(r > 0.0)) throw InvalidInput("geodesic_sphere: a vertex lies at the origin");
      p /= r;
    }
  };
  PolyMesh sphere = subdivide(base, {.scheme = SubdivisionScheme::midpoint, .levels = 0});
  project(sphere);
  for (int level = 0; level < levels; ++level) {
    sphere = subdivide(sphere, {.scheme = SubdivisionScheme::midpoint, .levels = 1});
    project(sphere);
  }
  return sphere;
}

}  // namespace tessera
