#include "tessera/volume/marching_cubes.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "reference.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/volume/mc_table.hpp"
#include "tessera/volume/procedural.hpp"

namespace tessera {
namespace {

using testing::parse_key_values;
using testing::run_reference;
using testing::write_temp_field;

/// Every undirected edge's face count.
std::map<std::pair<uint32_t, uint32_t>, int> edge_use(const PolyMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> use;
  for (size_t f = 0; f < m.face_count(); ++f) {
    const auto face = m.face(f);
    for (size_t i = 0; i < face.size(); ++i) {
      const uint32_t a = face[i], b = face[(i + 1) % face.size()];
      ++use[{std::min(a, b), std::max(a, b)}];
    }
  }
  return use;
}

/// True when every edge has exactly two faces and the topology report says closed, manifold and oriented.
bool closed_manifold(const PolyMesh& m) {
  for (const auto& [edge, count] : edge_use(m))
    if (count != 2) return false;
  const auto report = analyze_topology(m);
  return report.closed() && report.manifold() && report.oriented();
}

/// A 2x2x2 cube of corner values embedded in a 4^3 volume of outside values (so the surface is closed).
Volume<float> embedded_cube(const std::array<float, 8>& values, float outside) {
  Volume<float> v(glm::ivec3(4), outside);
  for (int c = 0; c < 8; ++c) {
    const auto p = mc::corners()[size_t(c)];
    v(1 + p.x, 1 + p.y, 1 + p.z) = values[size_t(c)];
  }
  return v;
}

/// Random corner values for a case: inside corners in [0.5, 1], outside in [0, 0.5).
std::array<float, 8> random_corners(int cube_case, Rng& rng) {
  std::array<float, 8> v{};
  for (int c = 0; c < 8; ++c)
    v[size_t(c)] = (cube_case >> c) & 1 ? 0.5f + 0.5f * rng.uniform() : 0.4995f * rng.uniform();
  return v;
}

TEST(MarchingCubesTable, SeparatesInsideCornersOnAmbiguousFaces) {
  // Case 5 (corners 0 and 2, diagonal on face z=0) gives two separate triangles.
  EXPECT_EQ(mc::classic_table()[5].triangles.size(), 2u);
  EXPECT_EQ(mc::ambiguous_faces(5), 1);
  // Complements have the same edges; a single corner gives one triangle.
  for (int c = 0; c < 256; ++c) {
    std::set<int> edges, complement;
    for (const auto& t : mc::classic_table()[size_t(c)].triangles) edges.insert(t.begin(), t.end());
    for (const auto& t : mc::classic_table()[size_t(255 - c)].triangles) complement.insert(t.begin(), t.end());
    EXPECT_EQ(edges, complement) << "case " << c;
  }
  EXPECT_EQ(mc::classic_table()[1].triangles.size(), 1u);
  EXPECT_EQ(mc::classic_table()[0].triangles.size(), 0u);
  EXPECT_EQ(mc::classic_table()[255].triangles.size(), 0u);
}

TEST(MarchingCubesTable, MatchesVtkOnAll256CasesWithRandomValues) {
  Rng rng(7);
  std::vector<std::array<float, 8>> cubes;
  for (int c = 0; c < 256; ++c) cubes.push_back(random_corners(c, rng));
  const auto path = std::filesystem::temp_directory_path() / fmt::format("tessera_mc_cases_{}.raw", ::getpid());
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(cubes.data()), std::streamsize(cubes.size() * sizeof(cubes[0])));
  }
  const auto ref = run_reference("cases " + path.string());
  std::filesystem::remove(path);
  if (!ref) GTEST_SKIP() << "VTK (python3-vtk9) is not available";
  std::istringstream in(*ref);
  for (int c = 0; c < 256; ++c) {
    size_t tris = 0;
    double area = 0;
    ASSERT_TRUE(in >> tris >> area);
    // The same triangles (as sets of the cube edges their corners lie on) as vtkMarchingCubes, case by case.
    std::set<std::array<int, 3>> theirs, ours;
    for (size_t t = 0; t < tris; ++t) {
      std::array<int, 3> tri{};
      ASSERT_TRUE(in >> tri[0] >> tri[1] >> tri[2]);
      std::sort(tri.begin(), tri.end());
      theirs.insert(tri);
    }
    for (const auto& t : mc::classic_table()[size_t(c)].triangles) {
      std::array<int, 3> tri{t[0], t[1], t[2]};
      std::sort(tri.begin(), tri.end());
      ours.insert(tri);
    }
    EXPECT_EQ(ours, theirs) << "case " << c;
    Volume<float> cube(glm::ivec3(2));
    for (int k = 0; k < 8; ++k) {
      const auto p = mc::corners()[size_t(k)];
      cube(p.x, p.y, p.z) = cubes[size_t(c)][size_t(k)];
    }
    const PolyMesh m = marching_cubes(cube, {.iso = 0.5f});
    EXPECT_EQ(m.face_count(), tris) << "case " << c;
    EXPECT_NEAR(surface_area(m), area, 1e-6 * std::max(area, 1.0)) << "case " << c;
  }
}

