#include "tessera/curves/bezier_patch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "normal_fallback.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {
namespace {

// The quadratic Bernstein basis, for the hodographs (derivatives) of cubics.
std::array<double, 3> quadratic_basis(double t) {
  const double s = 1 - t;
  return {s * s, 2 * t * s, t * t};
}

// A typical partial-derivative length: the diagonal of the control points' bounding box.
double control_scale(const BezierPatch& patch) {
  Vec3 lo = patch.points[0], hi = patch.points[0];
  for (const Vec3& p : patch.points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return glm::length(hi - lo);
}

Vec3 normal_at(const BezierPatch& patch, double u, double v, double scale) {
  return detail::normal_with_fallback(
      [&](double a, double b) {
        const PatchSample s = evaluate_with_partials(patch, a, b);
        return std::array<Vec3, 2>{s.du, s.dv};
      },
      u, v, ParamInterval{0, 1}, ParamInterval{0, 1}, scale);
}

// The signed volume of the triangles about the centroid of all control points (divergence theorem).
double signed_volume_about_centroid(std::span<const BezierPatch> patches, const TriMesh& mesh) {
  Vec3 centroid(0.0);
  for (const BezierPatch& patch : patches)
    for (const Vec3& p : patch.points) centroid += p;
  centroid /= double(std::max<size_t>(1, 16 * patches.size()));
  double volume = 0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 a = mesh.positions[mesh.indices[3 * t]] - centroid,
               b = mesh.positions[mesh.indices[3 * t + 1]] - centroid,
               c = mesh.positions[mesh.indices[3 * t + 2]] - centroid;
    volume += glm::dot(a, glm::cross(b, c)) / 6;
  }
  return volume;
}

// Turns the mesh inside out: negated normals, reversed triangles.
void flip(TriMesh& mesh) {
  for (Vec3& n : mesh.normals) n = -n;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
}

}  // namespace

Vec3 evaluate_four_curves(const BezierPatch& patch, double u, double v) {
  // Steps 1 and 2: the points G_k(t) of the four row curves at t = v.
  std::array<Vec3, 4> on_rows;
  for (int i = 0; i < 4; ++i) on_rows[size_t(i)] = evaluate_bernstein(patch.row(i), v);
  // Steps 3 and 4: the cubic with those control points, at s = u.
  return evaluate_bernstein(cubic(on_rows[0], on_rows[1], on_rows[2], on_rows[3]), u);
}

Vec3 evaluate_bernstein(const BezierPatch& patch, double u, double v) {
  const auto bu = cubic_basis(u), bv = cubic_basis(v);
  Vec3 q(0.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) q += (bu[size_t(i)] * bv[size_t(j)]) * patch.at(i, j);
  return q;
}

PatchSample evaluate_with_partials(const BezierPatch& patch, double u, double v) {
  const auto bu = cubic_basis(u), bv = cubic_basis(v);
  const auto du = quadratic_basis(u), dv = quadratic_basis(v);
  // Each row at v, and its v-derivative 3 sum_j B²_j(v) (P_{i,j+1} - P_ij).
  std::array<Vec3, 4> rows{}, row_dv{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) rows[size_t(i)] += bv[size_t(j)] * patch.at(i, j);
    for (int j = 0; j < 3; ++j) row_dv[size_t(i)] += (3 * dv[size_t(j)]) * (patch.at(i, j + 1) - patch.at(i, j));
  }
  PatchSample s{Vec3(0.0), Vec3(0.0), Vec3(0.0)};
  for (int i = 0; i < 4; ++i) {
    s.position += bu[size_t(i)] * rows[size_t(i)];
    s.dv += bu[size_t(i)] * row_dv[size_t(i)];
  }
  for (int i = 0; i < 3; ++i) {
    // The u-hodograph differences, formed from control-point differences so that a collapsed column gives exact 0.
    Vec3 diff(0.0);
    for (int j = 0; j < 4; ++j) diff += bv[size_t(j)] * (patch.at(i + 1, j) - patch.at(i, j));
    s.du += (3 * du[size_t(i)]) * diff;
  }
  return s;
}

Vec3 patch_normal(const BezierPatch& patch, double u, double v) { return normal_at(patch, u, v, control_scale(patch)); }

