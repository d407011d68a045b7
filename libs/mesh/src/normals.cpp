#include "tessera/mesh/normals.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "normal_scale.hpp"
#include "tessera/math/power_of_two.hpp"

namespace tessera {
namespace {

// Cross products and lengths of coordinates beyond about 2^512 overflow (and below 2^-512 underflow), though the
// normal they give is a direction and the area often still a double. A face whose largest coordinate lies outside
// [2^-128, 2^128] is computed on its points times 2^-s (s that coordinate's binary exponent): exact, but for
// subnormals, so normals are those of the same face at unit scale and areas are scaled back by 2^(2s). Other faces
// are computed as they are (2^-s is 1), bit for bit as before.

/// A face's points as rescale_exponent() scales them: point(i) = position of corner i times 2^-s.
struct FacePoints {
  const std::vector<Vec3>& positions;
  std::span<const uint32_t> face;
  int s = 0;

  FacePoints(const PolyMesh& mesh, size_t f) : positions(mesh.positions), face(mesh.face(f)) {
    double largest = 0;
    for (uint32_t v : face) largest = std::max(largest, largest_component(positions[v]));
    s = rescale_exponent(largest);
  }
  Vec3 operator[](size_t i) const { return ldexp(positions[face[i]], -s); }
};

/// The face's vector area times 2^-2s: half the sum of its fan's cross products, on the scaled points.
Vec3 scaled_area_vector(const FacePoints& p) {
  Vec3 sum(0.0);
  for (size_t i = 1; i + 1 < p.face.size(); ++i) sum += glm::cross(p[i] - p[0], p[i + 1] - p[0]);
  return 0.5 * sum;
}

/// |v|, computed on v scaled by a power of two: glm::length overflows once a component passes about 1e154, and
/// underflows to 0 below about 1e-154.
double robust_length(const Vec3& v) {
  const int e = rescale_exponent(largest_component(v));
  return std::ldexp(glm::length(ldexp(v, -e)), e);
}

/// v / |v| computed on v scaled by a power of two (its length may overflow or underflow); 0 for a zero or non-finite v.
Vec3 normalized_or_zero(const Vec3& v) {
  const Vec3 u = ldexp(v, -rescale_exponent(largest_component(v)));
  const double len = glm::length(u);
  return len > 0 && std::isfinite(len) ? u / len : Vec3(0.0);
}

}  // namespace

namespace detail {

double face_area(const PolyMesh& mesh, size_t f) {
  const FacePoints p(mesh, f);
  return std::ldexp(robust_length(scaled_area_vector(p)), 2 * p.s);
}

}  // namespace detail

Vec3 face_area_vector(const PolyMesh& mesh, size_t f) {
  const FacePoints p(mesh, f);
  return ldexp(scaled_area_vector(p), 2 * p.s);
}

Vec3 face_normal(const PolyMesh& mesh, size_t f) { return normalized_or_zero(scaled_area_vector(FacePoints(mesh, f))); }

std::vector<Vec3> face_normals(const PolyMesh& mesh) {
  std::vector<Vec3> normals(mesh.face_count());
  for (size_t f = 0; f < normals.size(); ++f) normals[f] = face_normal(mesh, f);
  return normals;
}

std::vector<Vec3> vertex_normals(const PolyMesh& mesh, NormalWeighting weighting) {
  // Area weights are summed in units of 2^(2 s), s the scale exponent of the mesh's largest coordinate, so that the
  // sums neither overflow nor underflow at any scale (a face over 2^500 times smaller than the mesh's largest
  // coordinate then weighs nothing, as it would next to the others anyway).
  const int mesh_s = rescale_exponent(std::span<const Vec3>(mesh.positions));
  std::vector<Vec3> sums(mesh.vertex_count(), Vec3(0.0));
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const FacePoints p(mesh, f);
    const Vec3 area = scaled_area_vector(p);
    if (weighting == NormalWeighting::area) {
      const Vec3 weight = ldexp(area, 2 * (p.s - mesh_s));
      for (uint32_t v : p.face) sums[v] += weight;
      continue;
    }
    const Vec3 n = normalized_or_zero(area);
    const size_t k = p.face.size();
    for (size_t i = 0; i < k; ++i) {
      const Vec3 a = normalized_or_zero(p[(i + 1) % k] - p[i]);
      const Vec3 b = normalized_or_zero(p[(i + k - 1) % k] - p[i]);
      sums[p.face[i]] += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * n;
    }
  }
  for (Vec3& s : sums) s = normalized_or_zero(s);
  return sums;
}

void compute_vertex_normals(PolyMesh& mesh, NormalWeighting weighting) {
  mesh.normals = vertex_normals(mesh, weighting);
  mesh.corner_normals.clear();
}

}  // namespace tessera
