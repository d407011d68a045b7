#include "tessera/math/transform.hpp"

#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/math/power_of_two.hpp"

namespace tessera {
namespace {
// GLM matrices are column-major (m[col][row]); this builds one from the notes' row-major notation.
Mat3 rows3(double a, double b, double c, double d, double e, double f, double g, double h, double i) {
  return glm::transpose(Mat3(a, b, c, d, e, f, g, h, i));
}
Mat4 rows4(const Vec4& r0, const Vec4& r1, const Vec4& r2, const Vec4& r3) {
  return glm::transpose(Mat4(r0, r1, r2, r3));
}
}  // namespace

Mat3 translate2d(double dx, double dy) { return rows3(1, 0, dx, 0, 1, dy, 0, 0, 1); }
Mat3 scale2d(double sx, double sy) { return rows3(sx, 0, 0, 0, sy, 0, 0, 0, 1); }
Mat3 rotate2d(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return rows3(c, -s, 0, s, c, 0, 0, 0, 1);
}
Mat3 shear2d(double a, double b) { return rows3(1, a, 0, b, 1, 0, 0, 0, 1); }
Mat3 reflect2d_y_axis() { return rows3(-1, 0, 0, 0, 1, 0, 0, 0, 1); }
Mat3 reflect2d_x_axis() { return rows3(1, 0, 0, 0, -1, 0, 0, 0, 1); }
Mat3 rotate2d_about(double theta, double cx, double cy) {
  return translate2d(cx, cy) * rotate2d(theta) * translate2d(-cx, -cy);
}

Mat4 translate(double dx, double dy, double dz) {
  return rows4({1, 0, 0, dx}, {0, 1, 0, dy}, {0, 0, 1, dz}, {0, 0, 0, 1});
}
Mat4 scale(double sx, double sy, double sz) { return rows4({sx, 0, 0, 0}, {0, sy, 0, 0}, {0, 0, sz, 0}, {0, 0, 0, 1}); }
Mat4 rotate_x(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return rows4({1, 0, 0, 0}, {0, c, -s, 0}, {0, s, c, 0}, {0, 0, 0, 1});
}
Mat4 rotate_y(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return rows4({c, 0, s, 0}, {0, 1, 0, 0}, {-s, 0, c, 0}, {0, 0, 0, 1});
}
Mat4 rotate_z(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return rows4({c, -s, 0, 0}, {s, c, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1});
}

Mat4 axis_frame(const Vec3& axis) {
  const double len = glm::length(axis);
  if (!(len > 0) || !std::isfinite(len)) throw InvalidInput("rotate: the rotation axis must be a nonzero vector");
  const Vec3 a = axis / len;
  // The notes: N = (1,0,0) if ax is 0, else (0,1,0). "ax is 0" is read as "A has no x component"; then A x (1,0,0)
  // cannot vanish. Otherwise A x (0,1,0) vanishes only if A is along y, which needs ax = 0.
  const Vec3 n = a.x == 0 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 b = glm::normalize(glm::cross(a, n));
  const Vec3 c = glm::cross(a, b);
  return rows4({a, 0}, {b, 0}, {c, 0}, {0, 0, 0, 1});
}

Mat4 rotate(double theta, const Vec3& axis) {
  const Mat4 r1 = axis_frame(axis);
  return glm::transpose(r1) * rotate_x(theta) * r1;
}

Mat4 shear(double xy, double xz, double yx, double yz, double zx, double zy) {
  return rows4({1, xy, xz, 0}, {yx, 1, yz, 0}, {zx, zy, 1, 0}, {0, 0, 0, 1});
}

Mat4 reflect(const Vec3& plane_normal) {
  const double len = glm::length(plane_normal);
  if (!(len > 0)) throw InvalidInput("reflect: the plane normal must be a nonzero vector");
  const Vec3 n = plane_normal / len;
  Mat4 m(1.0);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c][r] -= 2 * n[r] * n[c];
  return m;
}

Mat4 look_at(const Vec3& eye, const Vec3& center, const Vec3& up) {
  // The gaze and up are scaled by powers of two where they pass 2^+-128 (power_of_two.hpp): their lengths and cross
  // product would overflow beyond about 1e154 (or underflow below 1e-154), though the directions are well defined.
  const Vec3 g = center - eye;
  if (!std::isfinite(g.x) || !std::isfinite(g.y) || !std::isfinite(g.z))
    throw InvalidInput("camera: eye and center are farther apart than the finite numbers reach");
  const Vec3 gaze = ldexp(g, -rescale_exponent(largest_component(g)));
  if (!(glm::length(gaze) > 0)) throw InvalidInput("camera: eye and center must differ");
  const Vec3 w = -gaze / glm::length(gaze);
  const Vec3 up_scaled = ldexp(up, -rescale_exponent(largest_component(up)));
  const Vec3 txw = glm::cross(up_scaled, w);
  if (!(glm::length(txw) > 1e-12 * glm::length(up_scaled)))
    throw InvalidInput("camera: up must not be parallel to the gaze");
  const Vec3 u = txw / glm::length(txw);
  const Vec3 v = glm::cross(w, u);
  const Mat4 r = rows4({u, 0}, {v, 0}, {w, 0}, {0, 0, 0, 1});
  return r * translate(-eye.x, -eye.y, -eye.z);
}

Mat4 ortho(double l, double r, double b, double t, double n, double f) {
  if (l == r || b == t || n == f) throw InvalidInput("ortho: the view volume must not be empty");
  return rows4({2 / (r - l), 0, 0, -(r + l) / (r - l)}, {0, 2 / (t - b), 0, -(t + b) / (t - b)},
               {0, 0, -2 / (f - n), -(f + n) / (f - n)}, {0, 0, 0, 1});
}

Mat4 perspective(double fovy, double aspect, double n, double f) {
  if (!(fovy > 0 && fovy < kPi)) throw InvalidInput("perspective: fovy must be in (0, 180) degrees");
  if (!(aspect > 0)) throw InvalidInput("perspective: aspect must be positive");
  if (!(n > 0 && n < f)) throw InvalidInput("perspective: need 0 < near < far");
  const double k = std::tan(fovy / 2);
  return rows4({1 / (aspect * k), 0, 0, 0}, {0, 1 / k, 0, 0}, {0, 0, -(f + n) / (f - n), -2 * f * n / (f - n)},
               {0, 0, -1, 0});
}

Mat4 infinite_perspective(double fovy, double aspect, double n) {
  // The limits of perspective's third row; the checks are perspective's (with a finite far plane beyond n).
  Mat4 p = perspective(fovy, aspect, n, 2 * n + 1);
  p[2][2] = -1;
  p[3][2] = -2 * n;
  return p;
}

Mat3 normal_matrix(const Mat4& model_view) { return glm::inverse(glm::transpose(Mat3(model_view))); }

Vec3 transform_point(const Mat4& m, const Vec3& p) {
  const Vec4 q = m * Vec4(p, 1.0);
  return Vec3(q) / q.w;
}
Vec3 transform_vector(const Mat4& m, const Vec3& v) { return Vec3(m * Vec4(v, 0.0)); }
Vec2 transform_point(const Mat3& m, const Vec2& p) {
  const Vec3 q = m * Vec3(p, 1.0);
  return Vec2(q) / q.z;
}

}  // namespace tessera