TEST(MarchingCubes, SphereIsClosedGenusZeroWithOutwardNormals) {
  const auto v = make_sphere(40, 0.7);
  const PolyMesh m = marching_cubes(v, {});
  EXPECT_TRUE(closed_manifold(m));
  EXPECT_EQ(analyze_topology(m).euler, 2);
  EXPECT_GT(signed_volume(m), 0);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_GT(glm::dot(m.normals[i], glm::normalize(m.positions[i])), 0.99);
    EXPECT_NEAR(glm::length(m.positions[i]), 0.7, 0.01);
  }
}

// Voxels held elsewhere (the Python package's numpy arrays) give the Volume's mesh bit for bit; bad grids are refused.
TEST(MarchingCubes, VoxelGridEqualsTheVolume) {
  auto v = make_sphere(24, 0.6);
  v.set_spacing(Vec3(0.5, 0.75, 1.25));
  v.set_origin(Vec3(-1, 2, 0.5));
  const std::vector<float> copy(v.voxels().begin(), v.voxels().end());
  const PolyMesh a = marching_cubes(v, {.iso = 0.1f, .topological = true});
  const PolyMesh b =
      marching_cubes(VoxelGrid{copy.data(), v.dims(), v.spacing(), v.origin()}, {.iso = 0.1f, .topological = true});
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.face_vertices, b.face_vertices);
  EXPECT_THROW(marching_cubes(VoxelGrid{nullptr, v.dims()}), InvalidInput);
  EXPECT_THROW(marching_cubes(VoxelGrid{copy.data(), {0, 4, 4}}), InvalidInput);
  EXPECT_THROW(marching_cubes(VoxelGrid{copy.data(), v.dims(), Vec3(1, 0, 1)}), InvalidInput);
}

// A volume cut into slabs of cell layers (as `volume isosurface --mpi` cuts it), each extracted from a brick that
// holds its layers and one slice beyond each end, in the whole volume's coordinates: the pieces hold the whole
// mesh's vertices bit for bit (with their normals), the shared planes' vertices twice, and together its triangles.
TEST(MarchingCubes, SlabsOfLayersAreTheWholeMesh) {
  auto v = make_gyroid(30);
  v.set_spacing(Vec3(0.5, 0.75, 1.3));
  v.set_origin(Vec3(-1.1, 2, 0.37));
  for (const bool topological : {false, true}) {
    const MarchingCubesOptions options{.iso = 0.2f, .topological = topological};
    const PolyMesh whole = marching_cubes(v, options);
    std::map<std::array<double, 3>, Vec3> normal_of;
    for (size_t i = 0; i < whole.positions.size(); ++i)
      normal_of[{whole.positions[i].x, whole.positions[i].y, whole.positions[i].z}] = whole.normals[i];
    const auto triangle = [](const PolyMesh& m, size_t f) {
      std::array<std::array<double, 3>, 3> t;
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = m.positions[m.face_vertices[3 * f + size_t(k)]];
        t[size_t(k)] = {p.x, p.y, p.z};
      }
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // same triangle, same orientation
      return t;
    };
    std::multiset<std::array<std::array<double, 3>, 3>> expected, pieces;
    for (size_t f = 0; f < whole.face_count(); ++f) expected.insert(triangle(whole, f));
    const int bounds[] = {0, 7, 8, 19, 29};  // layers of z: 29 cells, one slab a single layer thick
    for (int b = 0; b < 4; ++b) {
      const int z0 = std::max(0, bounds[b] - 1), z1 = std::min(v.dims().z - 1, bounds[b + 1] + 1);
      const VoxelGrid brick{&v(0, 0, z0), {v.dims().x, v.dims().y, z1 - z0 + 1}, v.spacing(), v.origin(), z0};
      MarchingCubesOptions o = options;
      o.first_layer = bounds[b] - z0;
      o.end_layer = bounds[b + 1] - z0;
      const PolyMesh piece = marching_cubes(brick, o);
      for (size_t i = 0; i < piece.positions.size(); ++i) {
        const auto it = normal_of.find({piece.positions[i].x, piece.positions[i].y, piece.positions[i].z});
        ASSERT_NE(it, normal_of.end()) << "slab " << b << " made a vertex the whole mesh lacks";
        EXPECT_EQ(it->second, piece.normals[i]);
      }
      for (size_t f = 0; f < piece.face_count(); ++f) pieces.insert(triangle(piece, f));
    }
    EXPECT_EQ(pieces, expected) << (topological ? "topological" : "classic");
  }
}

