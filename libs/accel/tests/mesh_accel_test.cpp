// MeshAccel against brute force and against Embree 3 (the reference peer): on the same meshes and rays hit/miss agrees
// on >= 99.99% of rays and t to 1e-4 relative, for primary and random rays, on three meshes including one of >= 1M
// triangles. Also the smooth-normal helper and bad input.
#include "tessera/accel/mesh_accel.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include "embree_reference.hpp"
#include "tessera/accel/ray_workloads.hpp"
#include "tessera/core/cpu.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"

namespace tessera {
namespace {

TriMesh sphere_mesh(int slices, int stacks) { return to_tri_mesh(make_uv_sphere(slices, stacks)); }

/// The mesh's box.
AABB mesh_bounds(const TriMesh& mesh) {
  AABB b;
  for (const Vec3& p : mesh.positions) b.expand(Vec3f(p));
  return b;
}

std::vector<Ray> random_rays(const TriMesh& mesh, int count, uint64_t seed) {
  return incoherent_rays(mesh_bounds(mesh), size_t(count), seed);
}

/// Primary rays of a camera framing the mesh from an oblique direction.
std::vector<Ray> primary_rays(const TriMesh& mesh, int w, int h) {
  const AABB b = mesh_bounds(mesh);
  Camera cam;
  cam.center = Vec3(b.center());
  cam.eye = cam.center + 1.6 * double(glm::length(b.extent())) * glm::normalize(Vec3(0.4, 0.5, 1));
  cam.aspect = double(w) / h;
  return primary_rays(cam, w, h);
}

/// Hit/miss agreement and t agreement with Embree, for 200x200 primary rays and 50000 random rays; the same for both
/// stream APIs (MeshAccel's span intersect, Embree's rtcIntersect1M), as the benchmark compares those too.
void expect_agrees_with_embree(const TriMesh& mesh, const std::string& name, uint64_t seed) {
  const MeshAccel accel(mesh);
  const reference::EmbreeMesh embree(mesh);
  for (const bool primary : {true, false}) {
    const std::vector<Ray> rays = primary ? primary_rays(mesh, 200, 200) : random_rays(mesh, 50000, seed);
    std::vector<Hit> stream_hits(rays.size());
    accel.intersect(rays, stream_hits);
    std::vector<int> stream_prims(rays.size());
    std::vector<float> stream_t(rays.size());
    embree.intersect(rays, stream_prims, stream_t);
    for (const bool stream : {false, true}) {
      const std::string what = name + (primary ? " primary" : " random") + (stream ? " streams" : "");
      long disagree = 0, t_off = 0, hits = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        Ray ray = rays[i];
        Hit hit;
        bool ours = accel.intersect(ray, hit);
        float t;
        int prim = embree.intersect(rays[i], t);
        if (stream) {
          ours = stream_hits[i].prim >= 0;
          hit = stream_hits[i];
          prim = stream_prims[i];
          t = stream_t[i];
        }
        if (ours != (prim >= 0)) {
          ++disagree;
          continue;
        }
        if (!ours) continue;
        ++hits;
        if (std::abs(hit.t - t) > 1e-4f * std::max(t, 1e-3f)) ++t_off;
      }
      const double n = double(rays.size());
      EXPECT_LE(double(disagree) / n, 1e-4) << what << ": " << disagree << " of " << rays.size() << " rays disagree";
      EXPECT_LE(double(t_off) / n, 1e-4) << what << ": " << t_off << " hits with t off by more than 1e-4 relative";
      EXPECT_GT(hits, long(rays.size()) / 20) << what;
    }
  }
}

TEST(MeshAccel, MatchesBruteForceOnATorus) {
  const TriMesh torus = to_tri_mesh(make_torus(1.0, 0.3, 40, 20));
  const MeshAccel accel(torus);
  for (const Ray& r : random_rays(torus, 2000, 1)) {
    float best_t = r.tmax;
    int best = -1;
    for (size_t t = 0; t < torus.triangle_count(); ++t) {
      const Triangle tri{Vec3f(torus.positions[torus.indices[3 * t]]), Vec3f(torus.positions[torus.indices[3 * t + 1]]),
                         Vec3f(torus.positions[torus.indices[3 * t + 2]])};
      Ray rr = r;
      rr.tmax = best_t;
      Hit h;
      if (intersect(tri, rr, h)) {
        best_t = h.t;
        best = int(t);
      }
    }
    Ray ray = r;
    Hit hit;
    ASSERT_EQ(accel.intersect(ray, hit), best >= 0);
    ASSERT_EQ(accel.occluded(r), best >= 0);
    if (best < 0) continue;
    EXPECT_NEAR(hit.t, best_t, 1e-5f * best_t);
    EXPECT_EQ(ray.tmax, hit.t);
    // The reported triangle and barycentrics reproduce the point.
    const size_t t = size_t(hit.prim);
    const Vec3f p = (1 - hit.uv.x - hit.uv.y) * Vec3f(torus.positions[torus.indices[3 * t]]) +
                    hit.uv.x * Vec3f(torus.positions[torus.indices[3 * t + 1]]) +
                    hit.uv.y * Vec3f(torus.positions[torus.indices[3 * t + 2]]);
    EXPECT_NEAR(glm::length(p - hit.point), 0.0f, 1e-4f);
  }
}

/// The 4-wide (SSE) and 8-wide (AVX2, when the CPU has it) trees of a torus moved by `offset` and scaled by `size`,
/// over binned-SAH and bottom-up binary trees with leaves of 1 to 128 triangles (a larger leaf size is capped at 128),
/// against brute force, for random rays from around the mesh and from 1000 times its size away; both widths give
/// bit-identical t for the same tree (the same triangle arithmetic).
void check_widths_against_brute_force(const Vec3& offset, double size) {
  TriMesh torus = to_tri_mesh(make_torus(1.0, 0.3, 48, 24));
  for (Vec3& p : torus.positions) p = offset + size * p;
  std::vector<Ray> rays = random_rays(torus, 1500, 11);
  for (size_t i = 0, n = rays.size(); i < n; ++i) {
    Ray far = rays[i];
    far.origin -= float(1000 * size) * far.dir;
    rays.push_back(far);
  }
  std::vector<float> brute(rays.size(), -1.0f);
  for (size_t i = 0; i < rays.size(); ++i) {
    float best_t = rays[i].tmax;
    for (size_t t = 0; t < torus.triangle_count(); ++t) {
      const Triangle tri{Vec3f(torus.positions[torus.indices[3 * t]]), Vec3f(torus.positions[torus.indices[3 * t + 1]]),
                         Vec3f(torus.positions[torus.indices[3 * t + 2]])};
      Ray rr = rays[i];
      rr.tmax = best_t;
      Hit h;
      if (intersect(tri, rr, h)) best_t = brute[i] = h.t;
    }
  }
  const bool avx2 = cpu_features().avx2;
  for (const auto build : {BvhSettings::Build::binned_sah, BvhSettings::Build::bottom_up})
    for (const int leaf : {1, 4, 8, 13, 1000}) {
      BvhSettings s = MeshAccel::default_settings();
      s.build = build;
      s.max_leaf_size = leaf;
      const MeshAccel narrow(torus, s, 4);
      EXPECT_EQ(narrow.simd_width(), 4);
      std::optional<MeshAccel> wide;
      if (avx2) wide.emplace(torus, s, 8);
      for (size_t i = 0; i < rays.size(); ++i) {
        Ray ray = rays[i];
        Hit hit;
        TraversalStats stats;
        const bool h = narrow.intersect(ray, hit, &stats);
        ASSERT_EQ(h, brute[i] >= 0) << "ray " << i << " leaf " << leaf;
        ASSERT_EQ(narrow.occluded(rays[i]), h);
        EXPECT_GE(stats.nodes, 1);
        if (h) {
          EXPECT_NEAR(hit.t, brute[i], 1e-5f * brute[i]);
          EXPECT_GE(stats.prims, 1);
        }
        if (!wide) continue;
        Ray ray8 = rays[i];
        Hit hit8;
        ASSERT_EQ(wide->intersect(ray8, hit8), h);
        ASSERT_EQ(wide->occluded(rays[i]), h);
        if (h) {
          EXPECT_EQ(hit8.t, hit.t);
        }
      }
    }
}

TEST(MeshAccel, EveryWidthAndBuildMatchesBruteForce) {
  check_widths_against_brute_force(Vec3(0.0), 1.0);
  // Far from the origin, tiny and huge (the float rounding of boxes and ray origins scales with the coordinates).
  check_widths_against_brute_force(Vec3(2.5e4, -1.2e4, 7e3), 1.0);
  check_widths_against_brute_force(Vec3(1e-3, 0.0, -2e-3), 1e-5);
  check_widths_against_brute_force(Vec3(0.0), 3e6);
  EXPECT_THROW(MeshAccel(to_tri_mesh(make_torus(1.0, 0.3, 8, 4)), MeshAccel::default_settings(), 5), InvalidInput);
}

/// Whether two hits are the same bit for bit (t, point, normal, uv, prim).
bool same_bits(const Hit& a, const Hit& b) {
  const auto bits = [](const Hit& h) {
    return std::array<uint32_t, 10>{std::bit_cast<uint32_t>(h.t),        std::bit_cast<uint32_t>(h.point.x),
                                    std::bit_cast<uint32_t>(h.point.y),  std::bit_cast<uint32_t>(h.point.z),
                                    std::bit_cast<uint32_t>(h.normal.x), std::bit_cast<uint32_t>(h.normal.y),
                                    std::bit_cast<uint32_t>(h.normal.z), std::bit_cast<uint32_t>(h.uv.x),
                                    std::bit_cast<uint32_t>(h.uv.y),     uint32_t(h.prim)};
  };
  return bits(a) == bits(b);
}

TEST(MeshAccel, StreamsGiveTheOneRayHitsBitForBit) {
  // The span intersect walks several rays interleaved; each ray's walk must be the one-ray walk (same hit, same bits),
  // for both widths, small and large leaves, random rays (a third with a finite tmax, a sixth with tmin > 0), primary
  // rays, streams shorter than the number of walks in flight, and a tree of more than 24 MiB (whose walks fetch into
  // L2 rather than L1: other instantiations). occluded() must agree with the one-ray hit or miss.
  auto expect_streams_match = [](const MeshAccel& accel, const std::vector<Ray>& rays, const std::string& what) {
    std::vector<Hit> one(rays.size());
    long hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      Ray ray = rays[i];
      const bool hit = accel.intersect(ray, one[i]);
      ASSERT_EQ(accel.occluded(rays[i]), hit) << what << " ray " << i;  // any hit in the same interval
      hits += hit;
    }
    EXPECT_GT(hits, long(rays.size()) / 10) << what;
    for (const size_t count : {size_t(0), size_t(1), size_t(5), rays.size()}) {
      std::vector<Hit> streamed(count);
      // Stale contents must be overwritten, misses included.
      for (Hit& h : streamed) h.prim = 12345;
      accel.intersect(std::span<const Ray>(rays).first(count), streamed);
      for (size_t i = 0; i < count; ++i) ASSERT_TRUE(same_bits(streamed[i], one[i])) << what << " ray " << i;
    }
  };
  const TriMesh torus = to_tri_mesh(make_torus(1.0, 0.3, 64, 32));
  std::vector<Ray> rays = random_rays(torus, 4000, 21);
  Rng rng(5, 21);
  for (size_t i = 0; i < rays.size(); ++i) {
    if (i % 3 == 0) rays[i].tmax = 2.0f * rng.uniform();
    if (i % 6 == 1) rays[i].tmin = 0.5f * rng.uniform();
  }
  const std::vector<Ray> primary = primary_rays(torus, 64, 48);
  rays.insert(rays.end(), primary.begin(), primary.end());
  std::vector<int> widths{4};
  if (cpu_features().avx2) widths.push_back(8);
  const TriMesh big = to_tri_mesh(make_torus(1.0, 0.4, 1200, 450));
  const std::vector<Ray> big_rays = random_rays(big, 3000, 22);
  for (const int width : widths) {
    for (const int leaf : {1, 8, 1000}) {
      BvhSettings s = MeshAccel::default_settings();
      s.max_leaf_size = leaf;
      expect_streams_match(MeshAccel(torus, s, width), rays,
                           "width " + std::to_string(width) + " leaf " + std::to_string(leaf));
    }
    expect_streams_match(MeshAccel(big, MeshAccel::default_settings(), width), big_rays,
                         "1M torus, width " + std::to_string(width));
  }
  std::vector<Hit> too_few(3);
  EXPECT_THROW(MeshAccel(torus).intersect(std::span<const Ray>(rays).first(4), too_few), InvalidInput);
  std::vector<Hit> from_empty(2);
  from_empty[0].prim = 7;
  MeshAccel(TriMesh{}).intersect(std::span<const Ray>(rays).first(2), from_empty);
  EXPECT_EQ(from_empty[0].prim, -1);
}

