#include "tessera/volume/marching_cubes.hpp"

#include <algorithm>
#include <vector>

#include "tessera/core/parallel.hpp"
#include "tessera/volume/mc_table.hpp"

namespace tessera {
namespace {

/// A case table flattened for the inner loop: up to 16 triangles of edge indices (kCenter + k = center vertex k).
struct FlatCase {
  uint8_t count = 0;
  uint8_t centers = 0;
  std::array<uint16_t, mc::kMaxCenters> center_edges{};
  std::array<uint8_t, 3 * 16> edges{};
};

FlatCase flatten(const mc::CaseTriangles& c) {
  FlatCase f;
  TESSERA_CHECK_LE(c.triangles.size(), size_t(16));
  f.count = uint8_t(c.triangles.size());
  f.centers = uint8_t(c.center_edges.size());
  std::copy(c.center_edges.begin(), c.center_edges.end(), f.center_edges.begin());
  for (size_t t = 0; t < c.triangles.size(); ++t)
    for (size_t i = 0; i < 3; ++i) f.edges[3 * t + i] = c.triangles[t][i];
  return f;
}

const std::vector<FlatCase>& classic_cases() {
  static const std::vector<FlatCase> table = [] {
    std::vector<FlatCase> t;
    for (const auto& c : mc::classic_table()) t.push_back(flatten(c));
    return t;
  }();
  return table;
}

/// Topological table: entry [case * 64 + join] for every face-join mask within the case's ambiguous faces.
const std::vector<FlatCase>& topological_cases() {
  static const std::vector<FlatCase> table = [] {
    std::vector<FlatCase> t(256 * 64);
    for (int c = 0; c < 256; ++c) {
      const int amb = mc::ambiguous_faces(c);
      for (int join = 0; join < 64; ++join)
        if ((join & ~amb) == 0) t[size_t(c * 64 + join)] = flatten(mc::triangulate_case(c, join, true));
    }
    return t;
  }();
  return table;
}

constexpr uint32_t kCenterFlag = 0x80000000u;

class Extractor {
 public:
  Extractor(const Volume<float>& v, const MarchingCubesOptions& o)
      : v_(v), o_(o), d_(v.dims()), data_(v.voxels().data()), plane_(size_t(d_.x) * size_t(d_.y)) {}

  PolyMesh run() {
    PolyMesh mesh;
    if (d_.x < 2 || d_.y < 2 || d_.z < 2) return mesh;
    const int layers = d_.z - 1, per = std::max(1, o_.slab_layers);
    const int slabs = (layers + per - 1) / per;
    slab_first_.resize(size_t(slabs) + 1);
    for (int s = 0; s <= slabs; ++s) slab_first_[size_t(s)] = std::min(s * per, layers);
    // Pass 1: vertices per slab (the cut edges it owns), then their global numbering.
    std::vector<uint64_t> base(size_t(slabs) + 1, 0);
    parallel_for(0, slabs, 1, [&](int64_t b, int64_t e) {
      for (int64_t s = b; s < e; ++s) base[size_t(s) + 1] = count_slab(int(s), slabs);
    });
    for (int s = 0; s < slabs; ++s) base[size_t(s) + 1] += base[size_t(s)];
    if (base.back() >= kCenterFlag) throw InvalidInput("marching cubes: the mesh would exceed 2^31 vertices");
    base_ = base;
    mesh.positions.resize(size_t(base.back()));
    if (o_.normals) mesh.normals.resize(size_t(base.back()));
    positions_ = mesh.positions.data();
    normals_ = o_.normals ? mesh.normals.data() : nullptr;
    // Pass 2: vertices and triangles per slab.
    std::vector<std::vector<uint32_t>> triangles{size_t(slabs)};
    std::vector<std::vector<std::pair<Vec3, Vec3>>> centers{size_t(slabs)};
    parallel_for(0, slabs, 1, [&](int64_t b, int64_t e) {
      for (int64_t s = b; s < e; ++s) extract_slab(int(s), slabs, triangles[size_t(s)], centers[size_t(s)]);
    });
    // Concatenate in slab order; center vertices follow the edge vertices.
    size_t total = 0;
    for (const auto& t : triangles) total += t.size();
    mesh.face_vertices.reserve(total);
    uint32_t center_base = uint32_t(base.back());
    for (int s = 0; s < slabs; ++s) {
      for (uint32_t id : triangles[size_t(s)])
        mesh.face_vertices.push_back(id & kCenterFlag ? center_base + (id & ~kCenterFlag) : id);
      for (const auto& [p, n] : centers[size_t(s)]) {
        mesh.positions.push_back(p);
        if (o_.normals) mesh.normals.push_back(n);
      }
      center_base += uint32_t(centers[size_t(s)].size());
      std::vector<uint32_t>().swap(triangles[size_t(s)]);
    }
    mesh.face_offsets.resize(mesh.face_vertices.size() / 3 + 1);
    for (size_t f = 0; f < mesh.face_offsets.size(); ++f) mesh.face_offsets[f] = uint32_t(3 * f);
    return mesh;
  }