// Issue 24, class 2 (fuzzer finding): gradients were floats, so finite values of both signs near float's limit, or
// large values over small spacings, made them inf and the normals NaN (`volume isosurface` wrote them, exit 0). A
// field that varies along x only has the normal (-1, 0, 0) (towards lower values) wherever it is cut.
TEST(MarchingCubes, NormalsAreUnitWhereGradientsOverflowFloat) {
  for (const auto& row : {std::array{0.0f, 1.0f, 3e38f}, std::array{-3e38f, 1.0f, 3e38f}}) {
    Volume<float> v(glm::ivec3(3, 2, 2), 0.0f, Vec3(0.125));
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) v(x, y, z) = row[size_t(x)];
    const PolyMesh m = marching_cubes(v, {.iso = 0.5f});
    const IsoSurface s = extract_iso_surface(v, {.iso = 0.5f});
    ASSERT_GT(m.normals.size(), 0u);
    ASSERT_EQ(s.normals.size(), m.normals.size());
    for (size_t i = 0; i < m.normals.size(); ++i) {
      EXPECT_NEAR(glm::length(m.normals[i]), 1.0, 1e-12) << row[0] << " " << i;
      EXPECT_NEAR(m.normals[i].x, -1.0, 1e-12) << row[0] << " " << i;
      EXPECT_NEAR(glm::length(s.normals[i]), 1.0f, 1e-6f) << row[0] << " " << i;
    }
  }
}

// Issue 24, class 3: the output was allocated whatever its size. Pass 1 counts it exactly, and the budget is checked
// there: three times the arrays' bytes (a PolyMesh: 24-byte positions and normals, 3 indices and an offset per
// triangle; an IsoSurface: 12-byte vectors and 3 indices), refused one byte below and accepted at the bound.
TEST(MarchingCubes, OutputOverTheMemoryBudgetIsRefusedAfterCounting) {
  const auto v = make_sphere(40, 0.7);
  const PolyMesh mesh = marching_cubes(v, {});
  const uint64_t vertices = mesh.positions.size(), triangles = mesh.face_count();
  ASSERT_GT(triangles, 1000u);
  const uint64_t poly_bytes = 3 * (vertices * (24 + 24) + triangles * (12 + 4));
  const uint64_t iso_bytes = 3 * (vertices * (12 + 12) + triangles * 12);
  const uint64_t plain_bytes = 3 * (vertices * 24 + triangles * (12 + 4));  // no normals
  const auto refused = [](uint64_t budget, const auto& run) {
    MemoryBudget::set_limit(budget);
    std::string message = "no error";
    try {
      run();
    } catch (const MemoryBudgetError& e) {
      message = e.what();
    }
    MemoryBudget::set_limit(0);
    return message;
  };
  const std::string what =
      fmt::format("marching cubes: an iso-surface of {} triangles and {} vertices needs about ", triangles, vertices);
  EXPECT_NE(refused(poly_bytes - 1, [&] { marching_cubes(v, {}); }).find(what), std::string::npos);
  EXPECT_EQ(refused(poly_bytes, [&] { marching_cubes(v, {}); }), "no error");
  EXPECT_NE(refused(iso_bytes - 1, [&] { extract_iso_surface(v, {}); }).find(what), std::string::npos);
  EXPECT_EQ(refused(iso_bytes, [&] { extract_iso_surface(v, {}); }), "no error");
  EXPECT_NE(refused(plain_bytes - 1, [&] { marching_cubes(v, {.normals = false}); }).find(what), std::string::npos);
  EXPECT_EQ(refused(plain_bytes, [&] { marching_cubes(v, {.normals = false}); }), "no error");
}

