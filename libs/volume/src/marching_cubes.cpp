#include "tessera/volume/marching_cubes.hpp"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <bit>
#include <memory>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "tessera/core/memory.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/math/power_of_two.hpp"
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

/// Bit masks of the cases' ambiguous faces (the topological mode reads corner values only where one is set).
const std::array<uint8_t, 256>& ambiguous_table() {
  static const std::array<uint8_t, 256> table = [] {
    std::array<uint8_t, 256> t{};
    for (int c = 0; c < 256; ++c) t[size_t(c)] = uint8_t(mc::ambiguous_faces(c));
    return t;
  }();
  return table;
}

using Word = uint64_t;

/// Bit x of a row of inside flags (x may be one past the row's last word: it reads 0).
inline int bit(const Word* row, int x) { return int((row[x >> 6] >> (x & 63)) & 1u); }

// The extraction runs in two passes over slabs of z layers, as Flying Edges does: the first counts each slab's cut
// edges (its vertices), triangles and center vertices; prefix sums place every slab's output; the second writes
// vertices and triangles straight into the final arrays. Both passes walk packed inside-flags (one bit per voxel,
// 64 voxels a word), so that cut edges are XORs and popcounts, and runs of 64 cells that are all inside or all
// outside are skipped a word at a time.
//
// V is the output's vector type: Vec3 (double, for PolyMesh) or Vec3f (IsoSurface, half the bytes to write); the
// vertices are computed in double either way.
template <class V>
class Extractor {
 public:
  Extractor(const VoxelGrid& v, const MarchingCubesOptions& o)
      : o_(o),
        d_(v.dims),
        data_(v.voxels),
        spacing_(v.spacing),
        origin_(v.origin),
        z_offset_(v.z_offset),
        plane_(size_t(d_.x) * size_t(d_.y)),
        per_difference_(std::min({v.spacing.x, v.spacing.y, v.spacing.z}) / v.spacing),
        words_(size_t(d_.x + 63) / 64) {}

  /// Fills positions, normals (when asked for) and 3 indices per triangle; `fresh(array, n)` sizes an array for
  /// n elements that are then all written. `triangle_extra` is what the caller adds per triangle (a PolyMesh's face
  /// offset), for the memory estimate. Returns the triangle count.
  template <class Positions, class Indices, class Fresh>
  uint64_t run(Positions& positions, Positions& normals, Indices& triangles, const Fresh& fresh,
               uint64_t triangle_extra) {
    if (d_.x < 2 || d_.y < 2 || d_.z < 2) return 0;
    // The valid bits of a row's last word for cells and x-edges (x < nx - 1).
    edge_tail_ = (Word(1) << (d_.x - 1 - 64 * int(words_ - 1))) - 1;
    const int layer0 = std::clamp(o_.first_layer, 0, d_.z - 1);
    const int layer1 = std::clamp(o_.end_layer < 0 ? d_.z - 1 : o_.end_layer, layer0, d_.z - 1);
    const int layers = layer1 - layer0, per = std::max(1, o_.slab_layers);
    if (layers == 0) return 0;
    const int slabs = (layers + per - 1) / per;
    slab_first_.resize(size_t(slabs) + 1);
    for (int s = 0; s <= slabs; ++s) slab_first_[size_t(s)] = layer0 + std::min(s * per, layers);
    slabs_ = slabs;

    // Pass 1: counts per slab, then every slab's first vertex, triangle and center vertex.
    std::vector<Counts> first(size_t(slabs) + 1);
    parallel_for(0, slabs, 1, [&](int64_t b, int64_t e) {
      for (int64_t s = b; s < e; ++s) first[size_t(s) + 1] = process_slab<false>(int(s));
    });
    for (int s = 0; s < slabs; ++s) {
      first[size_t(s) + 1].vertices += first[size_t(s)].vertices;
      first[size_t(s) + 1].triangles += first[size_t(s)].triangles;
      first[size_t(s) + 1].centers += first[size_t(s)].centers;
    }
    const Counts total = first.back();
    if (total.vertices + total.centers >= uint64_t(UINT32_MAX) || 3 * total.triangles >= uint64_t(UINT32_MAX))
      throw InvalidInput("marching cubes: the mesh would exceed 2^32 vertices or triangle corners");
    first_ = first;
    check_output_memory(total, triangle_extra);
    const size_t vertices = size_t(total.vertices + total.centers);
    fresh(positions, vertices);
    if (o_.normals) fresh(normals, vertices);
    fresh(triangles, 3 * size_t(total.triangles));
    positions_ = positions.data();
    normals_ = o_.normals ? normals.data() : nullptr;
    triangles_ = triangles.data();

    // Pass 2: vertices and triangles, each slab into its own ranges.
    parallel_for(0, slabs, 1, [&](int64_t b, int64_t e) {
      for (int64_t s = b; s < e; ++s) process_slab<true>(int(s));
    });
    return total.triangles;
  }

