#include "tessera/mesh/smoothing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/math/power_of_two.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera {
namespace {

/// Each vertex's neighbours (CSR) with the edge that leads to each, so per-edge weights can be looked up.
struct Neighbours {
  std::vector<uint32_t> offsets, vertex, edge;
};

Neighbours neighbours_of(const EdgeTable& edges, size_t vertex_count) {
  Neighbours n;
  n.offsets.assign(vertex_count + 1, 0);
  for (const auto& [a, b] : edges.vertices) {
    ++n.offsets[a + 1];
    ++n.offsets[b + 1];
  }
  for (size_t v = 0; v < vertex_count; ++v) n.offsets[v + 1] += n.offsets[v];
  n.vertex.resize(n.offsets.back());
  n.edge.resize(n.offsets.back());
  std::vector<uint32_t> fill(n.offsets.begin(), n.offsets.end() - 1);
  for (uint32_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges.vertices[e];
    n.vertex[fill[a]] = b;
    n.edge[fill[a]++] = e;
    n.vertex[fill[b]] = a;
    n.edge[fill[b]++] = e;
  }
  return n;
}

/// Half the cotangent of the angle at corner c facing the edge of the next two corners, summed per edge; >= 0.
void cotangent_weights(const PolyMesh& tris, const EdgeTable& edges, std::vector<double>& w) {
  w.assign(edges.size(), 0.0);
  for (size_t c = 0; c < tris.face_vertices.size(); ++c) {
    const uint32_t n1 = edges.next_corner[c], n2 = edges.next_corner[n1];
    const Vec3& p = tris.positions[tris.face_vertices[c]];
    const Vec3 a = tris.positions[tris.face_vertices[n1]] - p, b = tris.positions[tris.face_vertices[n2]] - p;
    const double sine = glm::length(glm::cross(a, b));
    if (sine > 0) w[edges.edge_of_corner[n1]] += 0.5 * glm::dot(a, b) / sine;
  }
  for (double& x : w) x = std::max(x, 0.0);
}

}  // namespace

void smooth(PolyMesh& mesh, const SmoothingOptions& options, const std::function<void(int)>& progress) {
  if (options.iterations < 0)
    throw InvalidInput(fmt::format("smoothing iterations must be >= 0, got {}", options.iterations));
  if (!(options.lambda > 0 && options.lambda <= 1))
    throw InvalidInput(fmt::format("smoothing lambda must be in (0, 1], got {}", options.lambda));
  if (options.method == SmoothingMethod::taubin && !(options.mu < -options.lambda && options.mu >= -1))
    throw InvalidInput(
        fmt::format("Taubin mu must be in [-1, -lambda), got {} (lambda {})", options.mu, options.lambda));

  // Every step is linear in the positions and cotangent weights depend on angles only, so the steps run on the
  // positions scaled by a power of two (exact; power_of_two.hpp) where the largest coordinate passes 2^128:
  // differences and sums of coordinates near 1e308 would overflow to inf and NaN.
  const int exponent = rescale_exponent(std::span<const Vec3>(mesh.positions));
  std::vector<Vec3> positions(mesh.positions.size());
  for (size_t v = 0; v < positions.size(); ++v) positions[v] = ldexp(mesh.positions[v], -exponent);

  const bool cotangent = options.method == SmoothingMethod::cotangent;
  const PolyMesh tris = cotangent ? triangulate(mesh) : PolyMesh{};
  const PolyMesh& topology = cotangent ? tris : mesh;
  const EdgeTable edges = build_edge_table(topology);
  const Neighbours nb = neighbours_of(edges, mesh.vertex_count());
  std::vector<uint8_t> fixed(mesh.vertex_count(), 0);
  if (options.fix_boundary) {
    const auto kinds = classify_vertices(mesh, build_edge_table(mesh));
    for (size_t v = 0; v < kinds.size(); ++v) fixed[v] = kinds[v] != VertexKind::interior;
  }
  std::vector<double> weight(edges.size(), 1.0);
  std::vector<Vec3> next(positions.size());
  PolyMesh weighted = cotangent ? tris : PolyMesh{};  // positions updated for the cotangent weights

  const auto step = [&](double factor) {
    if (cotangent) {
      weighted.positions = positions;
      cotangent_weights(weighted, edges, weight);
    }
    parallel_for(0, int64_t(mesh.vertex_count()), 4096, [&](int64_t begin, int64_t end) {
      for (auto v = size_t(begin); v < size_t(end); ++v) {
        const Vec3& x = positions[v];
        next[v] = x;
        if (fixed[v]) continue;
        Vec3 sum(0.0);
        double total = 0;
        for (uint32_t i = nb.offsets[v]; i < nb.offsets[v + 1]; ++i) {
          sum += weight[nb.edge[i]] * (positions[nb.vertex[i]] - x);
          total += weight[nb.edge[i]];
        }
        if (total > 0) next[v] = x + factor * (sum / total);
      }
    });
    positions.swap(next);
  };
  for (int i = 0; i < options.iterations; ++i) {
    step(options.lambda);
    if (options.method == SmoothingMethod::taubin) step(options.mu);
    if (progress) progress(i + 1);
  }
  // Taubin's inflating steps can move a vertex beyond the mesh's box, and so beyond the finite numbers near 1e308.
  for (size_t v = 0; v < positions.size(); ++v) {
    positions[v] = ldexp(positions[v], exponent);
    if (!std::isfinite(positions[v].x) || !std::isfinite(positions[v].y) || !std::isfinite(positions[v].z))
      throw InvalidInput(
          fmt::format("smoothing moves vertex {} beyond the finite numbers (the largest coordinate is "
                      "{:g}); scale the mesh down first",
                      v, largest_coordinate(mesh.positions)));
  }
  mesh.positions = std::move(positions);
  // Normals of the old shape would be silently wrong: give the smoothed shape its own.
  if (options.iterations > 0 && (!mesh.normals.empty() || !mesh.corner_normals.empty())) {
    mesh.corner_normals.clear();
    compute_vertex_normals(mesh, NormalWeighting::area);
  }
}

}  // namespace tessera