TEST(MeshAccel, SameHitsForAnyThreadCount) {
  // The build is parallel (references, binning, subtrees, triangle blocks); the structure and so every hit and every
  // traversal count must not depend on the number of threads.
  const TriMesh mesh = to_tri_mesh(make_torus(1.0, 0.35, 400, 200));  // 160K triangles: parallel binning and tasks
  std::optional<MeshAccel> one, two;
  {
    ThreadLimit limit(1);
    one.emplace(mesh);
  }
  {
    ThreadLimit limit(2);
    two.emplace(mesh);
  }
  ASSERT_EQ(one->wide_node_count(), two->wide_node_count());
  for (const Ray& r : random_rays(mesh, 3000, 9)) {
    Ray a = r, b = r;
    Hit ha, hb;
    TraversalStats sa, sb;
    ASSERT_EQ(one->intersect(a, ha, &sa), two->intersect(b, hb, &sb));
    EXPECT_EQ(ha.t, hb.t);
    EXPECT_EQ(ha.prim, hb.prim);
    EXPECT_EQ(sa.nodes, sb.nodes);
    EXPECT_EQ(sa.prims, sb.prims);
  }
}

TEST(MeshAccel, StatsCountNodesAndTriangles) {
  // A single triangle is one leaf (no wide node): a hit tests one triangle; a ray beside it tests nothing.
  TriMesh one;
  one.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  one.indices = {0, 1, 2};
  const MeshAccel accel(one);
  Ray ray;
  ray.origin = Vec3f(0.25f, 0.25f, 1.0f);
  Hit hit;
  TraversalStats stats;
  ASSERT_TRUE(accel.intersect(ray, hit, &stats));
  EXPECT_EQ(stats.nodes, 0);
  EXPECT_EQ(stats.prims, 1);
  EXPECT_FLOAT_EQ(hit.t, 1.0f);
  EXPECT_EQ(hit.prim, 0);
  EXPECT_FLOAT_EQ(hit.uv.x, 0.25f);
  EXPECT_FLOAT_EQ(hit.uv.y, 0.25f);
  // A mesh of many triangles: a ray that hits visits the root and at least one more level, and tests a block.
  const TriMesh sphere = sphere_mesh(64, 32);
  const MeshAccel many(sphere);
  Ray r2;
  r2.origin = Vec3f(0.01f, 0.02f, 5.0f);
  TraversalStats s2;
  ASSERT_TRUE(many.intersect(r2, hit, &s2));
  EXPECT_GE(s2.nodes, 2);
  EXPECT_GE(s2.prims, 1);
  EXPECT_LE(s2.prims, int64_t(sphere.triangle_count()) / 10);
}