 private:
  struct Counts {
    uint64_t vertices = 0, triangles = 0, centers = 0;
  };

  size_t at(int x, int y, int z) const { return size_t(x) + size_t(d_.x) * size_t(y) + plane_ * size_t(z); }

  /// Refuses, once pass 1 has counted them and before anything is allocated, an output over the memory budget: the
  /// exact bytes of the arrays pass 2 fills (a position, and a normal when asked for, per vertex; 3 indices and
  /// `triangle_extra` per triangle), three times: the mesh, and what a writer builds from it (PLY and OFF write a
  /// seam-split copy). Measured on gyroid:256 (1.26M triangles, 48 MiB of arrays), `volume isosurface` peaked at 1.5
  /// (OBJ), 2.2 (PLY, OFF) and 4.5 (STL: a triangulated copy, face normals and 50 bytes a triangle) times the arrays
  /// beside the volume. The count is exact, so no legitimate request is refused by a worst case (5 triangles a cell).
  void check_output_memory(const Counts& total, uint64_t triangle_extra) const {
    const uint64_t vertices = total.vertices + total.centers;
    const uint64_t per_vertex = sizeof(V) * (o_.normals ? 2 : 1), per_triangle = 3 * sizeof(uint32_t) + triangle_extra;
    const uint64_t bytes =
        saturating_product({vertices, per_vertex}) + saturating_product({total.triangles, per_triangle});
    MemoryBudget::check(
        saturating_product({bytes, 3}),
        fmt::format("marching cubes: an iso-surface of {} triangles and {} vertices", total.triangles, vertices));
  }

  /// Packs plane z's inside flags (value >= iso) into rows of words; bits past the row's end are 0.
  void classify(int z, Word* bits) const {
    const float iso = o_.iso;
    for (int y = 0; y < d_.y; ++y) {
      const float* row = data_ + at(0, y, z);
      Word* out = bits + size_t(y) * words_;
      for (size_t w = 0; w < words_; ++w) {
        const int x0 = int(64 * w), n = std::min(64, d_.x - x0);
        Word word = 0;
        int i = 0;
#if defined(__SSE2__)
        // Four compares a step (an ordered compare: NaN is outside, as with >=).
        const __m128 threshold = _mm_set1_ps(iso);
        for (; i + 4 <= n; i += 4)
          word |= Word(unsigned(_mm_movemask_ps(_mm_cmpge_ps(_mm_loadu_ps(row + x0 + i), threshold)))) << i;
#endif
        for (; i < n; ++i) word |= Word(row[x0 + i] >= iso) << i;
        out[w] = word;
      }
    }
  }

  /// Word w of the cut x-edges of a row (x < nx - 1).
  Word x_cuts(const Word* row, size_t w) const {
    const Word next = w + 1 < words_ ? row[w + 1] : 0;
    const Word cuts = row[w] ^ ((row[w] >> 1) | (next << 63));
    return w + 1 < words_ ? cuts : cuts & edge_tail_;
  }

  /// Visits the cut x- and y-edges of a plane in the numbering order (row by row, x-edge before y-edge).
  template <class F>
  void scan_plane(const Word* bits, F&& visit) const {
    for (int y = 0; y < d_.y; ++y) {
      const Word* row = bits + size_t(y) * words_;
      const Word* up = y + 1 < d_.y ? row + words_ : nullptr;
      for (size_t w = 0; w < words_; ++w) {
        const Word xs = x_cuts(row, w), ys = up ? row[w] ^ up[w] : 0;
        for (Word any = xs | ys; any; any &= any - 1) {
          const int i = std::countr_zero(any), x = int(64 * w) + i;
          if ((xs >> i) & 1) visit(x, y, 0);
          if ((ys >> i) & 1) visit(x, y, 1);
        }
      }
    }
  }

  uint64_t count_plane(const Word* bits) const {
    uint64_t n = 0;
    for (int y = 0; y < d_.y; ++y) {
      const Word* row = bits + size_t(y) * words_;
      for (size_t w = 0; w < words_; ++w) {
        n += uint64_t(std::popcount(x_cuts(row, w)));
        if (y + 1 < d_.y) n += uint64_t(std::popcount(row[w] ^ row[w + words_]));
      }
    }
    return n;
  }

