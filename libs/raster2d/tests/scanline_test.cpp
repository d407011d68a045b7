#include "tessera/raster2d/scanline.hpp"

#include <gtest/gtest.h>

#include <random>

#include "raster_oracle.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {
namespace {

// A counting target: how many times scan_path hands each pixel to the sink (aliased), or the sum of its coverages.
struct Counts {
  Image<int> writes;
  Image<double> coverage;
  Counts(int w, int h) : writes(w, h, 0), coverage(w, h, 0.0) {}
  void scan(const Path& path, FillRule rule, bool antialias) {
    scan_path(path, rule, writes.width(), writes.height(), antialias, [&](int y, int x0, int x1, const float* cov) {
      for (int x = x0; x < x1; ++x) {
        ++writes(x, y);
        coverage(x, y) += cov ? cov[x - x0] : 1.0;
      }
    });
  }
};

// A jittered grid of (nx + 1) x (ny + 1) vertices over [0, w] x [0, h] (border vertices stay on the border), each
// cell split into two triangles along a random diagonal.
std::vector<Path> random_triangulated_grid(std::mt19937& rng, int w, int h, int nx, int ny) {
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  std::vector<Vec2> v;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = (i + (i > 0 && i < nx ? jitter(rng) : 0.0)) * w / nx;
      const double y = (j + (j > 0 && j < ny ? jitter(rng) : 0.0)) * h / ny;
      v.push_back({x, y});
    }
  auto at = [&](int i, int j) { return v[size_t(j * (nx + 1) + i)]; };
  std::vector<Path> tris;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (rng() % 2) {
        tris.push_back(Path{{{a, b, c}}});
        tris.push_back(Path{{{a, c, d}}});
      } else {
        tris.push_back(Path{{{a, b, d}}});
        tris.push_back(Path{{{b, c, d}}});
      }
    }
  return tris;
}

// Random guillotine cuts of [x0, x1) x [y0, y1) at random real positions into abutting rectangles.
void random_rects(std::mt19937& rng, double x0, double y0, double x1, double y1, int depth, std::vector<Path>& out) {
  std::uniform_real_distribution<double> u(0.2, 0.8);
  if (depth == 0 || (x1 - x0 < 2 && y1 - y0 < 2)) {
    out.push_back(Path{{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}});
    return;
  }
  if (x1 - x0 > y1 - y0) {
    const double xm = x0 + (x1 - x0) * u(rng);
    random_rects(rng, x0, y0, xm, y1, depth - 1, out);
    random_rects(rng, xm, y0, x1, y1, depth - 1, out);
  } else {
    const double ym = y0 + (y1 - y0) * u(rng);
    random_rects(rng, x0, y0, x1, ym, depth - 1, out);
    random_rects(rng, x0, ym, x1, y1, depth - 1, out);
  }
}

void expect_tiles_exactly_once(const std::vector<Path>& pieces, int w, int h) {
  for (const FillRule rule : {FillRule::non_zero, FillRule::even_odd}) {
    Counts aliased(w, h), smooth(w, h);
    for (const Path& p : pieces) {
      aliased.scan(p, rule, false);
      smooth.scan(p, rule, true);
    }
    int bad = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        bad += aliased.writes(x, y) != 1;
        EXPECT_NEAR(smooth.coverage(x, y), 1.0, 1e-3) << x << "," << y;
      }
    EXPECT_EQ(bad, 0) << "pixels not written exactly once";
  }
}

TEST(Scanline, RandomTriangulatedGridWritesEveryPixelExactlyOnce) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 4; ++trial)
    expect_tiles_exactly_once(random_triangulated_grid(rng, 97, 83, 9, 7), 97, 83);
}

TEST(Scanline, RandomAbuttingRectsWriteEveryPixelExactlyOnce) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<Path> rects;
    random_rects(rng, 0, 0, 101, 77, 7, rects);
    expect_tiles_exactly_once(rects, 101, 77);
  }
}

void expect_matches_point_in_polygon(const Path& path, int w, int h) {
  for (const FillRule rule : {FillRule::non_zero, FillRule::even_odd}) {
    Counts counts(w, h);
    counts.scan(path, rule, false);
    int mismatches = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        mismatches += (counts.writes(x, y) == 1) != test::point_in_path(path, rule, {x + 0.5, y + 0.5}) ||
                      counts.writes(x, y) > 1;
    EXPECT_EQ(mismatches, 0) << (rule == FillRule::non_zero ? "nonzero" : "even-odd");
  }
}

