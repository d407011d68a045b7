#pragma once
// OpenSubdiv 3.5 (Far::TopologyRefiner + PrimvarRefiner) as the reference for Tessera's subdivision, and a
// point-set comparison (nearest neighbours through a hash grid) for results whose vertex order may differ.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <cmath>
#include <memory>
#include <unordered_map>
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/subdiv/subdivide.hpp"

namespace tessera::test {

namespace osd = OpenSubdiv::Far;
namespace sdc = OpenSubdiv::Sdc;

/// A vertex in OpenSubdiv's primvar interface.
struct OsdPoint {
  Vec3 p{0.0};
  void Clear(void* = nullptr) { p = Vec3(0.0); }
  void AddWithWeight(const OsdPoint& src, double w) { p += w * src.p; }
};

/// OpenSubdiv's options for Tessera's.
inline sdc::Options osd_options(const SubdivisionOptions& o) {
  sdc::Options options;
  options.SetVtxBoundaryInterpolation(o.boundary == BoundaryInterpolation::edge_only
                                          ? sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                          : sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  options.SetCreasingMethod(o.crease_method == CreaseMethod::uniform ? sdc::Options::CREASE_UNIFORM
                                                                     : sdc::Options::CREASE_CHAIKIN);
  options.SetTriangleSubdivision(o.triangles == TriangleSubdivision::catmark ? sdc::Options::TRI_SUB_CATMARK
                                                                             : sdc::Options::TRI_SUB_SMOOTH);
  return options;
}

/// A mesh refined uniformly by OpenSubdiv: the positions and face count of every level 0..levels.
struct OsdRefinement {
  std::unique_ptr<osd::TopologyRefiner> refiner;
  std::vector<std::vector<OsdPoint>> levels;
  std::vector<Vec3> positions(int level) const {
    std::vector<Vec3> out;
    for (const OsdPoint& q : levels[level]) out.push_back(q.p);
    return out;
  }
  size_t face_count(int level) const { return size_t(refiner->GetLevel(level).GetNumFaces()); }
};

/// Refines `mesh` with OpenSubdiv (Catmark or Loop per o.scheme) to o.levels, with full topology at the last level.
inline OsdRefinement osd_refine(const PolyMesh& mesh, const SubdivisionOptions& o) {
  std::vector<int> sizes, indices(mesh.face_vertices.begin(), mesh.face_vertices.end()), crease_pairs, corner_ids;
  std::vector<float> crease_weights, corner_weights;
  for (size_t f = 0; f < mesh.face_count(); ++f) sizes.push_back(int(mesh.face_size(f)));
  for (const EdgeCrease& c : mesh.creases) {
    crease_pairs.push_back(int(c.v0));
    crease_pairs.push_back(int(c.v1));
    crease_weights.push_back(c.sharpness);
  }
  for (const VertexCorner& c : mesh.corners) {
    corner_ids.push_back(int(c.v));
    corner_weights.push_back(c.sharpness);
  }
  osd::TopologyDescriptor desc;
  desc.numVertices = int(mesh.vertex_count());
  desc.numFaces = int(mesh.face_count());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numCreases = int(crease_weights.size());
  desc.creaseVertexIndexPairs = crease_pairs.data();
  desc.creaseWeights = crease_weights.data();
  desc.numCorners = int(corner_weights.size());
  desc.cornerVertexIndices = corner_ids.data();
  desc.cornerWeights = corner_weights.data();
  const sdc::SchemeType type = o.scheme == SubdivisionScheme::loop ? sdc::SCHEME_LOOP : sdc::SCHEME_CATMARK;
  OsdRefinement r;
  r.refiner.reset(osd::TopologyRefinerFactory<osd::TopologyDescriptor>::Create(
      desc, osd::TopologyRefinerFactory<osd::TopologyDescriptor>::Options(type, osd_options(o))));
  osd::TopologyRefiner::UniformOptions uniform(o.levels);
  uniform.fullTopologyInLastLevel = true;
  r.refiner->RefineUniform(uniform);
  r.levels.resize(size_t(o.levels) + 1);
  for (const Vec3& p : mesh.positions) r.levels[0].push_back({p});
  osd::PrimvarRefinerReal<double> primvar(*r.refiner);
  for (int level = 1; level <= o.levels; ++level) {
    r.levels[level].resize(size_t(r.refiner->GetLevel(level).GetNumVertices()));
    const OsdPoint* src = r.levels[level - 1].data();
    OsdPoint* dst = r.levels[level].data();
    primvar.Interpolate(level, src, dst);
  }
  return r;
}

/// A face-varying uv in OpenSubdiv's primvar interface.
struct OsdUv {
  Vec2 uv{0.0};
  void Clear(void* = nullptr) { uv = Vec2(0.0); }
  void AddWithWeight(const OsdUv& src, double w) { uv += w * src.uv; }
};

/// A face corner of a refined mesh: its vertex's position and its face-varying uv.
struct CornerSample {
  Vec3 position;
  Vec2 uv;
};

/// Refines `mesh` (with corner_uvs, one face-varying channel whose values are the corners themselves) with
/// OpenSubdiv, the uvs by FVAR_LINEAR_ALL, and returns the corners of every face of the last level.
inline std::vector<CornerSample> osd_refine_face_varying(const PolyMesh& mesh, const SubdivisionOptions& o) {
  std::vector<int> sizes, indices(mesh.face_vertices.begin(), mesh.face_vertices.end()),
      fvar(mesh.face_vertices.size());
  for (size_t f = 0; f < mesh.face_count(); ++f) sizes.push_back(int(mesh.face_size(f)));
  for (size_t c = 0; c < fvar.size(); ++c) fvar[c] = int(c);
  osd::TopologyDescriptor::FVarChannel channel;
  channel.numValues = int(fvar.size());
  channel.valueIndices = fvar.data();
  osd::TopologyDescriptor desc;
  desc.numVertices = int(mesh.vertex_count());
  desc.numFaces = int(mesh.face_count());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numFVarChannels = 1;
  desc.fvarChannels = &channel;
  sdc::Options options = osd_options(o);
  options.SetFVarLinearInterpolation(sdc::Options::FVAR_LINEAR_ALL);
  const sdc::SchemeType type = o.scheme == SubdivisionScheme::loop ? sdc::SCHEME_LOOP : sdc::SCHEME_CATMARK;
  std::unique_ptr<osd::TopologyRefiner> refiner(osd::TopologyRefinerFactory<osd::TopologyDescriptor>::Create(
      desc, osd::TopologyRefinerFactory<osd::TopologyDescriptor>::Options(type, options)));
  osd::TopologyRefiner::UniformOptions uniform(o.levels);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);
  std::vector<OsdPoint> points;
  std::vector<OsdUv> uvs;
  for (const Vec3& p : mesh.positions) points.push_back({p});
  for (const Vec2& t : mesh.corner_uvs) uvs.push_back({t});
  osd::PrimvarRefinerReal<double> primvar(*refiner);
  for (int level = 1; level <= o.levels; ++level) {
    std::vector<OsdPoint> next_points(size_t(refiner->GetLevel(level).GetNumVertices()));
    std::vector<OsdUv> next_uvs(size_t(refiner->GetLevel(level).GetNumFVarValues(0)));
    const OsdPoint* src_points = points.data();
    OsdPoint* dst_points = next_points.data();
    const OsdUv* src_uvs = uvs.data();
    OsdUv* dst_uvs = next_uvs.data();
    primvar.Interpolate(level, src_points, dst_points);
    primvar.InterpolateFaceVarying(level, src_uvs, dst_uvs, 0);
    points.swap(next_points);
    uvs.swap(next_uvs);
  }
  const osd::TopologyLevel& last = refiner->GetLevel(o.levels);
  std::vector<CornerSample> corners;
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto verts = last.GetFaceVertices(f);
    const auto values = last.GetFaceFVarValues(f, 0);
    for (int i = 0; i < verts.size(); ++i) corners.push_back({points[size_t(verts[i])].p, uvs[size_t(values[i])].uv});
  }
  return corners;
}