int flatness_steps(const BezierPatch& patch, double tolerance, int max_steps) {
  if (!(tolerance > 0)) throw InvalidInput(fmt::format("flatness_steps: tolerance {} is not positive", tolerance));
  double uu = 0, uv = 0, vv = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (i < 2) uu = std::max(uu, glm::length(patch.at(i + 2, j) - 2.0 * patch.at(i + 1, j) + patch.at(i, j)));
      if (j < 2) vv = std::max(vv, glm::length(patch.at(i, j + 2) - 2.0 * patch.at(i, j + 1) + patch.at(i, j)));
      if (i < 3 && j < 3)
        uv = std::max(uv,
                      glm::length(patch.at(i + 1, j + 1) - patch.at(i + 1, j) - patch.at(i, j + 1) + patch.at(i, j)));
    }
  const double bound = 6 * uu + 2 * 9 * uv + 6 * vv;  // M_uu + 2 M_uv + M_vv
  const double n = std::ceil(std::sqrt(bound / (8 * tolerance)));
  return int(std::clamp(n, 1.0, double(std::max(1, max_steps))));
}

TriMesh tessellate(std::span<const BezierPatch> patches, const PatchTessellation& options) {
  if (options.steps < 1 || options.steps > 1024)
    throw InvalidInput(fmt::format("patch tessellation: steps {} (need 1..1024)", options.steps));
  if (!(options.tolerance >= 0))
    throw InvalidInput(fmt::format("patch tessellation: tolerance {} is negative", options.tolerance));
  // Per patch: its step count and where its vertices and triangles start.
  std::vector<int> steps(patches.size(), options.steps);
  std::vector<size_t> first_vertex(patches.size() + 1, 0), first_index(patches.size() + 1, 0);
  for (size_t p = 0; p < patches.size(); ++p) {
    if (options.tolerance > 0) steps[p] = flatness_steps(patches[p], options.tolerance, options.steps);
    const size_t n = size_t(steps[p]);
    first_vertex[p + 1] = first_vertex[p] + (n + 1) * (n + 1);
    first_index[p + 1] = first_index[p] + 6 * n * n;
  }
  if (first_vertex.back() > size_t(UINT32_MAX))
    throw InvalidInput(fmt::format("patch tessellation: {} vertices exceed 32-bit indices", first_vertex.back()));
  TriMesh mesh;
  mesh.positions.resize(first_vertex.back());
  mesh.normals.resize(first_vertex.back());
  mesh.uvs.resize(first_vertex.back());
  mesh.indices.resize(first_index.back());
  parallel_for(0, int64_t(patches.size()), 1, [&](int64_t begin, int64_t end) {
    for (int64_t p = begin; p < end; ++p) {
      const BezierPatch& patch = patches[size_t(p)];
      const int n = steps[size_t(p)];
      const double scale = control_scale(patch);
      const size_t base = first_vertex[size_t(p)];
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          const double u = double(i) / n, v = double(j) / n;
          const size_t k = base + size_t(i) * size_t(n + 1) + size_t(j);
          mesh.positions[k] = evaluate_bernstein(patch, u, v);
          mesh.normals[k] = normal_at(patch, u, v, scale);
          mesh.uvs[k] = Vec2(u, v);
        }
      uint32_t* out = mesh.indices.data() + first_index[size_t(p)];
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const auto a = uint32_t(base + size_t(i) * size_t(n + 1) + size_t(j));
          const uint32_t b = a + uint32_t(n + 1), c = b + 1, d = a + 1;
          // (u, v) -> (u + du, v) -> (u + du, v + dv) is counterclockwise around ∂u x ∂v.
          const std::array<uint32_t, 6> quad{a, b, c, a, c, d};
          out = std::copy(quad.begin(), quad.end(), out);
        }
    }
  });
  if (options.orientation == PatchOrientation::flipped ||
      (options.orientation == PatchOrientation::outward && signed_volume_about_centroid(patches, mesh) < 0))
    flip(mesh);
  return mesh;
}

PolyMesh control_net(std::span<const BezierPatch> patches) {
  PolyMesh net;
  for (const BezierPatch& patch : patches) {
    const auto base = uint32_t(net.positions.size());
    net.positions.insert(net.positions.end(), patch.points.begin(), patch.points.end());
    for (uint32_t i = 0; i < 3; ++i)
      for (uint32_t j = 0; j < 3; ++j) {
        const uint32_t a = base + 4 * i + j;
        net.add_face({a, a + 4, a + 5, a + 1});
      }
  }
  return net;
}

}  // namespace tessera