TEST(Scanline, ConcavePolygonsWithHolesMatchPointInPolygon) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial)
    expect_matches_point_in_polygon(test::random_polygon_with_holes(rng, 120, 90), 120, 90);
}

TEST(Scanline, SelfIntersectingPolygonsMatchPointInPolygon) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-20, 140);
  for (int trial = 0; trial < 20; ++trial) {
    Path path;
    for (int c = 0; c < 2; ++c) {
      path.contours.emplace_back();
      for (int i = 0; i < 12; ++i) path.contours.back().push_back({u(rng), u(rng)});
    }
    expect_matches_point_in_polygon(path, 120, 100);  // partly outside: clipping must not change inside pixels
  }
}

TEST(Scanline, PixelCenterRuleOnExactEdges) {
  // Centers exactly on the left/top edges are in, on the right/bottom edges out; a triangle's slanted edge through
  // centers includes them on its left side.
  Counts counts(8, 8);
  counts.scan(Path{{{{1.5, 1.5}, {5.5, 1.5}, {5.5, 5.5}}}}, FillRule::non_zero, false);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool expected = y >= 1 && y < 5 && x >= y && x < 5;
      EXPECT_EQ(counts.writes(x, y), expected ? 1 : 0) << x << "," << y;
    }
}

TEST(Scanline, TiesOnSlopesThatAreNotBinaryFractionsStayExact) {
  // A star whose edges have slope dx/dy = 1/3: accumulating x += 1/3 per scanline drifts, and the center (51.5, 9.5),
  // exactly on the right edge from (50, 5) to (61, 38), would be filled. Row 9 spans [48.5, 51.5): pixels 48..50.
  Counts counts(100, 50);
  counts.scan(Path{{{{50, 5}, {61, 38}, {33, 17}, {67, 17}, {39, 38}}}}, FillRule::non_zero, false);
  for (int x = 40; x < 60; ++x) EXPECT_EQ(counts.writes(x, 9), x >= 48 && x <= 50 ? 1 : 0) << x;
}

TEST(Scanline, AntialiasedCoverageMatchesSupersampledOracle) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 6; ++trial) {
    const Path path = test::random_polygon_with_holes(rng, 48, 40);
    for (const FillRule rule : {FillRule::non_zero, FillRule::even_odd}) {
      Counts counts(48, 40);
      counts.scan(path, rule, true);
      const std::vector<double> oracle = test::supersampled_coverage(path, rule, 48, 40, 64);
      double max_err = 0;
      for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 48; ++x)
          max_err = std::max(max_err, std::fabs(counts.coverage(x, y) - oracle[size_t(y * 48 + x)]));
      EXPECT_LT(max_err, 0.02);
    }
  }
}

TEST(Scanline, SpansOfARowAreOrderedDisjointAndInside) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-30, 230);
  Path path;
  for (int i = 0; i < 40; ++i) path.contours.resize(1), path.contours[0].push_back({u(rng), u(rng)});
  for (const bool aa : {false, true}) {
    std::vector<int> last_end(200, -1);
    bool ok = true;
    scan_path(path, FillRule::even_odd, 200, 200, aa, [&](int y, int x0, int x1, const float*) {
      ok = ok && y >= 0 && y < 200 && x0 >= 0 && x0 < x1 && x1 <= 200 && x0 >= last_end[size_t(y)];
      last_end[size_t(y)] = x1;
    });
    EXPECT_TRUE(ok);
  }
}

TEST(Scanline, IdenticalForAnyThreadCount) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(-10, 530);
  Path path;
  path.contours.emplace_back();
  for (int i = 0; i < 300; ++i) path.contours[0].push_back({u(rng), u(rng)});
  for (const bool aa : {false, true}) {
    Counts one(512, 512), all(512, 512);
    {
      ThreadLimit limit(1);
      one.scan(path, FillRule::non_zero, aa);
    }
    all.scan(path, FillRule::non_zero, aa);
    EXPECT_TRUE(std::equal(one.coverage.pixels().begin(), one.coverage.pixels().end(), all.coverage.pixels().begin()));
  }
}

TEST(Scanline, DegenerateInputAddsNothing) {
  Counts counts(10, 10);
  counts.scan(Path{{{{1, 1}, {5, 5}}, {}, {{1, 1}, {9, 1}, {NAN, 9}}}}, FillRule::non_zero, false);
  counts.scan(Path{{{{1, 1}, {9, 1}, {5, 1}}}}, FillRule::non_zero, true);
  for (int v : counts.writes.pixels()) EXPECT_EQ(v, 0);
}

}  // namespace
}  // namespace tessera