 private:
  size_t at(int x, int y, int z) const { return size_t(x) + size_t(d_.x) * size_t(y) + plane_ * size_t(z); }
  bool in(size_t i) const { return data_[i] >= o_.iso; }
  bool owns_top(int s, int slabs) const { return s == slabs - 1; }

  /// Cut x- and y-edges of plane z, in the numbering order (row by row, x-edge before y-edge).
  template <class F>
  void scan_plane(int z, F&& visit) const {
    for (int y = 0; y < d_.y; ++y) {
      const size_t row = at(0, y, z);
      for (int x = 0; x < d_.x; ++x) {
        const bool a = in(row + size_t(x));
        if (x + 1 < d_.x && a != in(row + size_t(x) + 1)) visit(x, y, 0);
        if (y + 1 < d_.y && a != in(row + size_t(x) + size_t(d_.x))) visit(x, y, 1);
      }
    }
  }

  template <class F>
  void scan_z_edges(int z, F&& visit) const {
    for (int y = 0; y < d_.y; ++y) {
      const size_t row = at(0, y, z);
      for (int x = 0; x < d_.x; ++x)
        if (in(row + size_t(x)) != in(row + size_t(x) + plane_)) visit(x, y, 2);
    }
  }

  uint64_t count_slab(int s, int slabs) const {
    uint64_t n = 0;
    const auto count = [&](int, int, int) { ++n; };
    const int z0 = slab_first_[size_t(s)], z1 = slab_first_[size_t(s) + 1];
    for (int z = z0; z < z1; ++z) {
      scan_plane(z, count);
      scan_z_edges(z, count);
    }
    if (owns_top(s, slabs)) scan_plane(z1, count);
    return n;
  }

  /// The vertex on the edge from voxel (x, y, z) along `axis`: position and outward normal.
  std::pair<Vec3, Vec3> edge_vertex(int x, int y, int z, int axis) const {
    glm::ivec3 p(x, y, z), q(x, y, z);
    q[axis] += 1;
    const double a = data_[at(p.x, p.y, p.z)], b = data_[at(q.x, q.y, q.z)];
    const double t = std::clamp((double(o_.iso) - a) / (b - a), kEdgeNudge, 1.0 - kEdgeNudge);
    Vec3 grid(p);
    grid[axis] += t;
    Vec3 normal(0.0);
    if (o_.normals) {
      const Vec3 ga(v_.gradient(p.x, p.y, p.z)), gb(v_.gradient(q.x, q.y, q.z));
      const Vec3 g = ga + t * (gb - ga);
      const double len = glm::length(g);
      if (len > 0) normal = -g / len;
    }
    return {v_.to_world(grid), normal};
  }

  void emit(uint32_t id, int x, int y, int z, int axis) const {
    const auto [p, n] = edge_vertex(x, y, z, axis);
    positions_[id] = p;
    if (normals_) normals_[id] = n;
  }

  /// Numbers the cut edges of plane z into ids (x-edge at 2i, y-edge at 2i+1), writing their vertices when `write`.
  void number_plane(int z, std::vector<uint32_t>& ids, uint32_t& next, bool write) const {
    scan_plane(z, [&](int x, int y, int axis) {
      ids[2 * (size_t(y) * size_t(d_.x) + size_t(x)) + size_t(axis)] = next;
      if (write) emit(next, x, y, z, axis);
      ++next;
    });
  }

  int decide_faces(int cube_case, const std::array<float, 8>& value) const {
    int join = 0;
    const int amb = mc::ambiguous_faces(cube_case);
    for (int f = 0; f < 6; ++f) {
      if (!((amb >> f) & 1)) continue;
      const auto& q = mc::faces()[size_t(f)];
      const double a = value[size_t(q[0])], b = value[size_t(q[1])], c = value[size_t(q[2])], d = value[size_t(q[3])];
      // The bilinear interpolant's saddle value; the inside corners connect across the face when it is inside.
      const double saddle = (a * c - b * d) / (a + c - b - d);
      if (saddle >= double(o_.iso)) join |= 1 << f;
    }
    return join;
  }