TEST(MarchingCubes, EachCutEdgeGivesOneVertex) {
  const auto v = make_gyroid(24);
  const PolyMesh m = marching_cubes(v, {});
  size_t cut = 0;
  const auto d = v.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const bool a = v(x, y, z) >= 0;
        if (x + 1 < d.x && a != (v(x + 1, y, z) >= 0)) ++cut;
        if (y + 1 < d.y && a != (v(x, y + 1, z) >= 0)) ++cut;
        if (z + 1 < d.z && a != (v(x, y, z + 1) >= 0)) ++cut;
      }
  EXPECT_EQ(m.positions.size(), cut);
  std::set<std::array<double, 3>> distinct;
  for (const auto& p : m.positions) distinct.insert({p.x, p.y, p.z});
  EXPECT_EQ(distinct.size(), m.positions.size());
}

TEST(MarchingCubes, RowsOfAnyLengthGiveEveryCutEdgeAndCellTriangle) {
  // The extractor packs 64 voxels of a row into a word; rows just under, at and over word boundaries are counted
  // against a plain per-voxel oracle: one vertex per cut edge and the table's triangles for every cell.
  Rng rng(17);
  for (int nx : {2, 63, 64, 65, 129}) {
    Volume<float> v(glm::ivec3(nx, 5, 6));
    for (auto& x : v.voxels()) x = rng.uniform() - 0.5f;
    size_t cut = 0, tris = 0;
    const auto d = v.dims();
    const auto in = [&](int x, int y, int z) { return v(x, y, z) >= 0.0f; };
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          if (x + 1 < d.x && in(x, y, z) != in(x + 1, y, z)) ++cut;
          if (y + 1 < d.y && in(x, y, z) != in(x, y + 1, z)) ++cut;
          if (z + 1 < d.z && in(x, y, z) != in(x, y, z + 1)) ++cut;
          if (x + 1 < d.x && y + 1 < d.y && z + 1 < d.z) {
            int cube_case = 0;
            for (int c = 0; c < 8; ++c) {
              const auto p = mc::corners()[size_t(c)];
              cube_case |= int(in(x + p.x, y + p.y, z + p.z)) << c;
            }
            tris += mc::classic_table()[size_t(cube_case)].triangles.size();
          }
        }
    const PolyMesh m = marching_cubes(v, {.slab_layers = 2});
    EXPECT_EQ(m.positions.size(), cut) << "nx " << nx;
    EXPECT_EQ(m.face_count(), tris) << "nx " << nx;
  }
}

TEST(MarchingCubes, IdenticalForAnyThreadCountAndSlabSize) {
  const auto v = make_noise(37, 3);
  PolyMesh one, two;
  {
    ThreadLimit limit(1);
    one = marching_cubes(v, {.iso = 0.05f, .slab_layers = 3});
  }
  {
    ThreadLimit limit(2);
    two = marching_cubes(v, {.iso = 0.05f, .slab_layers = 5});
  }
  EXPECT_EQ(one.positions, two.positions);
  EXPECT_EQ(one.normals, two.normals);
  EXPECT_EQ(one.face_vertices, two.face_vertices);
  const PolyMesh topo1 = marching_cubes(v, {.iso = 0.05f, .topological = true, .slab_layers = 1});
  const PolyMesh topo2 = marching_cubes(v, {.iso = 0.05f, .topological = true, .slab_layers = 64});
  EXPECT_EQ(topo1.positions, topo2.positions);
  EXPECT_EQ(topo1.face_vertices, topo2.face_vertices);
}

