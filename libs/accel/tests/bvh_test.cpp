// Bvh (both builds) and UniformGrid against brute force on random scenes of triangles and spheres; structural
// invariants of the flattened tree; determinism across thread counts.
#include "tessera/accel/bvh.hpp"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <variant>

#include "tessera/accel/grid.hpp"
#include "tessera/accel/shapes.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"

namespace tessera {
namespace {

Vec3f random_point(Rng& rng, float scale) {
  return scale * Vec3f(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
}

/// A random scene: small triangles and spheres of varied sizes in [-10, 10]^3 (some clustered, some large).
std::vector<Shape> random_scene(uint64_t seed, int count) {
  Rng rng(seed);
  std::vector<Shape> shapes;
  for (int i = 0; i < count; ++i) {
    const Vec3f c = i % 5 == 0 ? random_point(rng, 2) : random_point(rng, 10);  // a dense cluster near the origin
    const float size = i % 50 == 0 ? 3.0f : 0.2f + 1.5f * rng.uniform();
    if (i % 3 == 0) {
      shapes.emplace_back(Sphere{c, 0.5f * size});
    } else {
      shapes.emplace_back(
          Triangle{c + random_point(rng, size), c + random_point(rng, size), c + random_point(rng, size)});
    }
  }
  return shapes;
}

std::vector<AABB> boxes_of(const std::vector<Shape>& shapes) {
  std::vector<AABB> boxes;
  for (const Shape& s : shapes) boxes.push_back(bounds(s));
  return boxes;
}

/// Random rays: origins in the scene's box and around it, directions uniform, some with a finite tmax.
std::vector<Ray> random_rays(uint64_t seed, int count) {
  Rng rng(seed);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Ray r;
    r.origin = random_point(rng, 14);
    do r.dir = random_point(rng, 1);
    while (glm::length(r.dir) < 0.1f || glm::length(r.dir) > 1.0f);
    r.dir = glm::normalize(r.dir);
    if (i % 7 == 0) r.dir.y = 0;  // axis-parallel components exercise the slab test's infinities
    if (i % 4 == 0) r.tmax = 8.0f;
    rays.push_back(r);
  }
  return rays;
}

struct Nearest {
  int prim = -1;
  float t = 0;
};

Nearest brute_force(const std::vector<Shape>& shapes, Ray ray) {
  Nearest best;
  for (int i = 0; i < int(shapes.size()); ++i) {
    Hit h;
    if (intersect(shapes[size_t(i)], ray, h)) {
      ray.tmax = h.t;
      best = {i, h.t};
    }
  }
  return best;
}

/// The callback every structure is fed: tests one shape, shrinks the ray on a hit.
auto shape_tester(const std::vector<Shape>& shapes, Nearest& best) {
  return [&shapes, &best](int prim, Ray& ray) {
    Hit h;
    if (!intersect(shapes[size_t(prim)], ray, h)) return false;
    ray.tmax = h.t;
    best = {prim, h.t};
    return true;
  };
}

template <class Accel>
void expect_same_hits_as_brute_force(const Accel& accel, const std::vector<Shape>& shapes,
                                     const std::vector<Ray>& rays) {
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Nearest ref = brute_force(shapes, rays[i]);
    Nearest got;
    Ray ray = rays[i];
    const bool hit = accel.intersect(ray, shape_tester(shapes, got));
    ASSERT_EQ(hit, ref.prim >= 0) << "ray " << i;
    ASSERT_EQ(got.t, ref.t) << "ray " << i;  // the same kernel on the same ray: bit-identical
    if (hit) {
      ASSERT_EQ(ray.tmax, ref.t);
      // Two primitives at exactly the same t may tie; then either is right.
      if (got.prim != ref.prim) {
        Hit h;
        Ray r = rays[i];
        ASSERT_TRUE(intersect(shapes[size_t(got.prim)], r, h));
        ASSERT_EQ(h.t, ref.t);
      }
      ++hits;
    }
    // occluded: any hit in the interval.
    Nearest dummy;
    ASSERT_EQ(accel.occluded(rays[i], shape_tester(shapes, dummy)), ref.prim >= 0) << "ray " << i;
  }
  EXPECT_GT(hits, int(rays.size()) / 10);
  EXPECT_LT(hits, int(rays.size()));
}

TEST(Bvh, BinnedSahMatchesBruteForce) {
  const auto shapes = random_scene(1, 3000);
  const Bvh bvh(boxes_of(shapes));
  expect_same_hits_as_brute_force(bvh, shapes, random_rays(2, 3000));
}

TEST(Bvh, BottomUpMatchesBruteForce) {
  const auto shapes = random_scene(3, 3000);
  BvhSettings s;
  s.build = BvhSettings::Build::bottom_up;
  const Bvh bvh(boxes_of(shapes), s);
  expect_same_hits_as_brute_force(bvh, shapes, random_rays(4, 3000));
}

TEST(Bvh, LeafSizesAndBinCountsMatchBruteForce) {
  const auto shapes = random_scene(5, 800);
  const auto rays = random_rays(6, 800);
  for (int leaf : {1, 2, 8, 32})
    for (int bins : {2, 8, 64}) {
      BvhSettings s;
      s.max_leaf_size = leaf;
      s.bins = bins;
      s.traversal_cost = leaf == 32 ? 0.1f : 1.0f;
      expect_same_hits_as_brute_force(Bvh(boxes_of(shapes), s), shapes, rays);
    }
}

TEST(Grid, MatchesBruteForce) {
  const auto shapes = random_scene(7, 3000);
  for (float density : {0.5f, 2.0f, 8.0f}) {
    GridSettings s;
    s.density = density;
    const UniformGrid grid(boxes_of(shapes), s);
    const glm::ivec3 r = grid.resolution();
    EXPECT_NEAR(double(r.x) * r.y * r.z, density * 3000.0, 0.5 * density * 3000.0);
    expect_same_hits_as_brute_force(grid, shapes, random_rays(8, 2000));
  }
}

TEST(Grid, FlatSceneAndRayStartingInside) {
  // All triangles in the plane z = 0 (a zero-thickness grid box) and rays from inside the box.
  std::vector<Shape> shapes;
  Rng rng(9);
  for (int i = 0; i < 500; ++i) {
    const Vec3f c(random_point(rng, 5).x, random_point(rng, 5).y, 0);
    shapes.emplace_back(Triangle{c, c + Vec3f(0.3f, 0, 0), c + Vec3f(0, 0.3f, 0)});
  }
  const UniformGrid grid(boxes_of(shapes));
  const Bvh bvh(boxes_of(shapes));
  std::vector<Ray> rays;
  for (int i = 0; i < 1000; ++i) {
    Ray r;
    r.origin = Vec3f(random_point(rng, 5).x, random_point(rng, 5).y, i % 2 ? 0.0f : 3.0f);
    r.dir = glm::normalize(Vec3f(random_point(rng, 0.5f).x, random_point(rng, 0.5f).y, -1));
    rays.push_back(r);
  }
  expect_same_hits_as_brute_force(grid, shapes, rays);
  expect_same_hits_as_brute_force(bvh, shapes, rays);
  // A zero direction inside the grid visits one cell and ends (no endless walk).
  Ray still{Vec3f(0, 0, 0), Vec3f(0.0f)};
  TraversalStats stats;
  grid.intersect(
      still, [](int, Ray&) { return false; }, &stats);
  EXPECT_EQ(stats.nodes, 1);
}

/// Every node's box holds its children's boxes or its primitives' boxes; every primitive is in exactly one leaf;
/// the first child follows its parent (depth-first order).
void check_structure(const Bvh& bvh, const std::vector<AABB>& boxes, int max_leaf) {
  const auto nodes = bvh.nodes();
  std::vector<int> seen(boxes.size(), 0);
  auto inside = [](const AABB& outer, const AABB& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
  };
  int max_depth = 0;
  std::vector<std::pair<int, int>> stack{{0, 1}};
  while (!stack.empty()) {
    const auto [i, depth] = stack.back();
    stack.pop_back();
    max_depth = std::max(max_depth, depth);
    const BvhNode& n = nodes[size_t(i)];
    if (n.count > 0) {
      EXPECT_LE(int(n.count), max_leaf);
      for (int k = n.first; k < n.first + n.count; ++k) {
        const int p = bvh.prim_indices()[size_t(k)];
        ++seen[size_t(p)];
        ASSERT_TRUE(inside(n.box, boxes[size_t(p)]));
      }
    } else {
      ASSERT_LT(n.first, int(nodes.size()));
      ASSERT_GT(n.first, i + 1);
      ASSERT_TRUE(inside(n.box, nodes[size_t(i) + 1].box));
      ASSERT_TRUE(inside(n.box, nodes[size_t(n.first)].box));
      stack.push_back({i + 1, depth + 1});
      stack.push_back({n.first, depth + 1});
    }
  }
  for (size_t p = 0; p < boxes.size(); ++p) EXPECT_EQ(seen[p], boxes[p].empty() ? 0 : 1) << "primitive " << p;
  EXPECT_EQ(max_depth, bvh.depth());
  EXPECT_LE(bvh.depth(), Bvh::kMaxDepth);
}

TEST(Bvh, StructureInvariants) {
  auto boxes = boxes_of(random_scene(10, 5000));
  boxes[17] = AABB{};  // an empty box is left out
  for (auto build : {BvhSettings::Build::binned_sah, BvhSettings::Build::bottom_up}) {
    BvhSettings s;
    s.build = build;
    const Bvh bvh(boxes, s);
    check_structure(bvh, boxes, s.max_leaf_size);
    EXPECT_EQ(bvh.prim_indices().size(), boxes.size() - 1);
    // A reasonable tree: depth near log2(n / leaf) and an SAH cost well below the single-leaf cost n.
    EXPECT_LT(bvh.depth(), 40);
    EXPECT_LT(bvh.sah_cost(), 0.02f * float(boxes.size()));
  }
}

/// The tests the SAH charges a leaf of `count` primitives: whole blocks of s.leaf_block.
double block_tests(const BvhSettings& s, int count) { return double((count + s.leaf_block - 1) / s.leaf_block); }

/// The binned SAH by brute force (no sweep): the least cost over every bin boundary of every axis for the primitives
/// `prims`, binned as docs/accel.md says (twice the centroids, nb = min(bins, max(4, n)) bins over their bounds,
/// scale nb (1 - 1e-5) / extent in float), costed in double. Infinity when the centroids coincide.
double cheapest_binned_split(const std::vector<AABB>& boxes, const std::vector<int>& prims, const BvhSettings& s) {
  const int n = int(prims.size()), nb = std::min(s.bins, std::max(4, n));
  auto centroid2 = [&](int p, int a) { return boxes[size_t(p)].lo[a] + boxes[size_t(p)].hi[a]; };
  AABB all;
  for (int p : prims) all.expand(boxes[size_t(p)]);
  double best = INFINITY;
  for (int a = 0; a < 3; ++a) {
    float lo = INFINITY, hi = -INFINITY;
    for (int p : prims) lo = std::min(lo, centroid2(p, a)), hi = std::max(hi, centroid2(p, a));
    if (!(hi > lo)) continue;
    const float scale = float(nb) * (1.0f - 1e-5f) / (hi - lo);
    for (int boundary = 1; boundary < nb; ++boundary) {
      AABB left, right;
      int left_count = 0;
      for (int p : prims) {
        const int bin = std::clamp(int((centroid2(p, a) - lo) * scale), 0, nb - 1);
        (bin < boundary ? left : right).expand(boxes[size_t(p)]);
        left_count += bin < boundary;
      }
      if (left_count == 0 || left_count == n) continue;
      const double cost = s.traversal_cost + s.intersection_cost *
                                                 (double(left.area()) * block_tests(s, left_count) +
                                                  double(right.area()) * block_tests(s, n - left_count)) /
                                                 double(all.area());
      best = std::min(best, cost);
    }
  }
  return best;
}

TEST(Bvh, EverySplitIsTheCheapestBinBoundary) {
  // Every interior node splits where the brute-force binned SAH above is least, and every range becomes a leaf
  // exactly when the SAH says so: an independent check of the builder's sweep (the three axes at once) and of its
  // leaf rule, with MeshAccel's block-rounded costs and an odd bin count too.
  const auto boxes = boxes_of(random_scene(12, 2000));
  BvhSettings mesh_like;
  mesh_like.max_leaf_size = 8;
  mesh_like.leaf_block = 4;
  BvhSettings odd_bins;
  odd_bins.bins = 7;
  odd_bins.traversal_cost = 0.5f;
  for (const BvhSettings& s : {BvhSettings{}, mesh_like, odd_bins}) {
    const Bvh bvh(boxes, s);
    const auto nodes = bvh.nodes();
    // The primitives under each node (depth first: a node's subtree is a contiguous run of leaves).
    std::vector<std::vector<int>> under(nodes.size());
    for (int i = int(nodes.size()) - 1; i >= 0; --i) {
      const BvhNode& node = nodes[size_t(i)];
      if (node.count > 0) {
        for (int k = 0; k < node.count; ++k) under[size_t(i)].push_back(bvh.prim_indices()[size_t(node.first + k)]);
      } else {
        under[size_t(i)] = under[size_t(i) + 1];
        under[size_t(i)].insert(under[size_t(i)].end(), under[size_t(node.first)].begin(),
                                under[size_t(node.first)].end());
      }
    }
    int splits = 0, sah_leaves = 0;
    for (size_t i = 0; i < nodes.size(); ++i) {
      const BvhNode& node = nodes[i];
      const int n = int(under[i].size());
      if (n == 1) continue;
      const double cheapest = cheapest_binned_split(boxes, under[i], s);
      ASSERT_LT(cheapest, INFINITY) << "node " << i;  // random boxes: no coincident centroids
      auto tests = [&](size_t k) { return block_tests(s, int(under[k].size())); };
      const double leaf_cost = s.intersection_cost * tests(i);
      const bool one_block = n <= s.leaf_block && n <= s.max_leaf_size && s.traversal_cost >= s.intersection_cost;
      if (node.count > 0) {
        EXPECT_LE(n, s.max_leaf_size) << "node " << i;
        if (!one_block) {
          EXPECT_LE(leaf_cost, cheapest * (1 + 1e-6)) << "node " << i;
        }
        sah_leaves += !one_block;
        continue;
      }
      if (n <= s.max_leaf_size) {
        EXPECT_GT(leaf_cost, cheapest * (1 - 1e-6)) << "node " << i;
      }
      const size_t second = size_t(node.first);
      const double split_cost = s.traversal_cost + s.intersection_cost *
                                                       (double(nodes[i + 1].box.area()) * tests(i + 1) +
                                                        double(nodes[second].box.area()) * tests(second)) /
                                                       double(node.box.area());
      EXPECT_NEAR(split_cost, cheapest, 1e-6 * cheapest) << "node " << i << ", " << n << " primitives";
      ++splits;
    }
    EXPECT_GT(splits, 200);
    EXPECT_GT(sah_leaves, 10);  // leaves of several primitives that the SAH chose over a split
  }
}

TEST(Bvh, InputOrderChangesOnlyTheOrderInsideLeaves) {
  // The splits depend on the set of primitives in a range, not on their order: the same boxes listed sorted along x
  // (long runs of one side: the partition's plain loop) and shuffled (sides change often: its branch-free blocks)
  // must give the same nodes, and leaves holding the same primitives.
  auto boxes = boxes_of(random_scene(12, 20000));
  std::vector<int> sorted(boxes.size()), shuffled(boxes.size());
  std::iota(sorted.begin(), sorted.end(), 0);
  std::sort(sorted.begin(), sorted.end(), [&](int a, int b) { return boxes[size_t(a)].lo.x < boxes[size_t(b)].lo.x; });
  shuffled = sorted;
  Rng rng(5);
  for (size_t i = shuffled.size() - 1; i > 0; --i) std::swap(shuffled[i], shuffled[rng.next_u32() % (i + 1)]);
  auto build = [&](const std::vector<int>& order) {
    std::vector<AABB> listed(boxes.size());
    for (size_t i = 0; i < order.size(); ++i) listed[i] = boxes[size_t(order[i])];
    return Bvh(listed);
  };
  const Bvh a = build(sorted), b = build(shuffled);
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  for (size_t i = 0; i < a.nodes().size(); ++i) {
    const BvhNode &na = a.nodes()[i], &nb = b.nodes()[i];
    ASSERT_EQ(na.first, nb.first) << i;
    ASSERT_EQ(na.count, nb.count) << i;
    ASSERT_EQ(na.box.lo, nb.box.lo) << i;
    ASSERT_EQ(na.box.hi, nb.box.hi) << i;
    if (na.count == 0) continue;
    std::vector<int> pa, pb;
    for (int k = na.first; k < na.first + na.count; ++k) {
      pa.push_back(sorted[size_t(a.prim_indices()[size_t(k)])]);
      pb.push_back(shuffled[size_t(b.prim_indices()[size_t(k)])]);
    }
    std::sort(pa.begin(), pa.end());
    std::sort(pb.begin(), pb.end());
    ASSERT_EQ(pa, pb) << "leaf " << i;
  }
}

TEST(Bvh, CoincidentAndDegenerateInputs) {
  // 1000 identical boxes cannot be separated by any split: the range is halved until leaves are small.
  std::vector<AABB> same(1000, AABB{Vec3f(0.0f), Vec3f(1.0f)});
  for (auto build : {BvhSettings::Build::binned_sah, BvhSettings::Build::bottom_up}) {
    BvhSettings s;
    s.build = build;
    check_structure(Bvh(same, s), same, s.max_leaf_size);
  }
  // Points on a line with exponentially growing gaps (a chain for naive splits): the depth stays bounded.
  std::vector<AABB> chain;
  for (int i = 0; i < 3000; ++i) {
    const Vec3f p(std::ldexp(1.0f, i / 30), 0, 0);
    chain.push_back(AABB{p, p + Vec3f(1.0f)});
  }
  check_structure(Bvh(chain), chain, 4);
  // Empty input and a single primitive.
  const Bvh empty(std::vector<AABB>{});
  Ray r;
  EXPECT_FALSE(empty.intersect(r, [](int, Ray&) { return true; }));
  EXPECT_EQ(empty.depth(), 0);
  const Bvh one(std::vector<AABB>{AABB{Vec3f(-1.0f), Vec3f(1.0f)}});
  EXPECT_EQ(one.nodes().size(), 1u);
  r.origin = Vec3f(0, 0, 5);
  EXPECT_TRUE(one.intersect(r, [](int p, Ray&) { return p == 0; }));
}

TEST(Bvh, TwoPrimitivesByHand) {
  // Two unit boxes far apart along x, leaves of one: root with the left box first (axis x), then the right one.
  const std::vector<AABB> boxes{AABB{Vec3f(5, 0, 0), Vec3f(6, 1, 1)}, AABB{Vec3f(0.0f), Vec3f(1.0f)}};
  BvhSettings s;
  s.max_leaf_size = 1;
  const Bvh bvh(boxes, s);
  ASSERT_EQ(bvh.nodes().size(), 3u);
  EXPECT_EQ(bvh.nodes()[0].count, 0);
  EXPECT_EQ(bvh.nodes()[0].axis, 0);
  EXPECT_EQ(bvh.nodes()[0].first, 2);
  EXPECT_EQ(bvh.prim_indices()[size_t(bvh.nodes()[1].first)], 1);  // the box at x in [0, 1] comes first
  // SAH cost by hand: root 1 (traversal) + each leaf's area ratio times 1 (one primitive each).
  const float root = AABB{Vec3f(0.0f), Vec3f(6, 1, 1)}.area();
  EXPECT_NEAR(bvh.sah_cost(), 1.0f + 2 * 6.0f / root, 1e-5f);
  // Ordered traversal: a ray going down x visits primitive 0 (at x = 5) first.
  Ray ray{Vec3f(10, 0.5f, 0.5f), Vec3f(-1, 0, 0)};
  std::vector<int> order;
  bvh.intersect(ray, [&](int p, Ray&) {
    order.push_back(p);
    return false;
  });
  EXPECT_EQ(order, (std::vector<int>{0, 1}));
  TraversalStats stats;
  Ray ray2{Vec3f(-10, 0.5f, 0.5f), Vec3f(1, 0, 0)};
  order.clear();
  bvh.intersect(
      ray2,
      [&](int p, Ray& r) {
        order.push_back(p);
        r.tmax = 10.5f;  // a hit at x = 0.5 ends the search before the far box
        return true;
      },
      &stats);
  EXPECT_EQ(order, (std::vector<int>{1}));
  EXPECT_EQ(stats.nodes, 3);
  EXPECT_EQ(stats.prims, 1);
}

TEST(Bvh, SameTreeForAnyThreadCount) {
  // Large enough for the parallel paths: subtrees as tasks, parallel binning, and (with more than one thread) the
  // parallel partition of the ranges that are a large share of all, which must give the serial partition's result.
  // Shuffled boxes (the serial partition's branch-free blocks) and boxes sorted along x (its plain loop); arenas of
  // 3 and 8 threads reach deeper levels with the parallel partition, even on a 2-core machine.
  auto boxes = boxes_of(random_scene(11, 70000));
  auto sorted = boxes;
  std::sort(sorted.begin(), sorted.end(), [](const AABB& a, const AABB& b) { return a.lo.x < b.lo.x; });
  for (const auto* input : {&boxes, &sorted})
    for (auto build : {BvhSettings::Build::binned_sah, BvhSettings::Build::bottom_up}) {
      BvhSettings s;
      s.build = build;
      std::optional<Bvh> one;
      {
        ThreadLimit limit(1);
        one.emplace(*input, s);
      }
      auto expect_same = [&](const Bvh& other, const char* threads) {
        ASSERT_EQ(other.nodes().size(), one->nodes().size()) << threads;
        EXPECT_TRUE(std::equal(one->prim_indices().begin(), one->prim_indices().end(), other.prim_indices().begin()))
            << threads;
        for (size_t i = 0; i < one->nodes().size(); ++i) {
          ASSERT_EQ(other.nodes()[i].first, one->nodes()[i].first) << threads << " node " << i;
          ASSERT_EQ(other.nodes()[i].count, one->nodes()[i].count) << threads << " node " << i;
          ASSERT_EQ(other.nodes()[i].box.lo, one->nodes()[i].box.lo) << threads << " node " << i;
        }
      };
      expect_same(Bvh(*input, s), "all threads");
      for (int threads : {3, 8}) {
        tbb::task_arena arena(threads);
        arena.execute([&] { expect_same(Bvh(*input, s), threads == 3 ? "3 threads" : "8 threads"); });
      }
    }
}

TEST(Bvh, BadSettingsAndBoxesThrow) {
  const std::vector<AABB> boxes{AABB{Vec3f(0.0f), Vec3f(1.0f)}};
  BvhSettings s;
  s.bins = 1;
  EXPECT_THROW(Bvh bvh(boxes, s), InvalidInput);
  s = {};
  s.max_leaf_size = 0;
  EXPECT_THROW(Bvh bvh(boxes, s), InvalidInput);
  EXPECT_THROW(Bvh bvh(std::vector<AABB>{bounds(Plane{})}), InvalidInput);
  EXPECT_THROW(UniformGrid grid(std::vector<AABB>{bounds(Plane{})}), InvalidInput);
  GridSettings g;
  g.density = 0;
  EXPECT_THROW(UniformGrid grid(boxes, g), InvalidInput);
}

}  // namespace
}  // namespace tessera
