#include "camera_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera::cli {
namespace {

/// The model's front F, right R = U x F and up U (R x U = F; see CameraOptions). Throws InvalidInput when the front
/// axis is the up axis or its opposite.
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
  if (glm::dot(front, up) != 0) throw InvalidInput("--front-axis: expected an axis perpendicular to --up-axis");
  return {front, glm::cross(up, front), up};
}

/// The named views' azimuth and elevation, degrees. iso looks down the cube's diagonal (elevation atan(1/sqrt 2));
/// the default three-quarter view stands 30 degrees to the right of the front and 20 above it.
struct ViewAngles {
  double azimuth, elevation;
};
ViewAngles view_angles(View view) {
  switch (view) {
    case View::three_quarter:
      return {30, 20};
    case View::front:
      return {0, 0};
    case View::back:
      return {180, 0};
    case View::left:
      return {-90, 0};
    case View::right:
      return {90, 0};
    case View::top:
      return {0, 90};
    case View::bottom:
      return {0, -90};
    case View::iso:
      return {45, std::atan(1 / std::sqrt(2.0)) * 180 / std::numbers::pi};
  }
  return {0, 0};
}

}  // namespace

void CameraOptions::add(CLI::App& command, const std::string& default_size) {
  size = default_size;
  CLI::Option* eye_option =
      command.add_option("--eye", eye, "Camera position x,y,z (default: the --view, framing the mesh)")
          ->check(numbers_format(3));
  command.add_option("--center", center, "Point looked at x,y,z (default: the center of the bounds)")
      ->check(numbers_format(3));
  command.add_option("--up", up, "Image up vector x,y,z (default: from the view and --up-axis)")
      ->check(numbers_format(3));
  CLI::Option* fovy_option = command.add_option("--fovy", fovy, "Vertical field of view, degrees")
                                 ->check(CLI::Range(0.001, 179.999))
                                 ->capture_default_str();
  if (clip_planes) {
    command.add_option("--near", near, "Near-plane distance (default: from the scene's bounds)")->check(non_negative());
    command.add_option("--far", far, "Far-plane distance (default: from the scene's bounds)")->check(non_negative());
  }
  command.add_option("--size", size, "Image size WxH")->check(size_format())->capture_default_str();
  CLI::Option* view_option = add_choice(command, "--view", view,
                                        {{"three-quarter", View::three_quarter},
                                         {"front", View::front},
                                         {"back", View::back},
                                         {"left", View::left},
                                         {"right", View::right},
                                         {"top", View::top},
                                         {"bottom", View::bottom},
                                         {"iso", View::iso}},
                                        "Framed view of the model (with --up-axis): three-quarter is 30 degrees right "
                                        "of the front and 20 above, iso looks down the cube's diagonal");
  CLI::Option* azimuth_option =
      command
          .add_option("--azimuth", azimuth, "Degrees about the up axis from the front toward the right (90 = right)")
          ->check(CLI::Range(-360.0, 360.0));
  CLI::Option* elevation_option =
      command.add_option("--elevation", elevation, "Degrees above the horizontal plane (90 = top, -90 = bottom)")
          ->check(CLI::Range(-90.0, 90.0));
  add_choice(command, "--up-axis", up_axis, {{"x", UpAxis::x}, {"y", UpAxis::y}, {"z", UpAxis::z}},
             "The model's up axis (meshes are usually y-up; the teapot .bpt is z-up)");
  add_choice(command, "--front-axis", front_axis,
             {{"auto", FrontAxis::automatic},
              {"+x", FrontAxis::pos_x},
              {"-x", FrontAxis::neg_x},
              {"+y", FrontAxis::pos_y},
              {"-y", FrontAxis::neg_y},
              {"+z", FrontAxis::pos_z},
              {"-z", FrontAxis::neg_z}},
             "Where the model's front faces, for the views (auto: +z, or -y for z-up; Spot faces -z)");
  CLI::Option* ortho_option =
      command.add_flag("--ortho", ortho, "Orthographic (parallel) projection instead of perspective");
  command
      .add_option("--ortho-size", ortho_size,
                  "With --ortho: the view's height in world units (default: frames "
                  "the bounds)")
      ->check(positive())
      ->needs(ortho_option);
  // The framed views place the eye: with --eye they would be ignored. --fovy means nothing to a parallel projection.
  for (CLI::Option* o : {view_option, azimuth_option, elevation_option}) o->excludes(eye_option);
  ortho_option->excludes(fovy_option);
}

Size2 CameraOptions::image_size() const { return parse_size(size, "--size"); }

double CameraOptions::view_azimuth() const { return azimuth ? *azimuth : view_angles(view).azimuth; }
double CameraOptions::view_elevation() const { return elevation ? *elevation : view_angles(view).elevation; }

Camera CameraOptions::camera(const Vec3& lo, const Vec3& hi) const {
  const Vec3 mid = 0.5 * (lo + hi);
  const double extent = 0.5 * glm::length(hi - lo);
  const auto vec = [](const std::string& text, const char* what, const Vec3& fallback) {
    return text.empty() ? fallback : parse_vec3(text, what);
  };
  if (!(fovy > 0 && fovy < 180)) throw InvalidInput(fmt::format("--fovy: expected degrees in (0, 180), got {}", fovy));
  const Size2 s = image_size();
  Camera c;
  c.fovy = radians(fovy);
  c.aspect = double(s.width) / double(s.height);
  const double radius = extent > 0 ? extent : 1.0;  // a single point: a unit sphere around it
  // Distance at which the bounding sphere fits the narrower of the two fields of view, with a small margin.
  const double half = std::min(c.fovy, 2 * std::atan(std::tan(c.fovy / 2) * c.aspect)) / 2;
  const double dist = sphere_fit_distance(radius, half, 1.1);
  // The view's direction from the center to the eye, and the image's up: that direction turned 90 degrees upward.
  const auto [front, right, model_up] = model_frame(up_axis, front_axis);
  const double az = radians(view_azimuth()), el = radians(view_elevation());
  const Vec3 level = std::cos(az) * front + std::sin(az) * right;
  const Vec3 view_dir = std::cos(el) * level + std::sin(el) * model_up;
  const Vec3 view_up = -std::sin(el) * level + std::cos(el) * model_up;
  c.center = vec(center, "--center", mid);
  c.eye = vec(eye, "--eye", c.center + glm::normalize(view_dir) * dist);
  c.up = vec(up, "--up", eye.empty() ? view_up : model_up);
  c.orthographic = ortho;
  c.ortho_height = ortho_size > 0 ? ortho_size : 2.2 * radius / std::min(1.0, c.aspect);
  const double d = glm::length(c.eye - mid);
  c.near = near > 0 ? near : std::max(1e-3 * (d + radius), d - 1.5 * radius);
  c.far = far > 0 ? far : d + 1.5 * radius;
  if (!(c.far > c.near))
    throw InvalidInput(fmt::format("--near/--far: expected near < far, got {} and {}", c.near, c.far));
  return c;
}

void add_samples_option(CLI::App& command, int& samples) {
  command
      .add_option("--samples", samples,
                  "Anti-aliasing: samples per pixel, stratified (correlated multi-jittered), averaged; 1 = the "
                  "pixel centers")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
}

Vec3 parse_vec3(const std::string& text, const char* what) {
  const auto v = parse_doubles(text, 3, what);
  return {v[0], v[1], v[2]};
}

}  // namespace tessera::cli