/// The least SAH cost of collapsing binary tree `nodes` into a wide tree of width W, by exhaustive search: every wide
/// node's children are one of all the cuts of its binary subtree (sets of at most W nodes below it that cover its
/// leaves), each generated once by deciding node after node whether it stays a child or gives way to its two
/// children. MeshAccel's collapse finds the optimum by dynamic programming over slot counts instead.
class ExhaustiveCollapse {
 public:
  ExhaustiveCollapse(std::span<const BvhNode> nodes, int width, int max_leaf)
      : n_(nodes), w_(width), max_leaf_(max_leaf), best_(nodes.size(), -1.0), count_(nodes.size()) {
    for (size_t i = nodes.size(); i-- > 0;)
      count_[i] = nodes[i].count > 0 ? nodes[i].count : count_[i + 1] + count_[size_t(nodes[i].first)];
  }
  /// The tree's cost as MeshAccel::sah_cost defines it (relative to the root's area).
  double root_cost() { return as_child(0) / area(0); }

 private:
  double area(int i) const { return double(n_[size_t(i)].box.area()); }
  double leaf(int i) const { return area(i) * MeshAccel::kBlockCost * double((count_[size_t(i)] + 3) / 4); }
  /// Subtree i as one child: a binary leaf, a merged leaf (if small enough) or a wide node over its best cut.
  double as_child(int i) {
    double& b = best_[size_t(i)];
    if (b >= 0) return b;
    if (n_[size_t(i)].count > 0) return b = leaf(i);
    double best = std::numeric_limits<double>::infinity();
    std::vector<int> kept;
    cuts({i + 1, n_[size_t(i)].first}, kept, best);
    b = area(i) * MeshAccel::kNodeCost + best;
    if (count_[size_t(i)] <= max_leaf_) b = std::min(b, leaf(i));
    return b;
  }
  /// Every cut that keeps `kept` and covers the undecided subtrees `open`; best gets the least sum of child costs.
  void cuts(std::vector<int> open, std::vector<int>& kept, double& best) {
    if (int(open.size() + kept.size()) > w_) return;
    if (open.empty()) {
      double sum = 0;
      for (int k : kept) sum += as_child(k);
      best = std::min(best, sum);
      return;
    }
    const int i = open.back();
    open.pop_back();
    kept.push_back(i);
    cuts(open, kept, best);
    kept.pop_back();
    if (n_[size_t(i)].count == 0) {
      open.push_back(i + 1);
      open.push_back(n_[size_t(i)].first);
      cuts(open, kept, best);
    }
  }

