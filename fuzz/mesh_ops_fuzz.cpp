// libFuzzer target for the algorithms that run on parsed meshes (`tessera mesh info/normals/smooth/subdivide/
// triangulate`): the first two bytes are parameters, the rest is an OBJ file (read_obj from memory; at most 8 KiB and
// 2048 face corners, so one input stays well under a second). On what parses it runs the topology report, the edge
// table and vertex classification, triangulation, the corner table of the triangulated mesh, face and vertex normals
// (area and angle weighted), smoothing (method, 0-7 iterations, lambda and fixed boundary from byte 1), subdivision
// (scheme, 1-2 levels, boundary rule, crease method, Loop weights and Catmull-Clark triangle rule from byte 0; Loop on
// the triangulated mesh) with the file's creases and corners, and the limit surface of the subdivided mesh.
// tessera::Error is the expected outcome (a mesh that a step refuses: non-manifold for subdivision, a request over
// the 256 MiB memory budget); anything else (a crash, another exception, a sanitizer report) is a bug, and so is a
// broken invariant (__builtin_trap): a position, normal or limit point that is not finite (the reader refuses
// non-finite numbers, so every input is finite), a normal that is neither unit length nor zero, a corner table whose
// opposites do not pair up, or a triangulation that does not give s - 2 triangles per s-gon.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/mesh/corner_table.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/smoothing.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/mesh/triangulate.hpp"
#include "tessera/subdiv/limit.hpp"
#include "tessera/subdiv/subdivide.hpp"

namespace {

using namespace tessera;

void check(bool ok) {
  if (!ok) __builtin_trap();
}

void check_finite(const std::vector<Vec3>& points) {
  for (const Vec3& p : points) check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
}

// Unit length (to float-ish precision) or exactly zero (a degenerate face, an unreferenced vertex).
void check_normals(const std::vector<Vec3>& normals) {
  check_finite(normals);
  for (const Vec3& n : normals) {
    const double length = glm::length(n);
    check(length == 0 || std::abs(length - 1) < 1e-6);
  }
}

void check_corner_table(const CornerTable& table) {
  for (uint32_t c = 0; c < table.corner_count(); ++c) {
    const uint32_t o = table.opposite(c);
    if (o == CornerTable::kNoCorner) continue;
    check(o < table.corner_count() && table.opposite(o) == c);
    check(table.vertex(CornerTable::next(c)) == table.vertex(CornerTable::prev(o)));
    check(table.vertex(CornerTable::prev(c)) == table.vertex(CornerTable::next(o)));
  }
  for (uint32_t v = 0; v < table.vertex_count(); ++v) {
    const uint32_t c = table.vertex_corner(v);
    check(c == CornerTable::kNoCorner || table.vertex(c) == v);
  }
}

void topology(const PolyMesh& mesh) {
  const TopologyReport report = analyze_topology(mesh);
  check(report.vertices == mesh.vertex_count() && report.faces == mesh.face_count());
  const EdgeTable edges = build_edge_table(mesh);
  check(edges.size() == report.edges);
  check(classify_vertices(mesh, edges).size() == mesh.vertex_count());
  boundary_loops(mesh, edges);
  is_consistently_oriented(mesh, edges);
}

PolyMesh triangulated(const PolyMesh& mesh) {
  PolyMesh t = triangulate(mesh);
  size_t expected = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) expected += mesh.face_size(f) - 2;
  check(t.is_triangle_mesh() && t.face_count() == expected && t.positions == mesh.positions);
  return t;
}

void normals(const PolyMesh& mesh) {
  check_normals(face_normals(mesh));
  check_normals(vertex_normals(mesh, NormalWeighting::area));
  check_normals(vertex_normals(mesh, NormalWeighting::angle));
}

void smoothing(PolyMesh mesh, uint8_t byte) {
  SmoothingOptions options;
  options.method = SmoothingMethod(byte % 3);
  options.iterations = byte / 3 % 8;
  options.fix_boundary = byte / 24 % 2;
  constexpr double kLambdas[] = {0.5, 1.0, 0.33, 0.9};
  options.lambda = kLambdas[byte / 48 % 4];
  options.mu = -options.lambda - 0.03;
  smooth(mesh, options);
  check(mesh.vertex_count() == mesh.positions.size());
  check_finite(mesh.positions);
  // Smoothing recomputes the normals it moved; zero iterations keep the file's `vn`, which need not be unit length.
  if (options.iterations > 0) check_normals(mesh.normals);
}

void subdivision(const PolyMesh& mesh, const PolyMesh& triangles, uint8_t byte) {
  SubdivisionOptions options;
  options.scheme = SubdivisionScheme(byte % 3);
  options.levels = 1 + byte / 3 % 2;
  options.boundary = BoundaryInterpolation(byte / 6 % 2);
  options.crease_method = CreaseMethod(byte / 12 % 2);
  options.loop_weights = LoopWeights(byte / 24 % 2);
  options.triangles = TriangleSubdivision(byte / 48 % 2);
  const PolyMesh refined = subdivide(options.scheme == SubdivisionScheme::loop ? triangles : mesh, options);
  check_finite(refined.positions);
  if (options.scheme == SubdivisionScheme::midpoint) return;  // no limit surface
  const LimitSurface limit = limit_surface(refined, options);
  check(limit.positions.size() == refined.vertex_count() && limit.normals.size() == refined.vertex_count());
  check_finite(limit.positions);
  check_finite(limit.normals);
}

// Runs one step; a step that refuses the mesh (tessera::Error) does not stop the others.
template <class F>
void step(F&& f) {
  try {
    f();
  } catch (const Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2 || size > 8192 + 2) return 0;
  MemoryBudget::set_limit(uint64_t(256) << 20);
  PolyMesh mesh;
  try {
    mesh = read_obj(std::string_view(reinterpret_cast<const char*>(data) + 2, size - 2), "fuzz.obj");
  } catch (const Error&) {
    return 0;
  }
  if (mesh.face_vertices.size() > 2048) return 0;
  check_finite(mesh.positions);
  step([&] { topology(mesh); });
  PolyMesh triangles;
  try {
    triangles = triangulated(mesh);
  } catch (const Error&) {
    return 0;
  }
  step([&] { check_corner_table(CornerTable(triangles)); });
  step([&] { normals(mesh); });
  step([&] { normals(triangles); });
  step([&] { smoothing(mesh, data[1]); });
  step([&] { subdivision(mesh, triangles, data[0]); });
  return 0;
}
