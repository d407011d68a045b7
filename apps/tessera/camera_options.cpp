#include "camera_options.hpp"

#include "command.hpp"

namespace tessera::cli {
namespace {

/// A library table of names as add_choice's list.
template <class T, size_t N>
std::vector<std::pair<std::string, T>> names_of(const std::array<std::pair<std::string_view, T>, N>& names) {
  std::vector<std::pair<std::string, T>> out;
  out.reserve(N);
  for (const auto& [name, value] : names) out.emplace_back(name, value);
  return out;
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
  CLI::Option* view_option = add_choice(command, "--view", view, names_of(kFramedViewNames),
                                        "Framed view of the model (with --up-axis): three-quarter is 30 degrees right "
                                        "of the front and 20 above, iso looks down the cube's diagonal");
  CLI::Option* azimuth_option =
      command
          .add_option("--azimuth", azimuth, "Degrees about the up axis from the front toward the right (90 = right)")
          ->check(CLI::Range(-360.0, 360.0));
  CLI::Option* elevation_option =
      command.add_option("--elevation", elevation, "Degrees above the horizontal plane (90 = top, -90 = bottom)")
          ->check(CLI::Range(-90.0, 90.0));
  add_choice(command, "--up-axis", up_axis, names_of(kUpAxisNames),
             "The model's up axis (meshes are usually y-up; the teapot .bpt is z-up)");
  add_choice(command, "--front-axis", front_axis, names_of(kFrontAxisNames),
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
  const auto vec = [](const std::string& text, const char* what) {
    return text.empty() ? std::nullopt : std::optional<Vec3>(parse_vec3(text, what));
  };
  Framing f;
  f.angles = {view_azimuth(), view_elevation()};
  f.up_axis = up_axis;
  f.front_axis = front_axis;
  f.fovy = fovy;
  f.ortho = ortho;
  f.ortho_size = ortho_size;
  f.eye = vec(eye, "--eye");
  f.center = vec(center, "--center");
  f.up = vec(up, "--up");
  f.near = near;
  f.far = far;
  const Size2 s = image_size();
  return frame_camera(f, lo, hi, double(s.width) / double(s.height));
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
