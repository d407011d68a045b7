// Subdivision end to end (topology + positions) to level 4 of a ~10k-face cage with creases: Tessera's driver vs
// OpenSubdiv 3.5 Far (TopologyRefinerFactory + RefineUniform + PrimvarRefiner::Interpolate), in the same run.
//
//   ninja -C build/release bench_subdiv && build/release/bench/bench_subdiv --benchmark_min_time=2
//
// Tessera runs on 2 threads (and 1 for reference); OpenSubdiv's refinement is serial.
#include <benchmark/benchmark.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <memory>
#include <vector>

#include "tessera/core/parallel.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/triangulate.hpp"
#include "tessera/subdiv/subdivide.hpp"

namespace {

using namespace tessera;
namespace osd = OpenSubdiv::Far;
namespace sdc = OpenSubdiv::Sdc;

constexpr int kLevels = 4;

// A 100 x 100 torus of quads (or 100 x 50 x 2 triangles) with three creased rings (sharpness 2, 3.5 and infinite)
// and two corners.
PolyMesh cage(bool triangles) {
  const int n = 100, m = triangles ? 50 : 100;
  PolyMesh torus = make_torus(2.0, 0.7, n, m);  // vertex (i, j) is i * m + j
  torus.normals.clear();                        // positions only, as OpenSubdiv gets
  torus.corner_uvs.clear();
  PolyMesh mesh = triangles ? triangulate(torus) : std::move(torus);
  auto id = [&](int i, int j) { return uint32_t((i % n) * m + (j % m)); };
  const float sharpness[] = {2.0f, 3.5f, 10.0f};
  for (int r = 0; r < 3; ++r)
    for (int i = 0; i < n; ++i) mesh.creases.push_back({id(i, r * m / 3), id(i + 1, r * m / 3), sharpness[r]});
  mesh.corners = {{id(0, m / 2), 2.0f}, {id(n / 2, m / 2), 10.0f}};
  return mesh;
}

void tessera_refine(benchmark::State& state, bool triangles) {
  const PolyMesh mesh = cage(triangles);
  const ThreadLimit limit(int(state.range(0)));
  const SubdivisionOptions options{.scheme = triangles ? SubdivisionScheme::loop : SubdivisionScheme::catmull_clark,
                                   .levels = kLevels,
                                   .loop_weights = LoopWeights::loop};
  size_t faces = 0;
  for (auto _ : state) {
    const PolyMesh refined = subdivide(mesh, options);
    faces = refined.face_count();
    benchmark::DoNotOptimize(refined.positions.data());
  }
  state.counters["faces"] = double(faces);
  state.counters["faces/s"] = benchmark::Counter(double(faces), benchmark::Counter::kIsIterationInvariantRate);
}

struct OsdVertex {
  float p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0f; }
  void AddWithWeight(const OsdVertex& s, float w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

void opensubdiv_refine(benchmark::State& state, bool triangles) {
  const PolyMesh mesh = cage(triangles);
  std::vector<int> sizes, indices(mesh.face_vertices.begin(), mesh.face_vertices.end()), pairs, corner_ids;
  std::vector<float> weights, corner_weights;
  for (size_t f = 0; f < mesh.face_count(); ++f) sizes.push_back(int(mesh.face_size(f)));
  for (const EdgeCrease& c : mesh.creases) {
    pairs.insert(pairs.end(), {int(c.v0), int(c.v1)});
    weights.push_back(c.sharpness);
  }
  for (const VertexCorner& c : mesh.corners) {
    corner_ids.push_back(int(c.v));
    corner_weights.push_back(c.sharpness);
  }
  std::vector<OsdVertex> base;
  for (const Vec3& p : mesh.positions) base.push_back({{float(p.x), float(p.y), float(p.z)}});
  osd::TopologyDescriptor desc;
  desc.numVertices = int(mesh.vertex_count());
  desc.numFaces = int(mesh.face_count());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numCreases = int(weights.size());
  desc.creaseVertexIndexPairs = pairs.data();
  desc.creaseWeights = weights.data();
  desc.numCorners = int(corner_weights.size());
  desc.cornerVertexIndices = corner_ids.data();
  desc.cornerWeights = corner_weights.data();
  sdc::Options options;
  options.SetVtxBoundaryInterpolation(sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  const sdc::SchemeType type = triangles ? sdc::SCHEME_LOOP : sdc::SCHEME_CATMARK;
  size_t faces = 0;
  for (auto _ : state) {
    std::unique_ptr<osd::TopologyRefiner> refiner(osd::TopologyRefinerFactory<osd::TopologyDescriptor>::Create(
        desc, osd::TopologyRefinerFactory<osd::TopologyDescriptor>::Options(type, options)));
    refiner->RefineUniform(osd::TopologyRefiner::UniformOptions(kLevels));
    std::vector<OsdVertex> vertices(size_t(refiner->GetNumVerticesTotal()));
    std::copy(base.begin(), base.end(), vertices.begin());
    OsdVertex* src = vertices.data();
    const osd::PrimvarRefiner primvar(*refiner);
    for (int level = 1; level <= kLevels; ++level) {
      OsdVertex* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
      primvar.Interpolate(level, src, dst);
      src = dst;
    }
    faces = size_t(refiner->GetLevel(kLevels).GetNumFaces());
    benchmark::DoNotOptimize(vertices.data());
  }
  state.counters["faces"] = double(faces);
  state.counters["faces/s"] = benchmark::Counter(double(faces), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_CatmullClark_Tessera(benchmark::State& state) { tessera_refine(state, false); }
void BM_CatmullClark_OpenSubdiv(benchmark::State& state) { opensubdiv_refine(state, false); }
void BM_Loop_Tessera(benchmark::State& state) { tessera_refine(state, true); }
void BM_Loop_OpenSubdiv(benchmark::State& state) { opensubdiv_refine(state, true); }

// The peers run first: Tessera advises its large arrays to use transparent huge pages, and the heap regions it
// advises keep that flag after they are freed, so a peer running later would partly get huge pages too. Run with
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1 to give every allocation huge pages (compares the arithmetic alone).
BENCHMARK(BM_CatmullClark_OpenSubdiv)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Loop_OpenSubdiv)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CatmullClark_Tessera)->ArgName("threads")->Arg(2)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Loop_Tessera)->ArgName("threads")->Arg(2)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
