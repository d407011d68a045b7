#include "tessera/curves/surface.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "normal_fallback.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {
namespace {

// A typical length of the partial derivatives: the extent of a 5 x 5 sample grid over the widest parameter range.
double derivative_scale(const ParametricSurface& surface) {
  Vec3 lo(INFINITY), hi(-INFINITY);
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j) {
      const Vec3 p = surface.position(surface.s.lo + (surface.s.hi - surface.s.lo) * i / 4.0,
                                      surface.t.lo + (surface.t.hi - surface.t.lo) * j / 4.0);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  const double range = std::max(surface.s.hi - surface.s.lo, surface.t.hi - surface.t.lo);
  return glm::length(hi - lo) / range;
}

// Central differences with a step of 1e-6 of the range, one-sided where the step would leave the domain.
std::array<Vec3, 2> finite_difference_partials(const ParametricSurface& surface, double s, double t) {
  const auto diff = [](const auto& f, double x, ParamInterval r) {
    const double h = 1e-6 * (r.hi - r.lo);
    const double a = std::max(r.lo, x - h), b = std::min(r.hi, x + h);
    return (f(b) - f(a)) / (b - a);
  };
  return {diff([&](double x) { return surface.position(x, t); }, s, surface.s),
          diff([&](double x) { return surface.position(s, x); }, t, surface.t)};
}

Vec3 normal_at(const ParametricSurface& surface, double s, double t, double scale) {
  if (surface.normal) return surface.normal(s, t);
  return detail::normal_with_fallback([&](double a, double b) { return finite_difference_partials(surface, a, b); }, s,
                                      t, surface.s, surface.t, scale);
}

void require_surface(const ParametricSurface& surface) {
  if (!surface.position) throw InvalidInput("parametric surface: no position function");
  if (!(surface.s.lo < surface.s.hi) || !(surface.t.lo < surface.t.hi))
    throw InvalidInput(fmt::format("parametric surface: empty parameter range s [{}, {}], t [{}, {}]", surface.s.lo,
                                   surface.s.hi, surface.t.lo, surface.t.hi));
}

}  // namespace

ParametricSurface parallelogram(const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const Vec3 e1 = p2 - p1, e2 = p3 - p1;
  const Vec3 n = glm::cross(e1, e2);
  if (!(glm::length(n) > 1e-300)) throw InvalidInput("parallelogram: the three corners are collinear");
  const Vec3 unit = glm::normalize(n);
  return {
      [=](double s, double t) { return p1 + s * e1 + t * e2; }, [=](double, double) { return unit; }, {0, 1}, {0, 1}};
}

ParametricSurface cylinder(double radius, double height) {
  if (!(radius > 0) || !(height > 0))
    throw InvalidInput(fmt::format("cylinder: radius {} and height {} must be positive", radius, height));
  return {[=](double s, double t) { return Vec3(radius * std::cos(s), radius * std::sin(s), height * t); },
          [](double s, double) { return Vec3(std::cos(s), std::sin(s), 0.0); },
          {0, 2 * kPi},
          {0, 1}};
}

ParametricSurface sphere(double radius) {
  if (!(radius > 0)) throw InvalidInput(fmt::format("sphere: radius {} must be positive", radius));
  const auto unit = [](double s, double t) {
    return Vec3(std::cos(t) * std::cos(s), std::cos(t) * std::sin(s), std::sin(t));
  };
  return {[=](double s, double t) { return radius * unit(s, t); }, unit, {0, 2 * kPi}, {-kPi / 2, kPi / 2}};
}

Vec3 surface_normal(const ParametricSurface& surface, double s, double t) {
  require_surface(surface);
  return normal_at(surface, s, t, surface.normal ? 0.0 : derivative_scale(surface));
}

TriMesh tessellate(const ParametricSurface& surface, int s_steps, int t_steps) {
  require_surface(surface);
  if (s_steps < 1 || t_steps < 1 || s_steps > 4096 || t_steps > 4096)
    throw InvalidInput(fmt::format("tessellate: steps {} x {} (need 1..4096 each)", s_steps, t_steps));
  const double scale = surface.normal ? 0.0 : derivative_scale(surface);
  const int columns = t_steps + 1;
  TriMesh mesh;
  const size_t vertices = size_t(s_steps + 1) * size_t(columns);
  mesh.positions.resize(vertices);
  mesh.normals.resize(vertices);
  mesh.uvs.resize(vertices);
  parallel_for(0, s_steps + 1, 8, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      for (int j = 0; j <= t_steps; ++j) {
        const double u = double(i) / s_steps, w = double(j) / t_steps;
        const double s = surface.s.lo + u * (surface.s.hi - surface.s.lo);
        const double t = surface.t.lo + w * (surface.t.hi - surface.t.lo);
        const size_t k = size_t(i) * columns + j;
        mesh.positions[k] = surface.position(s, t);
        mesh.normals[k] = normal_at(surface, s, t, scale);
        mesh.uvs[k] = Vec2(u, w);
      }
  });
  mesh.indices.reserve(size_t(6) * s_steps * t_steps);
  for (int i = 0; i < s_steps; ++i)
    for (int j = 0; j < t_steps; ++j) {
      const uint32_t a = uint32_t(i * columns + j), b = a + uint32_t(columns), c = b + 1, d = a + 1;
      // (s, t) -> (s + ds, t) -> (s + ds, t + dt) is counterclockwise around ∂s x ∂t.
      mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
    }
  return mesh;
}

}  // namespace tessera
