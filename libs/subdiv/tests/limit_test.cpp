#include "tessera/subdiv/limit.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "fixtures.hpp"
#include "osd_reference.hpp"
#include "tessera/core/error.hpp"
#include "tessera/subdiv/topology.hpp"

namespace tessera {
namespace {

struct LimitCase {
  std::string name;
  PolyMesh mesh;
  SubdivisionOptions options;  // levels: the level the limit is taken at
};

void PrintTo(const LimitCase& c, std::ostream* os) { *os << c.name; }

class LimitMatchesOpenSubdiv : public ::testing::TestWithParam<LimitCase> {};

// Limit positions and normals at the same refinement level as OpenSubdiv's PrimvarRefiner::Limit. Normals are
// compared except at interior creases and corners, where the normal depends on which side of the crease the ring
// starts (a crease has two normals; OpenSubdiv picks the side after its first sharp edge).
TEST_P(LimitMatchesOpenSubdiv, PositionsAndNormals) {
  const LimitCase& c = GetParam();
  const test::OsdRefinement reference = test::osd_refine(c.mesh, c.options);
  const int level = c.options.levels;
  std::vector<test::OsdPoint> position(reference.levels[level].size()), tan1(position.size()), tan2(position.size());
  const test::OsdPoint* src = reference.levels[level].data();
  test::OsdPoint *dst = position.data(), *t1 = tan1.data(), *t2 = tan2.data();
  OpenSubdiv::Far::PrimvarRefinerReal<double>(*reference.refiner).Limit(src, dst, t1, t2);

  const PolyMesh refined = subdivide(c.mesh, c.options);
  const LimitSurface mine = limit_surface(refined, c.options);
  std::vector<Vec3> osd_positions;
  for (const test::OsdPoint& p : position) osd_positions.push_back(p.p);
  const double diagonal = test::bbox_diagonal(c.mesh.positions);
  const double deviation = test::point_set_distance(mine.positions, osd_positions, 1e-3 * diagonal) / diagonal;
  EXPECT_LE(deviation, 1e-6);

  std::set<uint32_t> tagged;
  for (const EdgeCrease& e : refined.creases) tagged.insert({e.v0, e.v1});
  for (const VertexCorner& v : refined.corners) tagged.insert(v.v);
  const TopologyTables t(refined.face_offsets, refined.face_vertices, refined.vertex_count());
  const std::vector<int64_t> match = test::nearest_points(mine.positions, osd_positions, 1e-3 * diagonal);
  double worst_normal = 0.0;
  size_t compared = 0;
  for (uint32_t v = 0; v < refined.vertex_count(); ++v) {
    if (tagged.count(v) && !t.is_boundary_vertex(v)) continue;
    ASSERT_GE(match[v], 0);
    const Vec3 n = glm::normalize(glm::cross(tan1[size_t(match[v])].p, tan2[size_t(match[v])].p));
    worst_normal = std::max(worst_normal, glm::distance(n, mine.normals[v]));
    ++compared;
  }
  std::printf("[limit] %-26s level %d: position deviation %.2e of the diagonal, normal deviation %.2e (%zu normals)\n",
              c.name.c_str(), level, deviation, worst_normal, compared);
  EXPECT_LE(worst_normal, 1e-6);
}

std::vector<LimitCase> limit_cases() {
  const SubdivisionOptions loop{.scheme = SubdivisionScheme::loop, .levels = 1, .loop_weights = LoopWeights::loop};
  PolyMesh tri_grid;
  const PolyMesh g = test::grid(4, 4);
  tri_grid.positions = g.positions;
  for (size_t f = 0; f < g.face_count(); ++f) {
    const auto q = g.face(f);
    tri_grid.add_face({q[0], q[1], q[2]});
    tri_grid.add_face({q[0], q[2], q[3]});
  }
  SubdivisionOptions loop2 = loop;
  loop2.levels = 2;
  SubdivisionOptions loop_corner = loop2;
  loop_corner.boundary = BoundaryInterpolation::edge_and_corner;
  return {
      {"cube_level1", test::cube(), {.levels = 1}},
      {"cube_level2", test::cube(), {.levels = 2}},
      {"mixed_level2", test::house(), {.levels = 2}},
      {"grid_edge_only", test::grid(5, 4), {.levels = 2}},
      {"grid_edge_and_corner", test::grid(5, 4), {.levels = 2, .boundary = BoundaryInterpolation::edge_and_corner}},
      {"creased_cube_s3", test::creased_cube(3.0f), {.levels = 2}},
      {"creased_cube_inf", test::creased_cube(10.0f), {.levels = 2}},
      {"loop_icosahedron_level0",
       test::icosahedron(),
       {.scheme = SubdivisionScheme::loop, .levels = 0, .loop_weights = LoopWeights::loop}},
      {"loop_icosahedron_level2", test::icosahedron(), loop2},
      {"loop_grid_edge_only", tri_grid, loop2},
      {"loop_grid_edge_and_corner", tri_grid, loop_corner},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, LimitMatchesOpenSubdiv, ::testing::ValuesIn(limit_cases()),
                         [](const auto& test_case) { return test_case.param.name; });

// Independent of OpenSubdiv: the limit of a vertex is where its refined copies converge (vertex v keeps index v).
TEST(Limit, IsWhereRefinementConverges) {
  for (const auto& [mesh, scheme] :
       {std::pair{test::icosahedron(), SubdivisionScheme::loop},
        std::pair{catmull_clark_subdivide(test::house()), SubdivisionScheme::catmull_clark}}) {
    const SubdivisionOptions options{.scheme = scheme};  // the notes' Loop weights
    const LimitSurface limit = limit_surface(mesh, options);
    double previous = 1e300;
    for (int level = 2; level <= 6; level += 2) {
      const PolyMesh refined = subdivide(mesh, {.scheme = scheme, .levels = level});
      double worst = 0.0;
      for (size_t v = 0; v < mesh.vertex_count(); ++v)
        worst = std::max(worst, glm::distance(refined.positions[v], limit.positions[v]));
      EXPECT_LT(worst, previous / 4.0) << "level " << level;
      previous = worst;
    }
    EXPECT_LT(previous, 1e-3);
  }
}

TEST(Limit, SphereNormalsPointOutward) {
  const PolyMesh mesh = loop_subdivide(test::icosahedron(), 2);
  const LimitSurface limit = limit_surface(mesh, {.scheme = SubdivisionScheme::loop});
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_NEAR(glm::length(limit.normals[v]), 1.0, 1e-12);
    EXPECT_GT(glm::dot(limit.normals[v], glm::normalize(limit.positions[v])), 0.95);
  }
}

TEST(Limit, RejectsWrongFaces) {
  EXPECT_THROW(limit_surface(test::house(), {}), InvalidInput);
  EXPECT_THROW(limit_surface(test::cube(), {.scheme = SubdivisionScheme::loop}), InvalidInput);
  EXPECT_THROW(limit_surface(test::cube(), {.scheme = SubdivisionScheme::midpoint}), InvalidInput);
}

// Issue 24, class 2: a cube with coordinates of 1e308 (finite) gave NaN vertices (4 corners summed to infinity, then
// inf - inf), and one of 1e-300 zero normals (the tangents' cross product underflowed). Subdivision and limit masks
// are affine, so the result must be the unit mesh's, scaled: positions times the scale, the same normals.
TEST(Limit, HugeAndTinyCoordinatesGiveTheScaledResult) {
  const struct {
    PolyMesh mesh;
    SubdivisionScheme scheme;
  } cases[] = {{test::cube(), SubdivisionScheme::catmull_clark}, {test::icosahedron(), SubdivisionScheme::loop}};
  for (const auto& c : cases) {
    const SubdivisionOptions options{.scheme = c.scheme, .levels = 2};
    const PolyMesh unit = subdivide(c.mesh, options);
    const LimitSurface unit_limit = limit_surface(unit, options);
    for (double scale : {1e308, -1e308, 1e-300, 3e200}) {
      PolyMesh scaled = c.mesh;
      for (Vec3& p : scaled.positions) p *= scale;
      const PolyMesh refined = subdivide(scaled, options);
      const LimitSurface limit = limit_surface(refined, options);
      ASSERT_EQ(refined.vertex_count(), unit.vertex_count());
      for (size_t v = 0; v < unit.vertex_count(); ++v) {
        for (int a = 0; a < 3; ++a) {
          EXPECT_NEAR(refined.positions[v][a] / scale, unit.positions[v][a], 1e-12) << scale << " vertex " << v;
          EXPECT_NEAR(limit.positions[v][a] / scale, unit_limit.positions[v][a], 1e-12) << scale << " vertex " << v;
        }
        // A negative scale negates both tangents, which leaves their cross product as it is.
        EXPECT_NEAR(glm::distance(limit.normals[v], unit_limit.normals[v]), 0.0, 1e-12) << scale << " vertex " << v;
      }
    }
  }
}

// Issue 24, class 2: a result that is not finite is an error, never returned.
TEST(Limit, NonFiniteInputIsRefusedNotPropagated) {
  PolyMesh mesh = test::cube();
  mesh.positions[3].y = INFINITY;
  EXPECT_THROW(subdivide(mesh, {.scheme = SubdivisionScheme::catmull_clark, .levels = 1}), InvalidInput);
  PolyMesh quads = subdivide(test::cube(), {.scheme = SubdivisionScheme::catmull_clark, .levels = 1});
  quads.positions[5].x = NAN;
  EXPECT_THROW(limit_surface(quads, {.scheme = SubdivisionScheme::catmull_clark}), InvalidInput);
}

}  // namespace
}  // namespace tessera
