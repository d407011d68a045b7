#include "tessera/subdiv/subdivide.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "fixtures.hpp"
#include "osd_reference.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/subdiv/topology.hpp"

namespace tessera {
namespace {

using test::cube;

PolyMesh fan_triangulated(const PolyMesh& mesh) {
  PolyMesh out;
  out.positions = mesh.positions;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (uint32_t i = 1; i + 1 < face.size(); ++i) out.add_face({face[0], face[i], face[i + 1]});
  }
  return out;
}

long euler_characteristic(const PolyMesh& mesh) {
  const TopologyTables t(mesh.face_offsets, mesh.face_vertices, mesh.vertex_count());
  return long(t.vertex_count()) - long(t.edge_count()) + long(t.face_count());
}

// ---------------------------------------------------------------------------------------------------------------
// Worked by hand from the notes

TEST(CatmullClark, CubeCornerFollowsTheNotesVertexRuleWithNeighbourEnds) {
  // Corner (1,1,1), k = 3: neighbours' mean R = (1/3,1/3,1/3), face points' mean F = (1/3,1/3,1/3).
  // The notes' v' = (E + F + (k-2) v)/k with E = mean of the neighbours (edge ends) gives 5/9; reading E as the mean
  // of the edge midpoints (2/3 each) would give 2/3. The textbook (F + 2 Rmid + (k-3) v)/k also gives 5/9.
  const PolyMesh out = catmull_clark_subdivide(cube());
  const Vec3 corner = out.positions[6];
  EXPECT_NEAR(corner.x, 5.0 / 9.0, 1e-15);
  EXPECT_NEAR(corner.y, 5.0 / 9.0, 1e-15);
  EXPECT_NEAR(corner.z, 5.0 / 9.0, 1e-15);
  // Face point of the top face and edge point of edge 4-5: (v0 + v1 + f0 + f1)/4.
  EXPECT_EQ(out.positions[8 + 1], Vec3(0, 0, 1));
  const PolyMesh c = cube();
  const TopologyTables t(c.face_offsets, c.face_vertices, 8);
  const uint32_t e = t.find_edge(4, 5);
  const Vec3 expected = (Vec3(-1, -1, 1) + Vec3(1, -1, 1) + Vec3(0, 0, 1) + Vec3(0, -1, 0)) / 4.0;
  EXPECT_EQ(out.positions[8 + 6 + e], expected);
}

TEST(CatmullClark, SharpCreaseVertexRule) {
  // Top ring of the cube infinitely sharp: vertex 6 (crease through 5 and 7 only) moves to (6v + v1 + v2)/8 and
  // the crease edge points are midpoints.
  PolyMesh m = cube();
  m.creases = {{4, 5, 10.0f}, {5, 6, 10.0f}, {6, 7, 10.0f}, {7, 4, 10.0f}};
  const PolyMesh out = catmull_clark_subdivide(m);
  const Vec3 expected = (6.0 * Vec3(1, 1, 1) + Vec3(1, -1, 1) + Vec3(-1, 1, 1)) / 8.0;
  EXPECT_NEAR(glm::distance(out.positions[6], expected), 0.0, 1e-15);
  const TopologyTables t(m.face_offsets, m.face_vertices, 8);
  EXPECT_EQ(out.positions[14 + t.find_edge(5, 6)], Vec3(1, 0, 1));
  // The halves of the tagged edges carry the sharpness on.
  EXPECT_EQ(out.creases.size(), 8u);
  for (const EdgeCrease& c : out.creases) EXPECT_EQ(c.sharpness, 10.0f);
}

TEST(Loop, NotesRulesOnTheIcosahedron) {
  // Valence 5: beta = 3/(8*5) (the notes); edge points 3/8 (v1 + v2) + 1/8 (v3 + v4).
  const PolyMesh ico = test::icosahedron();
  const PolyMesh out = loop_subdivide(ico);
  const TopologyTables t(ico.face_offsets, ico.face_vertices, ico.vertex_count());
  Vec3 ring(0.0);
  for (uint32_t i = 0; i < 5; ++i) ring += ico.positions[t.ring_neighbor(0, i)];
  const double beta = 3.0 / 40.0;
  EXPECT_NEAR(glm::distance(out.positions[0], (1.0 - 5.0 * beta) * ico.positions[0] + beta * ring), 0.0, 1e-14);
  const auto [a, b] = t.edge_vertices(0);
  const auto k = t.edge_corners(0);
  const Vec3 c = ico.positions[t.corner_vertex(t.prev_corner(k[0]))],
             d = ico.positions[t.corner_vertex(t.prev_corner(k[1]))];
  EXPECT_NEAR(glm::distance(out.positions[12], 0.375 * (ico.positions[a] + ico.positions[b]) + 0.125 * (c + d)), 0.0,
              1e-14);
}

TEST(Midpoint, KeepsVerticesAndSplitsAtMidpoints) {
  const PolyMesh ico = test::icosahedron();
  const PolyMesh tri = midpoint_subdivide(ico);
  EXPECT_EQ(tri.face_count(), 80u);
  EXPECT_TRUE(tri.is_triangle_mesh());
  for (size_t v = 0; v < ico.vertex_count(); ++v) EXPECT_EQ(tri.positions[v], ico.positions[v]);
  const TopologyTables t(ico.face_offsets, ico.face_vertices, ico.vertex_count());
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const auto [a, b] = t.edge_vertices(e);
    EXPECT_EQ(tri.positions[12 + e], 0.5 * (ico.positions[a] + ico.positions[b]));
  }
  const PolyMesh quads = midpoint_subdivide(test::house());
  EXPECT_EQ(quads.face_count(), 5u + 5u * 4u + 5u * 3u);
  EXPECT_EQ(quads.face_vertices.size(), 4 * quads.face_count());
}