/// The diagonal of the bounding box of `points`.
inline double bbox_diagonal(const std::vector<Vec3>& points) {
  Vec3 lo(1e300), hi(-1e300);
  for (const Vec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return glm::length(hi - lo);
}

/// For every point of `from`, the index of its nearest point of `to` within one grid cell of size `cell`
/// (a hash grid), or -1 when there is none.
inline std::vector<int64_t> nearest_points(const std::vector<Vec3>& from, const std::vector<Vec3>& to, double cell) {
  auto key = [cell](const Vec3& p, int dx, int dy, int dz) {
    const auto x = int64_t(std::floor(p.x / cell)) + dx, y = int64_t(std::floor(p.y / cell)) + dy,
               z = int64_t(std::floor(p.z / cell)) + dz;
    return (x * 73856093) ^ (y * 19349663) ^ (z * 83492791);
  };
  std::unordered_map<int64_t, std::vector<uint32_t>> grid;
  for (uint32_t i = 0; i < to.size(); ++i) grid[key(to[i], 0, 0, 0)].push_back(i);
  std::vector<int64_t> out(from.size(), -1);
  for (size_t i = 0; i < from.size(); ++i) {
    double best = cell;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(key(from[i], dx, dy, dz));
          if (it == grid.end()) continue;
          for (uint32_t j : it->second)
            if (const double d = glm::distance(from[i], to[j]); d < best) {
              best = d;
              out[i] = j;
            }
        }
  }
  return out;
}

/// The largest distance from a point of `a` to its nearest point of `b` and back (symmetric); `cell` when the sets
/// differ in size or a point has no neighbour within `cell`.
inline double point_set_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double cell) {
  if (a.size() != b.size()) return cell;
  double worst = 0.0;
  for (const auto& [from, to] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
    const std::vector<int64_t> nearest = nearest_points(*from, *to, cell);
    for (size_t i = 0; i < from->size(); ++i)
      worst = std::max(worst, nearest[i] < 0 ? cell : glm::distance((*from)[i], (*to)[size_t(nearest[i])]));
  }
  return worst;
}

}  // namespace tessera::test
