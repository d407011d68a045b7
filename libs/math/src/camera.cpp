#include "tessera/math/camera.hpp"

#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"

namespace tessera {

Mat4 Camera::view() const { return look_at(eye, center, up); }

Mat4 Camera::projection() const {
  if (!orthographic) return perspective(fovy, aspect, near, far);
  if (!(ortho_height > 0 && std::isfinite(ortho_height)))
    throw InvalidInput("orthographic camera: the view's height must be positive");
  const double h = ortho_height / 2, w = h * aspect;
  return ortho(-w, w, -h, h, near, far);
}

void Camera::frame(Vec3& u, Vec3& v, Vec3& w) const {
  const Mat4 m = view();
  u = Vec3(m[0][0], m[1][0], m[2][0]);
  v = Vec3(m[0][1], m[1][1], m[2][1]);
  w = Vec3(m[0][2], m[1][2], m[2][2]);
}

EyeRays::EyeRays(const Camera& camera, int width, int height)
    : eye_(camera.eye), aspect_(double(width) / double(height)), width_(width), height_(height) {
  if (width <= 0 || height <= 0) throw InvalidInput("eye rays: image size must be positive");
  if (!(camera.fovy > 0 && camera.fovy < kPi)) throw InvalidInput("eye rays: fovy must be in (0, 180) degrees");
  camera.frame(u_, v_, w_);
  d_ = 1.0 / std::tan(camera.fovy / 2);
  if (camera.orthographic) {
    if (!(camera.ortho_height > 0 && std::isfinite(camera.ortho_height)))
      throw InvalidInput("eye rays: the orthographic view's height must be positive");
    ortho_half_ = camera.ortho_height / 2;
  }
}

Ray EyeRays::ray(double i, double j, double dx, double dy) const {
  const double u = (2.0 * (i + dx) / width_ - 1.0) * aspect_;
  const double v = 1.0 - 2.0 * (j + dy) / height_;
  if (ortho_half_ > 0) {
    Ray r;
    r.origin = Vec3f(eye_ + ortho_half_ * (u * u_ + v * v_));
    r.dir = Vec3f(-w_);
    return r;
  }
  const Vec3 dir = glm::normalize(-d_ * w_ + u * u_ + v * v_);
  Ray r;
  r.origin = Vec3f(eye_);
  r.dir = Vec3f(dir);
  return r;
}

}  // namespace tessera