TEST(GeodesicSphere, CountsAndRadius) {
  for (int level = 0; level <= 4; ++level) {
    const PolyMesh ico = geodesic_sphere(test::icosahedron(), level);
    const PolyMesh oct = geodesic_sphere(test::octahedron(), level);
    EXPECT_EQ(ico.face_count(), 20u << (2 * level));
    EXPECT_EQ(ico.vertex_count(), 10u * (1u << (2 * level)) + 2u);
    EXPECT_EQ(oct.face_count(), 8u << (2 * level));
    EXPECT_EQ(oct.vertex_count(), 4u * (1u << (2 * level)) + 2u);
    for (const Vec3& p : ico.positions) EXPECT_NEAR(glm::length(p), 1.0, 1e-14);
    for (const Vec3& p : oct.positions) EXPECT_NEAR(glm::length(p), 1.0, 1e-14);
    EXPECT_EQ(euler_characteristic(ico), 2);
  }
  EXPECT_THROW(geodesic_sphere(cube(), 1), InvalidInput);
}

// ---------------------------------------------------------------------------------------------------------------
// Invariants

TEST(Subdivide, FaceCountsPerLevel) {
  for (int level = 1; level <= 3; ++level) {
    EXPECT_EQ(catmull_clark_subdivide(cube(), level).face_count(), 6u << (2 * level));
    EXPECT_EQ(loop_subdivide(test::icosahedron(), level).face_count(), 20u << (2 * level));
    EXPECT_EQ(catmull_clark_subdivide(test::house(), level).face_count(), 40u << (2 * (level - 1)));
  }
  EXPECT_EQ(loop_subdivide(test::icosahedron()).face_count(), 80u);
}

TEST(Subdivide, EulerCharacteristicIsPreserved) {
  const struct {
    PolyMesh mesh;
    SubdivisionScheme scheme;
    long chi;
  } cases[] = {{cube(), SubdivisionScheme::catmull_clark, 2},
               {test::grid(4, 3), SubdivisionScheme::catmull_clark, 1},
               {test::torus(12, 8), SubdivisionScheme::catmull_clark, 0},
               {test::house(), SubdivisionScheme::midpoint, 2},
               {test::icosahedron(), SubdivisionScheme::loop, 2},
               {fan_triangulated(test::grid(3, 3)), SubdivisionScheme::loop, 1},
               {test::torus(10, 6, true), SubdivisionScheme::loop, 0}};
  for (const auto& c : cases) {
    EXPECT_EQ(euler_characteristic(c.mesh), c.chi);
    for (int level = 1; level <= 3; ++level)
      EXPECT_EQ(euler_characteristic(subdivide(c.mesh, {.scheme = c.scheme, .levels = level})), c.chi);
  }
}