TEST(MarchingCubes, IsoSurfaceIsTheMeshInFloatForAnyThreadCount) {
  const auto v = make_noise(37, 3);
  for (const bool topological : {false, true}) {
    const PolyMesh mesh = marching_cubes(v, {.iso = 0.05f, .topological = topological});
    IsoSurface one, two;
    {
      ThreadLimit limit(1);
      one = extract_iso_surface(v, {.iso = 0.05f, .topological = topological, .slab_layers = 3});
    }
    {
      ThreadLimit limit(2);
      two = extract_iso_surface(v, {.iso = 0.05f, .topological = topological, .slab_layers = 5});
    }
    ASSERT_EQ(one.vertex_count(), mesh.positions.size());
    ASSERT_EQ(one.normals.size(), mesh.normals.size());
    ASSERT_GT(one.triangle_count(), 100u);
    EXPECT_TRUE(
        std::equal(one.indices.begin(), one.indices.end(), mesh.face_vertices.begin(), mesh.face_vertices.end()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      ASSERT_EQ(one.positions[i], Vec3f(mesh.positions[i])) << i;
      ASSERT_EQ(one.normals[i], Vec3f(mesh.normals[i])) << i;
    }
    EXPECT_TRUE(one.positions == two.positions);
    EXPECT_TRUE(one.normals == two.normals);
    EXPECT_TRUE(one.indices == two.indices);
    const TriMesh tri = one.to_tri_mesh();
    EXPECT_EQ(tri.triangle_count(), mesh.face_count());
  }
}

TEST(MarchingCubes, SamplesEqualToIsoGiveNoDegenerateTrianglesOrDuplicateVertices) {
  // An integer field where many voxels equal the iso value exactly.
  Volume<float> v(glm::ivec3(12));
  Rng rng(5);
  for (auto& x : v.voxels()) x = float(rng.below(3));  // 0, 1, 2 with iso 1
  for (bool topological : {false, true}) {
    const PolyMesh m = marching_cubes(v, {.iso = 1.0f, .topological = topological});
    ASSERT_GT(m.face_count(), 100u);
    for (size_t f = 0; f < m.face_count(); ++f) {
      const auto t = m.face(f);
      const Vec3 n = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
      EXPECT_GT(glm::length(n), 1e-12) << "face " << f;
    }
    std::set<std::array<double, 3>> distinct;
    for (const auto& p : m.positions) distinct.insert({p.x, p.y, p.z});
    EXPECT_EQ(distinct.size(), m.positions.size());
  }
}

TEST(MarchingCubesTopological, All256CasesWithRandomValuesGiveClosedManifolds) {
  Rng rng(11);
  for (int c = 0; c < 256; ++c)
    for (int trial = 0; trial < 20; ++trial) {
      const auto v = embedded_cube(random_corners(c, rng), 0.0f);
      const PolyMesh m = marching_cubes(v, {.iso = 0.5f, .topological = true});
      ASSERT_TRUE(closed_manifold(m)) << "case " << c << " trial " << trial;
      EXPECT_EQ(m.face_count() == 0, c == 0);
    }
}

TEST(MarchingCubesTopological, RandomFieldsGiveClosedManifolds) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    Volume<float> v = make_noise(20, seed, 6);
    const auto d = v.dims();
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x)
          if (x == 0 || y == 0 || z == 0 || x == d.x - 1 || y == d.y - 1 || z == d.z - 1) v(x, y, z) = -1;
    const PolyMesh m = marching_cubes(v, {.iso = 0.0f, .topological = true});
    ASSERT_GT(m.face_count(), 0u);
    EXPECT_TRUE(closed_manifold(m)) << "seed " << seed;
    EXPECT_GT(signed_volume(m), 0);
  }
}