  /// Volume::gradient times the smallest spacing, in double: only its direction matters, and scaled so it stays
  /// finite for any finite floats and spacings (in float, values of both signs near 3e38 made it inf, and the
  /// normals NaN). Without per-axis clamps inside the grid (two per vertex: they showed in the profile).
  Vec3 gradient(int x, int y, int z) const {
    if (x < 1 || y < 1 || z < 1 || x > d_.x - 2 || y > d_.y - 2 || z > d_.z - 2) {
      Vec3 g(0.0);
      for (int axis = 0; axis < 3; ++axis) {
        glm::ivec3 lo(x, y, z), hi(x, y, z);
        lo[axis] = std::max(lo[axis] - 1, 0);
        hi[axis] = std::min(hi[axis] + 1, d_[axis] - 1);
        if (hi[axis] > lo[axis])
          g[axis] = (double(data_[at(hi.x, hi.y, hi.z)]) - data_[at(lo.x, lo.y, lo.z)]) * per_difference_[axis] /
                    (hi[axis] - lo[axis]);
      }
      return g;
    }
    const float* c = data_ + at(x, y, z);
    const ptrdiff_t dy = ptrdiff_t(d_.x), dz = ptrdiff_t(plane_);
    return 0.5 * Vec3((double(c[1]) - c[-1]) * per_difference_.x, (double(c[dy]) - c[-dy]) * per_difference_.y,
                      (double(c[dz]) - c[-dz]) * per_difference_.z);
  }

  /// The vertex on the edge from voxel (x, y, z) along `axis`: position and outward normal.
  std::pair<Vec3, Vec3> edge_vertex(int x, int y, int z, int axis) const {
    glm::ivec3 p(x, y, z), q(x, y, z);
    q[axis] += 1;
    const double a = data_[at(p.x, p.y, p.z)], b = data_[at(q.x, q.y, q.z)];
    const double t = std::clamp((double(o_.iso) - a) / (b - a), kEdgeNudge, 1.0 - kEdgeNudge);
    Vec3 grid(p.x, p.y, p.z + z_offset_);  // the whole volume's voxel coordinates (integers: exact)
    grid[axis] += t;
    Vec3 normal(0.0);
    if (o_.normals) {
      const Vec3 ga = gradient(p.x, p.y, p.z), gb = gradient(q.x, q.y, q.z);
      // Brought near 1 first (powers of two, exact) so that squaring neither overflows nor underflows.
      Vec3 g = ga + t * (gb - ga);
      g = ldexp(g, -rescale_exponent(largest_component(g)));
      const double len = glm::length(g);
      if (len > 0) normal = -g / len;
    }
    return {origin_ + spacing_ * grid, normal};  // Volume::to_world
  }

  void emit(uint32_t id, int x, int y, int z, int axis) const {
    const auto [p, n] = edge_vertex(x, y, z, axis);
    positions_[id] = V(p);
    if (normals_) normals_[id] = V(n);
  }

  /// Numbers the cut edges of a plane into ids (x-edge at 2i, y-edge at 2i+1), writing their vertices when `write`.
  void number_plane(const Word* bits, int z, uint32_t* ids, uint32_t& next, bool write) const {
    scan_plane(bits, [&](int x, int y, int axis) {
      ids[2 * (size_t(y) * size_t(d_.x) + size_t(x)) + size_t(axis)] = next;
      if (write) emit(next, x, y, z, axis);
      ++next;
    });
  }