TEST(Subdivide, LevelsComposeThroughTheCarriedTags) {
  for (float s : {0.5f, 1.5f, 2.5f, 10.0f}) {
    const PolyMesh m = test::creased_cube(s);
    const PolyMesh two = catmull_clark_subdivide(m, 3);
    const PolyMesh one = catmull_clark_subdivide(catmull_clark_subdivide(catmull_clark_subdivide(m)));
    EXPECT_EQ(two.positions, one.positions);
    EXPECT_EQ(two.face_vertices, one.face_vertices);
  }
}

// A tag given twice counts once, with its last sharpness (as a later line of an OBJ file overrides an earlier one).
TEST(Subdivide, RepeatedTagsCountOnceWithTheLastSharpness) {
  const PolyMesh once = test::creased_cube(2.0f);
  PolyMesh twice = once;
  twice.creases.insert(twice.creases.begin(), {5, 4, 0.5f});
  twice.corners.insert(twice.corners.begin(), {0, 1.0f});
  for (int levels : {1, 2}) {
    const PolyMesh a = catmull_clark_subdivide(once, levels), b = catmull_clark_subdivide(twice, levels);
    EXPECT_EQ(a.positions, b.positions);
    ASSERT_EQ(a.creases.size(), b.creases.size());
    for (size_t i = 0; i < a.creases.size(); ++i) {
      EXPECT_EQ(a.creases[i].v0, b.creases[i].v0);
      EXPECT_EQ(a.creases[i].v1, b.creases[i].v1);
      EXPECT_EQ(a.creases[i].sharpness, b.creases[i].sharpness);
    }
    ASSERT_EQ(a.corners.size(), b.corners.size());
    for (size_t i = 0; i < a.corners.size(); ++i) EXPECT_EQ(a.corners[i].sharpness, b.corners[i].sharpness);
  }
}

TEST(Subdivide, IdenticalForAnyThreadCount) {
  const PolyMesh m = test::torus(40, 30);
  PolyMesh serial, parallel;
  {
    const ThreadLimit one(1);
    serial = catmull_clark_subdivide(m, 2);
  }
  {
    const ThreadLimit two(2);
    parallel = catmull_clark_subdivide(m, 2);
  }
  EXPECT_EQ(serial.positions, parallel.positions);
  EXPECT_EQ(serial.face_vertices, parallel.face_vertices);
}

TEST(Subdivide, InterpolatesUvsAndColorsWithTheSameMasks) {
  PolyMesh m = test::grid(3, 3);
  for (const Vec3& p : m.positions) {
    m.uvs.push_back({p.x, p.y});
    m.colors.push_back(p);
  }
  const PolyMesh out = catmull_clark_subdivide(m, 2);
  ASSERT_EQ(out.uvs.size(), out.vertex_count());
  for (size_t v = 0; v < out.vertex_count(); ++v) {
    EXPECT_NEAR(out.uvs[v].x, out.positions[v].x, 1e-12);
    EXPECT_NEAR(glm::distance(out.colors[v], out.positions[v]), 0.0, 1e-12);
  }
}

// A uv-mapped plane: midpoint subdivision keeps positions linear, and linear face-varying uvs stay the same linear
// function of them, at every corner of every level.
TEST(Subdivide, FaceVaryingUvsOfAPlaneStayLinear) {
  for (bool triangles : {false, true}) {
    PolyMesh m = triangles ? fan_triangulated(test::grid(3, 2)) : test::grid(3, 2);
    for (uint32_t v : m.face_vertices) m.corner_uvs.emplace_back(0.25 * m.positions[v].x, 0.5 * m.positions[v].y);
    const PolyMesh out = subdivide(m, {.scheme = SubdivisionScheme::midpoint, .levels = 3});
    ASSERT_EQ(out.corner_uvs.size(), out.face_vertices.size());
    for (size_t c = 0; c < out.face_vertices.size(); ++c) {
      const Vec3& p = out.positions[out.face_vertices[c]];
      EXPECT_NEAR(out.corner_uvs[c].x, 0.25 * p.x, 1e-12);
      EXPECT_NEAR(out.corner_uvs[c].y, 0.5 * p.y, 1e-12);
    }
  }
}