  std::span<const BvhNode> n_;
  int w_, max_leaf_;
  std::vector<double> best_;
  std::vector<int> count_;
};

TEST(MeshAccel, TheCollapseIsSahOptimal) {
  // Random triangle soups (clustered, so the SAH has choices to make) and a small torus, both widths, leaves of 1
  // (no merging), 8 (the default) and 13: the collapse's cost is the exhaustive search's least cost.
  Rng rng(17);
  std::vector<TriMesh> meshes{to_tri_mesh(make_torus(1.0, 0.4, 10, 6))};
  for (const int n : {3, 9, 24, 50, 90}) {
    TriMesh soup;
    for (int t = 0; t < n; ++t) {
      const Vec3 center = rng.uniform() < 0.5 ? Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 10.0
                                              : Vec3(rng.uniform(), 0, 0) * 10.0;
      const double size = rng.uniform() < 0.8 ? 0.3 : 3.0;
      for (int k = 0; k < 3; ++k) {
        soup.positions.push_back(center + size * Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        soup.indices.push_back(uint32_t(soup.positions.size() - 1));
      }
    }
    meshes.push_back(soup);
  }
  const bool avx2 = cpu_features().avx2;
  for (size_t m = 0; m < meshes.size(); ++m)
    for (const int width : {4, 8})
      for (const int leaf : {1, 8, 13}) {
        if (width == 8 && !avx2) continue;
        BvhSettings s = MeshAccel::default_settings();
        s.max_leaf_size = leaf;
        const MeshAccel accel(meshes[m], s, width);
        const double expected = ExhaustiveCollapse(accel.bvh().nodes(), width, leaf).root_cost();
        EXPECT_NEAR(accel.sah_cost(), expected, 1e-5 * expected)
            << "mesh " << m << " width " << width << " leaf " << leaf;
      }
}

TEST(MeshAccel, SmoothNormalsOfASphereMeshPointFromTheCenter) {
  const TriMesh sphere = sphere_mesh(64, 32);
  ASSERT_EQ(sphere.normals.size(), sphere.positions.size());
  const MeshAccel accel(sphere);
  for (const Ray& r : primary_rays(sphere, 64, 64)) {
    Ray ray = r;
    Hit hit;
    if (!accel.intersect(ray, hit)) continue;
    const Vec3f n = shading_normal(sphere, hit);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    // Interpolated vertex normals are much closer to the true sphere normal than the facet normal is.
    const Vec3f truth = glm::normalize(hit.point);
    EXPECT_GT(glm::dot(n, truth), 0.9995f);
    EXPECT_GT(glm::dot(hit.normal, truth), 0.99f);
  }
  TriMesh bare = sphere;
  bare.normals.clear();
  Hit h;
  h.prim = 0;
  h.normal = Vec3f(0, 0, 1);
  EXPECT_EQ(shading_normal(bare, h), h.normal);
}

TEST(MeshAccel, BadMeshesThrow) {
  TriMesh m = sphere_mesh(8, 4);
  m.indices[5] = uint32_t(m.positions.size());
  EXPECT_THROW(MeshAccel accel(m), InvalidInput);
  m = sphere_mesh(8, 4);
  m.positions[3].x = std::nan("");
  EXPECT_THROW(MeshAccel accel(m), InvalidInput);
  const MeshAccel empty{TriMesh{}};
  Ray r;
  Hit h;
  EXPECT_FALSE(empty.intersect(r, h));
}

TEST(MeshAccel, AgreesWithEmbreeOnASphere) { expect_agrees_with_embree(sphere_mesh(200, 100), "sphere", 2); }

TEST(MeshAccel, AgreesWithEmbreeOnATorus) {
  expect_agrees_with_embree(to_tri_mesh(make_torus(1.0, 0.35, 300, 150)), "torus", 3);
}

TEST(MeshAccel, AgreesWithEmbreeOnAMillionTriangles) {
  // The Stanford bunny when the shared data is present (69K triangles, as a second real mesh), and always a
  // tessellated torus of 1.08M triangles.
  const std::filesystem::path bunny = std::filesystem::path(TESSERA_SHARED_DATA) / "meshes/bunny/bun_zipper.ply";
  if (std::filesystem::exists(bunny)) {
    expect_agrees_with_embree(to_tri_mesh(read_mesh(bunny)), "bunny", 4);
  }
  const TriMesh mesh = to_tri_mesh(make_torus(1.0, 0.4, 1200, 450));
  ASSERT_GE(mesh.triangle_count(), 1000000u);
  expect_agrees_with_embree(mesh, "1M torus", 5);
}

}  // namespace
}  // namespace tessera