  int decide_faces(int cube_case, const std::array<float, 8>& value) const {
    int join = 0;
    const int amb = ambiguous_table()[size_t(cube_case)];
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

  /// The case table entry of cell (x, y, z) with corner case `cube_case`.
  const FlatCase& cell_case(int x, int y, int z, int cube_case) const {
    if (!o_.topological) return classic_cases()[size_t(cube_case)];
    int join = 0;
    if (ambiguous_table()[size_t(cube_case)] != 0) {
      const float* r0 = data_ + at(x, y, z);
      const float* r1 = r0 + d_.x;
      const float* r2 = r0 + plane_;
      const float* r3 = r2 + d_.x;
      join = decide_faces(cube_case, {r0[0], r0[1], r1[1], r1[0], r2[0], r2[1], r3[1], r3[0]});
    }
    return topological_cases()[size_t(cube_case * 64 + join)];
  }

  /// One slab: counts its output (kWrite false) or writes it at the places pass 1 gave it (kWrite true). A slab owns
  /// the x/y edges of its planes but the last (which the next slab owns, except for the top slab) and the z edges and
  /// cells of its layers. A slab numbers its bottom plane first, so the slab below can compute the ids of the shared
  /// plane itself.
  template <bool kWrite>
  Counts process_slab(int s) const {
    const int z0 = slab_first_[size_t(s)], z1 = slab_first_[size_t(s) + 1];
    const bool top = s == slabs_ - 1;
    const size_t nx = size_t(d_.x), plane_words = size_t(d_.y) * words_;
    Scratch& scratch = scratch_.local();
    if (scratch.lo.empty()) {
      // One spare word each: bit() may read past a row; nothing writes it, so it stays 0.
      scratch.lo.assign(plane_words + 1, 0);
      scratch.hi.assign(plane_words + 1, 0);
    }
    std::vector<Word>& lo = scratch.lo;
    std::vector<Word>& hi = scratch.hi;
    std::unique_ptr<uint32_t[]>& lo_id = scratch.lo_id;
    std::unique_ptr<uint32_t[]>& hi_id = scratch.hi_id;
    std::unique_ptr<uint32_t[]>& zid = scratch.zid;
    Counts counts;
    uint32_t next = 0, center = 0;
    uint32_t* tris = nullptr;
    if constexpr (kWrite) {
      if (!zid) {  // only entries written in this slab are read, so stale ones do not matter
        lo_id.reset(new uint32_t[2 * plane_]);
        hi_id.reset(new uint32_t[2 * plane_]);
        zid.reset(new uint32_t[plane_]);
      }
      next = uint32_t(first_[size_t(s)].vertices);
      center = uint32_t(first_.back().vertices + first_[size_t(s)].centers);
      tris = triangles_ + 3 * first_[size_t(s)].triangles;
    }
    classify(z0, lo.data());
    if constexpr (kWrite)
      number_plane(lo.data(), z0, lo_id.get(), next, true);
    else
      counts.vertices += count_plane(lo.data());
    std::array<uint32_t, 12 + mc::kMaxCenters> id{};
    for (int z = z0; z < z1; ++z) {
      classify(z + 1, hi.data());
      for (int y = 0; y < d_.y; ++y) {
        const Word* a = lo.data() + size_t(y) * words_;
        const Word* c = hi.data() + size_t(y) * words_;
        for (size_t w = 0; w < words_; ++w) {
          const Word cuts = a[w] ^ c[w];
          if constexpr (kWrite) {
            for (Word m = cuts; m; m &= m - 1) {
              const int x = int(64 * w) + std::countr_zero(m);
              zid[size_t(y) * nx + size_t(x)] = next;
              emit(next++, x, y, z, 2);
            }
          } else {
            counts.vertices += uint64_t(std::popcount(cuts));
          }
        }
      }
      if (z + 1 < z1 || top) {
        if constexpr (kWrite)
          number_plane(hi.data(), z + 1, hi_id.get(), next, true);
        else
          counts.vertices += count_plane(hi.data());
      } else if constexpr (kWrite) {
        uint32_t neighbour = uint32_t(first_[size_t(s) + 1].vertices);  // the next slab numbers this plane first
        number_plane(hi.data(), z + 1, hi_id.get(), neighbour, false);
      }
      for (int y = 0; y + 1 < d_.y; ++y) {
        const Word* a = lo.data() + size_t(y) * words_;
        const Word* b = a + words_;
        const Word* c = hi.data() + size_t(y) * words_;
        const Word* d = c + words_;
        for (size_t w = 0; w < words_; ++w) {
          // A cell is active unless its 8 corners agree: fold the four rows, then pair bit x with bit x + 1.
          const Word any = a[w] | b[w] | c[w] | d[w], all = a[w] & b[w] & c[w] & d[w];
          const Word any_next = w + 1 < words_ ? a[w + 1] | b[w + 1] | c[w + 1] | d[w + 1] : 0;
          const Word all_next = w + 1 < words_ ? a[w + 1] & b[w + 1] & c[w + 1] & d[w + 1] : 0;
          Word active = (any | (any >> 1) | (any_next << 63)) & ~(all & ((all >> 1) | (all_next << 63)));
          if (w + 1 == words_) active &= edge_tail_;
          for (; active; active &= active - 1) {
            const int x = int(64 * w) + std::countr_zero(active);
            const int cube_case = bit(a, x) | bit(a, x + 1) << 1 | bit(b, x + 1) << 2 | bit(b, x) << 3 |
                                  bit(c, x) << 4 | bit(c, x + 1) << 5 | bit(d, x + 1) << 6 | bit(d, x) << 7;
            const FlatCase& fc = cell_case(x, y, z, cube_case);
            if constexpr (!kWrite) {
              counts.triangles += fc.count;
              counts.centers += fc.centers;
            } else {
              const size_t i = size_t(y) * nx + size_t(x);
              id[0] = lo_id[2 * i];
              id[1] = lo_id[2 * (i + 1) + 1];
              id[2] = lo_id[2 * (i + nx)];
              id[3] = lo_id[2 * i + 1];
              id[4] = hi_id[2 * i];
              id[5] = hi_id[2 * (i + 1) + 1];
              id[6] = hi_id[2 * (i + nx)];
              id[7] = hi_id[2 * i + 1];
              id[8] = zid[i];
              id[9] = zid[i + 1];
              id[10] = zid[i + nx + 1];
              id[11] = zid[i + nx];
              for (size_t k = 0; k < fc.centers; ++k) {
                id[size_t(mc::kCenter) + k] = center;
                const auto [p, n] = center_vertex(x, y, z, fc.center_edges[k]);
                positions_[center] = V(p);
                if (normals_) normals_[center] = V(n);
                ++center;
              }
              for (int t = 0; t < 3 * fc.count; ++t) *tris++ = id[fc.edges[size_t(t)]];
            }
          }
        }
      }
      std::swap(lo, hi);
      std::swap(lo_id, hi_id);
    }
    return counts;
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

  MarchingCubesOptions o_;
  glm::ivec3 d_;
  const float* data_;
  Vec3 spacing_, origin_;
  int z_offset_;
  size_t plane_;
  Vec3 per_difference_;  ///< smallest spacing / spacing: a difference over one voxel, scaled as gradient() returns
  size_t words_;
  Word edge_tail_ = 0;
  int slabs_ = 0;
  std::vector<int> slab_first_;
  std::vector<Counts> first_;
  /// Each thread's planes of bits and ids, reused from slab to slab (allocated per slab they were megabytes of fresh
  /// pages each at 512^3, faulted in again for every slab).
  struct Scratch {
    std::vector<Word> lo, hi;
    std::unique_ptr<uint32_t[]> lo_id, hi_id, zid;
  };
  mutable tbb::enumerable_thread_specific<Scratch> scratch_;
  V* positions_ = nullptr;
  V* normals_ = nullptr;
  uint32_t* triangles_ = nullptr;
};

}  // namespace

PolyMesh marching_cubes(const Volume<float>& volume, const MarchingCubesOptions& options) {
  return marching_cubes(VoxelGrid::of(volume), options);
}

PolyMesh marching_cubes(const VoxelGrid& grid, const MarchingCubesOptions& options) {
  if (!grid.voxels) throw InvalidInput("marching cubes: no voxels");
  checked_voxel_count(grid.dims);
  const Vec3& s = grid.spacing;
  if (!(s.x > 0 && s.y > 0 && s.z > 0))
    throw InvalidInput(fmt::format("marching cubes: spacing must be positive, got {},{},{}", s.x, s.y, s.z));
  PolyMesh mesh;
  const auto fresh = [](auto& array, size_t n) { resize_fresh(array, n); };
  const uint64_t triangles =
      Extractor<Vec3>(grid, options).run(mesh.positions, mesh.normals, mesh.face_vertices, fresh, sizeof(uint32_t));
  resize_fresh(mesh.face_offsets, size_t(triangles) + 1);
  uint32_t* offsets = mesh.face_offsets.data();
  parallel_for(0, int64_t(triangles) + 1, 1 << 16, [&](int64_t b, int64_t e) {
    for (int64_t f = b; f < e; ++f) offsets[f] = uint32_t(3 * f);
  });
  return mesh;
}

IsoSurface extract_iso_surface(const Volume<float>& volume, const MarchingCubesOptions& options) {
  IsoSurface s;
  // Uninitialized, on huge pages: pass 2 writes every element, each slab its own ranges, so the pages are first
  // touched there, in parallel, and never zeroed by the library.
  const auto fresh = [](auto& array, size_t n) { array.resize(n); };
  Extractor<Vec3f>(VoxelGrid::of(volume), options).run(s.positions, s.normals, s.indices, fresh, 0);
  return s;
}

TriMesh IsoSurface::to_tri_mesh() const {
  TriMesh mesh;
  mesh.positions.assign(positions.begin(), positions.end());
  mesh.normals.assign(normals.begin(), normals.end());
  mesh.indices.assign(indices.begin(), indices.end());
  return mesh;
}

}  // namespace tessera