// Face-varying uvs with a seam at every edge (each face its own uv square or triangle) against OpenSubdiv's
// FVAR_LINEAR_ALL: the multiset of (corner position, corner uv) of the refined faces must agree.
TEST(Subdivide, FaceVaryingUvsMatchOpenSubdivLinearInterpolation) {
  const auto with_uvs = [](PolyMesh m) {
    for (size_t f = 0; f < m.face_count(); ++f)
      for (uint32_t j = 0; j < m.face_size(f); ++j) {
        const double a = 2 * kPi * j / m.face_size(f);
        m.corner_uvs.emplace_back(0.1 * double(f) + 0.05 * std::cos(a), 0.3 + 0.05 * std::sin(a));
      }
    return m;
  };
  const struct {
    PolyMesh mesh;
    SubdivisionOptions options;
  } cases[] = {
      {with_uvs(cube()), {.levels = 2}},
      {with_uvs(test::house()), {.levels = 2}},
      {with_uvs(test::grid(3, 3)), {.levels = 3}},
      {with_uvs(test::icosahedron()),
       {.scheme = SubdivisionScheme::loop, .levels = 2, .loop_weights = LoopWeights::loop}},
  };
  const auto sorted = [](std::vector<test::CornerSample> corners) {
    const auto key = [](const test::CornerSample& c) {
      return std::array<double, 5>{std::round(c.position.x * 1e6), std::round(c.position.y * 1e6),
                                   std::round(c.position.z * 1e6), c.uv.x, c.uv.y};
    };
    std::sort(corners.begin(), corners.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    return corners;
  };
  for (const auto& c : cases) {
    const PolyMesh out = subdivide(c.mesh, c.options);
    std::vector<test::CornerSample> ours;
    for (size_t k = 0; k < out.face_vertices.size(); ++k)
      ours.push_back({out.positions[out.face_vertices[k]], out.corner_uvs[k]});
    const std::vector<test::CornerSample> reference = sorted(test::osd_refine_face_varying(c.mesh, c.options));
    ours = sorted(ours);
    ASSERT_EQ(ours.size(), reference.size());
    for (size_t k = 0; k < ours.size(); ++k) {
      EXPECT_NEAR(glm::distance(ours[k].position, reference[k].position), 0.0, 1e-9) << k;
      EXPECT_NEAR(glm::distance(ours[k].uv, reference[k].uv), 0.0, 1e-12) << k;
    }
  }
}

TEST(Subdivide, RejectsBadInput) {
  EXPECT_THROW(loop_subdivide(cube()), InvalidInput);
  EXPECT_THROW(subdivide(cube(), {.levels = -1}), InvalidInput);
  EXPECT_THROW(subdivide(cube(), {.levels = 13}), InvalidInput);
  PolyMesh bad_crease = cube();
  bad_crease.creases = {{0, 6, 1.0f}};
  EXPECT_THROW(catmull_clark_subdivide(bad_crease), InvalidInput);
  PolyMesh fin = cube();
  fin.positions.push_back({0, 0, 3});
  fin.add_face({4, 5, 8});  // a third face on edge 4-5
  EXPECT_THROW(catmull_clark_subdivide(fin), TopologyError);
  PolyMesh short_uvs = cube();
  short_uvs.corner_uvs.resize(3);
  EXPECT_THROW(catmull_clark_subdivide(short_uvs), InvalidInput);
}

// ---------------------------------------------------------------------------------------------------------------
// Reference: OpenSubdiv 3.5 uniform refinement, levels 1-3, within 1e-6 of the bounding box diagonal

struct ReferenceCase {
  std::string name;
  PolyMesh mesh;
  SubdivisionOptions options;
};

void PrintTo(const ReferenceCase& c, std::ostream* os) { *os << c.name; }

class MatchesOpenSubdiv : public ::testing::TestWithParam<ReferenceCase> {};

TEST_P(MatchesOpenSubdiv, Levels1To3) {
  const ReferenceCase& c = GetParam();
  SubdivisionOptions options = c.options;
  options.levels = 3;
  const test::OsdRefinement reference = test::osd_refine(c.mesh, options);
  const double diagonal = test::bbox_diagonal(c.mesh.positions);
  options.levels = 1;
  PolyMesh mesh = c.mesh;
  for (int level = 1; level <= 3; ++level) {
    mesh = subdivide(mesh, options);
    ASSERT_EQ(mesh.face_count(), reference.face_count(level)) << "level " << level;
    const double deviation =
        test::point_set_distance(mesh.positions, reference.positions(level), 1e-3 * diagonal) / diagonal;
    std::printf("[reference] %-28s level %d: %zu vertices, max deviation %.2e of the diagonal\n", c.name.c_str(), level,
                mesh.vertex_count(), deviation);
    EXPECT_LE(deviation, 1e-6) << "level " << level;
  }
}

std::vector<ReferenceCase> catmark_cases() {
  std::vector<ReferenceCase> cases = {
      {"cube", cube(), {}},
      {"cube_edge_and_corner", cube(), {.boundary = BoundaryInterpolation::edge_and_corner}},
      {"grid_edge_only", test::grid(6, 5), {}},
      {"grid_edge_and_corner", test::grid(6, 5), {.boundary = BoundaryInterpolation::edge_and_corner}},
      {"mixed_tri_quad_pentagon", test::house(), {}},
      {"mixed_tri_smooth", test::house(), {.triangles = TriangleSubdivision::smooth}},
      {"torus_10k_quads", test::torus(100, 100), {}},
  };
  for (float s : {0.5f, 1.0f, 1.5f, 2.0f, 3.0f, 10.0f})
    cases.push_back({"creased_cube_s" + std::to_string(int(s * 10)), test::creased_cube(s), {}});
  for (float s : {0.5f, 1.5f, 2.5f}) {
    PolyMesh m = test::creased_cube(s);
    m.creases.push_back({5, 1, 0.25f + s});  // differing sharpness around vertex 5
    cases.push_back({"chaikin_cube_s" + std::to_string(int(s * 10)), m, {.crease_method = CreaseMethod::chaikin}});
  }
  PolyMesh creased_grid = test::grid(6, 5);
  creased_grid.creases = {{8, 9, 1.5f}, {9, 10, 1.5f}, {10, 11, 2.5f}, {16, 23, 0.7f}};
  creased_grid.corners = {{24, 2.0f}};
  cases.push_back({"creased_grid", creased_grid, {.boundary = BoundaryInterpolation::edge_and_corner}});
  return cases;
}

std::vector<ReferenceCase> loop_cases() {
  const SubdivisionOptions loop{.scheme = SubdivisionScheme::loop, .loop_weights = LoopWeights::loop};
  SubdivisionOptions loop_corner = loop;
  loop_corner.boundary = BoundaryInterpolation::edge_and_corner;
  PolyMesh creased = test::icosahedron();
  const TopologyTables t(creased.face_offsets, creased.face_vertices, creased.vertex_count());
  for (uint32_t i = 0; i < t.ring_edge_count(0); ++i) creased.creases.push_back({0, t.ring_neighbor(0, i), 1.5f});
  creased.creases.push_back({t.edge_vertices(20)[0], t.edge_vertices(20)[1], 10.0f});
  creased.corners = {{5, 0.5f}};
  return {
      {"loop_icosahedron", test::icosahedron(), loop},
      {"loop_octahedron", test::octahedron(), loop},
      {"loop_grid_edge_only", fan_triangulated(test::grid(5, 4)), loop},
      {"loop_grid_edge_and_corner", fan_triangulated(test::grid(5, 4)), loop_corner},
      {"loop_creased_icosahedron", creased, loop},
      {"loop_torus_12k_triangles", test::torus(80, 80, true), loop},
  };
}

INSTANTIATE_TEST_SUITE_P(CatmullClark, MatchesOpenSubdiv, ::testing::ValuesIn(catmark_cases()),
                         [](const auto& test_case) { return test_case.param.name; });
INSTANTIATE_TEST_SUITE_P(Loop, MatchesOpenSubdiv, ::testing::ValuesIn(loop_cases()),
                         [](const auto& test_case) { return test_case.param.name; });

TEST(Loop, NotesBetaDiffersFromOpenSubdivOnlyAtExtraordinaryVertices) {
  // Valence 5 (icosahedron): Warren's beta 3/40 vs Loop's 0.0797...; valence 6 (torus): both 1/16.
  const SubdivisionOptions warren{.scheme = SubdivisionScheme::loop, .levels = 1};
  const PolyMesh ico = test::icosahedron();
  const double d_ico =
      test::point_set_distance(subdivide(ico, warren).positions, test::osd_refine(ico, warren).positions(1), 1.0);
  EXPECT_GT(d_ico, 1e-3);
  const PolyMesh torus = test::torus(20, 20, true);  // all valence 6
  const double d_torus =
      test::point_set_distance(subdivide(torus, warren).positions, test::osd_refine(torus, warren).positions(1), 1.0);
  EXPECT_LT(d_torus, 1e-12);
}

}  // namespace
}  // namespace tessera