TEST(MarchingCubes, SphereAreaAndVolumeConvergeQuadratically) {
  // A sphere of radius r voxels: the relative errors fall as 1/r^2 (each doubling of r divides them by about 4).
  std::vector<double> area_error, volume_error;
  for (int r : {6, 12, 24}) {
    const int n = 2 * r + 6;
    const double h = 2.0 / (n - 1), radius = r * h;
    const auto v = make_sphere(n, radius, Vec3(0.37 * h, 0.21 * h, 0.11 * h));
    const PolyMesh m = marching_cubes(v, {});
    area_error.push_back(std::abs(surface_area(m) / (4 * kPi * radius * radius) - 1));
    volume_error.push_back(std::abs(signed_volume(m) / (4.0 / 3.0 * kPi * radius * radius * radius) - 1));
  }
  for (size_t i = 0; i + 1 < area_error.size(); ++i) {
    EXPECT_GT(area_error[i] / area_error[i + 1], 2.5) << i;
    EXPECT_LT(area_error[i] / area_error[i + 1], 6.5) << i;
    EXPECT_GT(volume_error[i] / volume_error[i + 1], 2.5) << i;
    EXPECT_LT(volume_error[i] / volume_error[i + 1], 6.5) << i;
  }
  EXPECT_LT(area_error.back(), 2e-3);
}

struct Field {
  const char* name;
  Volume<float> volume;
  float iso;
};

std::vector<Field> reference_fields() {
  return {{"sphere", make_sphere(48, 0.7), 0.0f},
          {"torus", make_torus(48), 0.0f},
          {"gyroid", make_gyroid(48), 0.0f},
          {"noise", make_noise(48, 9), 0.02f}};
}

/// Area in voxel units (the references get unit spacing).
double voxel_area(const PolyMesh& m, const Volume<float>& v) {
  return surface_area(m) / (v.spacing().x * v.spacing().x);
}

/// "name method" -> {tris, area} from one reference run over all fields (cached), or empty when unavailable.
const std::map<std::string, std::pair<double, double>>& reference_results() {
  static const auto results = [] {
    std::map<std::string, std::pair<double, double>> r;
    const auto list = std::filesystem::temp_directory_path() / fmt::format("tessera_mc_fields_{}.txt", ::getpid());
    std::vector<std::filesystem::path> files;
    {
      std::ofstream out(list);
      for (const auto& f : reference_fields()) {
        files.push_back(write_temp_field(f.volume, f.name));
        const auto d = f.volume.dims();
        out << fmt::format("{} {} {} {} {} {}\n", f.name, files.back().string(), d.x, d.y, d.z, f.iso);
      }
    }
    const auto out = run_reference("fields " + list.string());
    for (const auto& file : files) std::filesystem::remove(file);
    std::filesystem::remove(list);
    if (!out) return r;
    std::istringstream in(*out);
    std::string name, method, tris, area;
    while (in >> name >> method >> tris >> area) {
      const auto kv = parse_key_values(tris + " " + area);
      r[name + " " + method] = {kv.at("tris"), kv.at("area")};
    }
    return r;
  }();
  return results;
}

TEST(MarchingCubesReference, ClassicMatchesVtkAndSkimageLorensen) {
  if (reference_results().empty()) GTEST_SKIP() << "VTK / scikit-image are not available";
  for (const auto& f : reference_fields()) {
    const PolyMesh m = marching_cubes(f.volume, {.iso = f.iso, .normals = false});
    // The same triangles in every case, so the same count and the same area (up to float rounding) on every field.
    const double tolerance = 1e-4;
    for (const char* method : {"vtk", "lorensen"}) {
      const auto [tris, area] = reference_results().at(std::string(f.name) + " " + method);
      EXPECT_EQ(double(m.face_count()), tris) << f.name << " vs " << method;
      EXPECT_NEAR(voxel_area(m, f.volume), area, tolerance * area) << f.name << " vs " << method;
    }
  }
}

TEST(MarchingCubesReference, TopologicalIsCloseToSkimageLewiner) {
  if (reference_results().empty()) GTEST_SKIP() << "scikit-image is not available";
  for (const auto& f : reference_fields()) {
    const PolyMesh m = marching_cubes(f.volume, {.iso = f.iso, .topological = true, .normals = false});
    const auto [tris, area] = reference_results().at(std::string(f.name) + " lewiner");
    // Lewiner's MC33 also resolves interior ambiguities; on the rough noise field the two differ by about 2%.
    const double count_tol = std::string(f.name) == "noise" ? 0.03 : 0.01;
    const double area_tol = std::string(f.name) == "noise" ? 0.02 : 0.005;
    EXPECT_NEAR(double(m.face_count()), tris, count_tol * tris) << f.name;
    EXPECT_NEAR(voxel_area(m, f.volume), area, area_tol * area) << f.name;
  }
}

}  // namespace
}  // namespace tessera
