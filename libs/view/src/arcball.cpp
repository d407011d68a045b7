#include "tessera/view/arcball.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {

Vec3 arcball_point(double x, double y, int width, int height) {
  const double radius = 0.5 * std::max(1, std::min(width, height));
  const double px = (x - 0.5 * width) / radius, py = (0.5 * height - y) / radius;
  const double r2 = px * px + py * py;
  if (r2 > 1) {
    const double r = std::sqrt(r2);
    return {px / r, py / r, 0};
  }
  return {px, py, std::sqrt(1 - r2)};
}

Quat arcball_rotation(const Vec3& from, const Vec3& to) {
  const Vec3 axis = glm::cross(from, to);
  return glm::normalize(Quat(glm::dot(from, to), axis.x, axis.y, axis.z));
}

OrbitControl::OrbitControl(const Camera& home, const Vec3& center, double radius)
    : home_(home), center_(center), radius_(radius) {
  if (!(radius > 0 && std::isfinite(radius)))
    throw InvalidInput(fmt::format("orbit control: expected a positive finite radius, got {}", radius));
  home_.center = center;
  home_distance_ = distance_ = glm::length(home.eye - center);
  if (!(home_distance_ > 0 && std::isfinite(home_distance_)))
    throw InvalidInput("orbit control: the home camera's eye is at the center it orbits");
  static_cast<void>(home_.view());  // throws for a degenerate camera (up along the gaze)
}

Camera OrbitControl::camera(double aspect) const {
  Vec3 u, v, w;
  home_.frame(u, v, w);
  // Eye to world is the matrix of columns u, v, w. The scene turned by q in eye coordinates is the scene turned by
  // Rw = E q E^T in world coordinates, which the home camera turned by Rw^T sees the same way.
  const Mat3 e(u, v, w);
  const Mat3 rw = e * glm::mat3_cast(orientation_) * glm::transpose(e);
  const Mat3 back = glm::transpose(rw);
  const Vec3 u2 = back * u, v2 = back * v, w2 = back * w;
  Camera c = home_;
  c.aspect = aspect;
  c.center = center_ - pan_.x * u2 - pan_.y * v2;  // the scene moves by +pan: the camera by -pan
  c.eye = c.center + distance_ * w2;
  c.up = v2;
  c.near = std::max(distance_ - 1.5 * radius_, distance_ / 1000);
  c.far = distance_ + 1.5 * radius_;
  if (c.orthographic) c.ortho_height = home_.ortho_height * distance_ / home_distance_;
  return c;
}

void OrbitControl::begin_rotate(double x, double y, int width, int height) {
  drag_start_ = arcball_point(x, y, width, height);
  drag_start_orientation_ = orientation_;
}

void OrbitControl::rotate_to(double x, double y, int width, int height) {
  orientation_ =
      glm::normalize(arcball_rotation(drag_start_, arcball_point(x, y, width, height)) * drag_start_orientation_);
}

void OrbitControl::begin_pan(double x, double y) {
  pan_start_ = pan_;
  pan_pointer_ = {x, y};
}

void OrbitControl::pan_to(double x, double y, int height) {
  // World units per pixel in the plane through the center, facing the eye.
  const double view_height =
      home_.orthographic ? home_.ortho_height * distance_ / home_distance_ : 2 * distance_ * std::tan(home_.fovy / 2);
  const double scale = view_height / std::max(1, height);
  pan_ = pan_start_ + Vec2(x - pan_pointer_.x, pan_pointer_.y - y) * scale;  // window rows grow downward
}

void OrbitControl::zoom(double steps) {
  distance_ = std::clamp(distance_ * std::pow(1.1, steps), radius_ / 100, 100 * home_distance_);
}

Quat OrbitControl::turn_about_up(double angle) const {
  Vec3 u, v, w;
  home_.frame(u, v, w);
  const Vec3 up = glm::normalize(home_.up);
  return glm::angleAxis(angle, glm::normalize(Vec3(glm::dot(u, up), glm::dot(v, up), glm::dot(w, up))));
}

void OrbitControl::reset() {
  orientation_ = drag_start_orientation_ = Quat(1, 0, 0, 0);
  pan_ = pan_start_ = Vec2(0.0);
  distance_ = home_distance_;
}

}  // namespace tessera