  void extract_slab(int s, int slabs, std::vector<uint32_t>& tris, std::vector<std::pair<Vec3, Vec3>>& centers) const {
    const int z0 = slab_first_[size_t(s)], z1 = slab_first_[size_t(s) + 1];
    const size_t nx = size_t(d_.x);
    std::vector<uint32_t> lo(2 * plane_), hi(2 * plane_), zid(plane_);
    uint32_t next = uint32_t(base_[size_t(s)]);
    number_plane(z0, lo, next, true);
    const auto& classic = classic_cases();
    const auto& topo = topological_cases();
    std::array<uint32_t, 12 + mc::kMaxCenters> id{};
    std::array<float, 8> value{};
    for (int z = z0; z < z1; ++z) {
      scan_z_edges(z, [&](int x, int y, int axis) {
        zid[size_t(y) * nx + size_t(x)] = next;
        emit(next++, x, y, z, axis);
      });
      if (z + 1 < z1 || owns_top(s, slabs)) {
        number_plane(z + 1, hi, next, true);
      } else {
        uint32_t neighbour = uint32_t(base_[size_t(s) + 1]);  // the next slab numbers its bottom plane first
        number_plane(z + 1, hi, neighbour, false);
      }
      for (int y = 0; y + 1 < d_.y; ++y) {
        const float* r0 = data_ + at(0, y, z);
        const float* r1 = r0 + nx;
        const float* r2 = r0 + plane_;
        const float* r3 = r2 + nx;
        for (int x = 0; x + 1 < d_.x; ++x) {
          value = {r0[x], r0[x + 1], r1[x + 1], r1[x], r2[x], r2[x + 1], r3[x + 1], r3[x]};
          int cube_case = 0;
          for (int c = 0; c < 8; ++c) cube_case |= int(value[size_t(c)] >= o_.iso) << c;
          if (cube_case == 0 || cube_case == 255) continue;
          const FlatCase& fc =
              o_.topological ? topo[size_t(cube_case * 64 + decide_faces(cube_case, value))] : classic[size_t(cube_case)];
          const size_t i = size_t(y) * nx + size_t(x);
          id[0] = lo[2 * i];
          id[1] = lo[2 * (i + 1) + 1];
          id[2] = lo[2 * (i + nx)];
          id[3] = lo[2 * i + 1];
          id[4] = hi[2 * i];
          id[5] = hi[2 * (i + 1) + 1];
          id[6] = hi[2 * (i + nx)];
          id[7] = hi[2 * i + 1];
          id[8] = zid[i];
          id[9] = zid[i + 1];
          id[10] = zid[i + nx + 1];
          id[11] = zid[i + nx];
          for (size_t k = 0; k < fc.centers; ++k) {
            id[size_t(mc::kCenter) + k] = kCenterFlag | uint32_t(centers.size());
            centers.push_back(center_vertex(x, y, z, fc.center_edges[k]));
          }
          for (int t = 0; t < 3 * fc.count; ++t) tris.push_back(id[fc.edges[size_t(t)]]);
        }
      }
      std::swap(lo, hi);
    }
  }

  /// The centroid of the vertices on `edge_mask`'s edges of cell (x, y, z), with their averaged normal.
  std::pair<Vec3, Vec3> center_vertex(int x, int y, int z, uint16_t edge_mask) const {
    Vec3 p(0.0), n(0.0);
    int count = 0;
    for (int e = 0; e < 12; ++e) {
      if (!((edge_mask >> e) & 1)) continue;
      const auto [c0, c1] = mc::edges()[size_t(e)];
      const glm::ivec3 a = mc::corners()[size_t(c0)], b = mc::corners()[size_t(c1)];
      const glm::ivec3 lo = glm::min(a, b);
      const int axis = a.x != b.x ? 0 : a.y != b.y ? 1 : 2;
      const auto [vp, vn] = edge_vertex(x + lo.x, y + lo.y, z + lo.z, axis);
      p += vp;
      n += vn;
      ++count;
    }
    const double len = glm::length(n);
    return {p / double(count), len > 0 ? n / len : n};
  }

  const Volume<float>& v_;
  MarchingCubesOptions o_;
  glm::ivec3 d_;
  const float* data_;
  size_t plane_;
  std::vector<int> slab_first_;
  std::vector<uint64_t> base_;
  Vec3* positions_ = nullptr;
  Vec3* normals_ = nullptr;
};

}  // namespace

PolyMesh marching_cubes(const Volume<float>& volume, const MarchingCubesOptions& options) {
  return Extractor(volume, options).run();
}

}  // namespace tessera
