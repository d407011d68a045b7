#include "tessera/scene/framing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera {
namespace {

/// The model's front F, right R = U x F and up U (R x U = F). Throws InvalidInput when the front axis is the up axis
/// or its opposite.
struct ModelFrame {
  Vec3 front, right, up;
};
ModelFrame model_frame(UpAxis up_axis, FrontAxis front_axis) {
  const Vec3 up = up_axis == UpAxis::x ? Vec3(1, 0, 0) : up_axis == UpAxis::y ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  Vec3 front = up_axis == UpAxis::z ? Vec3(0, -1, 0) : Vec3(0, 0, 1);
  switch (front_axis) {
    case FrontAxis::automatic:
      break;
    case FrontAxis::pos_x:
      front = {1, 0, 0};
      break;
    case FrontAxis::neg_x:
      front = {-1, 0, 0};
      break;
    case FrontAxis::pos_y:
      front = {0, 1, 0};
      break;
    case FrontAxis::neg_y:
      front = {0, -1, 0};
      break;
    case FrontAxis::pos_z:
      front = {0, 0, 1};
      break;
    case FrontAxis::neg_z:
      front = {0, 0, -1};
      break;
  }
  if (glm::dot(front, up) != 0) throw InvalidInput("front axis: expected an axis perpendicular to the up axis");
  return {front, glm::cross(up, front), up};
}

}  // namespace

ViewAngles view_angles(FramedView view) {
  switch (view) {
    case FramedView::three_quarter:
      return {30, 20};
    case FramedView::front:
      return {0, 0};
    case FramedView::back:
      return {180, 0};
    case FramedView::left:
      return {-90, 0};
    case FramedView::right:
      return {90, 0};
    case FramedView::top:
      return {0, 90};
    case FramedView::bottom:
      return {0, -90};
    case FramedView::iso:
      return {45, std::atan(1 / std::sqrt(2.0)) * 180 / std::numbers::pi};
  }
  return {0, 0};
}

Camera frame_camera(const Framing& framing, const Vec3& lo, const Vec3& hi, double aspect) {
  const Framing& f = framing;
  if (!(f.fovy > 0 && f.fovy < 180))
    throw InvalidInput(fmt::format("field of view: expected degrees in (0, 180), got {}", f.fovy));
  if (!(aspect > 0 && std::isfinite(aspect))) throw InvalidInput(fmt::format("aspect: expected > 0, got {}", aspect));
  const Vec3 mid = 0.5 * (lo + hi);
  const double extent = 0.5 * glm::length(hi - lo);
  Camera c;
  c.fovy = radians(f.fovy);
  c.aspect = aspect;
  const double radius = extent > 0 ? extent : 1.0;  // a single point: a unit sphere around it
  // Distance at which the bounding sphere fits the narrower of the two fields of view, with a small margin.
  const double half = std::min(c.fovy, 2 * std::atan(std::tan(c.fovy / 2) * c.aspect)) / 2;
  const double dist = sphere_fit_distance(radius, half, 1.1);
  // The view's direction from the center to the eye, and the image's up: that direction turned 90 degrees upward.
  const auto [front, right, model_up] = model_frame(f.up_axis, f.front_axis);
  const double az = radians(f.angles.azimuth), el = radians(f.angles.elevation);
  const Vec3 level = std::cos(az) * front + std::sin(az) * right;
  const Vec3 view_dir = std::cos(el) * level + std::sin(el) * model_up;
  const Vec3 view_up = -std::sin(el) * level + std::cos(el) * model_up;
  c.center = f.center.value_or(mid);
  c.eye = f.eye.value_or(c.center + glm::normalize(view_dir) * dist);
  c.up = f.up.value_or(f.eye ? model_up : view_up);
  c.orthographic = f.ortho;
  c.ortho_height = f.ortho_size > 0 ? f.ortho_size : 2.2 * radius / std::min(1.0, c.aspect);
  const double d = glm::length(c.eye - mid);
  c.near = f.near > 0 ? f.near : std::max(1e-3 * (d + radius), d - 1.5 * radius);
  c.far = f.far > 0 ? f.far : d + 1.5 * radius;
  if (!(c.far > c.near)) throw InvalidInput(fmt::format("near/far: expected near < far, got {} and {}", c.near, c.far));
  return c;
}

}  // namespace tessera
