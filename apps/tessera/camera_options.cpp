#include "camera_options.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "tessera/core/error.hpp"

namespace tessera::cli {

void CameraOptions::add(CLI::App& command, const std::string& default_size) {
  size = default_size;
  command.add_option("--eye", eye, "Camera position x,y,z (default: frames the scene)");
  command.add_option("--center", center, "Point looked at x,y,z (default: the scene's center)");
  command.add_option("--up", up, "Up vector x,y,z (default 0,1,0)");
  command.add_option("--fovy", fovy, "Vertical field of view, degrees")->capture_default_str();
  command.add_option("--near", near, "Near-plane distance (default: from the scene's bounds)");
  command.add_option("--far", far, "Far-plane distance (default: from the scene's bounds)");
  command.add_option("--size", size, "Image size WxH")->capture_default_str();
}

Size2 CameraOptions::image_size() const { return parse_size(size, "--size"); }

Camera CameraOptions::camera(const Vec3& lo, const Vec3& hi, const Vec3& view_dir) const {
  const Vec3 mid = 0.5 * (lo + hi);
  const double extent = 0.5 * glm::length(hi - lo);
  const auto vec = [](const std::string& text, const char* what, const Vec3& fallback) {
    if (text.empty()) return fallback;
    const auto d = parse_doubles(text, 3, what);
    return Vec3(d[0], d[1], d[2]);
  };
  if (!(fovy > 0 && fovy < 180)) throw InvalidInput(fmt::format("--fovy: expected degrees in (0, 180), got {}", fovy));
  const Size2 s = image_size();
  Camera c;
  c.fovy = radians(fovy);
  c.aspect = double(s.width) / double(s.height);
  const double radius = extent > 0 ? extent : 1.0;  // a single point: a unit sphere around it
  // Distance at which the bounding sphere fits the narrower of the two fields of view, with a small margin.
  const double half = std::min(c.fovy, 2 * std::atan(std::tan(c.fovy / 2) * c.aspect)) / 2;
  const double dist = 1.1 * radius / std::sin(half);
  c.center = vec(center, "--center", mid);
  c.eye = vec(eye, "--eye", c.center + glm::normalize(view_dir) * dist);
  c.up = vec(up, "--up", Vec3(0, 1, 0));
  const double d = glm::length(c.eye - mid);
  c.near = near > 0 ? near : std::max(1e-3 * (d + radius), d - 1.5 * radius);
  c.far = far > 0 ? far : d + 1.5 * radius;
  if (!(c.far > c.near)) throw InvalidInput(fmt::format("--near/--far: expected near < far, got {} and {}", c.near, c.far));
  return c;
}

}  // namespace tessera::cli
