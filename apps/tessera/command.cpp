#include "command.hpp"

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "tessera/core/error.hpp"

namespace tessera::cli {

namespace {

/// The number a whole option value spells, if it is one (the validators below leave anything else to the option's own
/// conversion and its error).
std::optional<double> number_in(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') return std::nullopt;
  return v;
}

/// Refuses a number that parses as NaN or an infinity.
std::string finite_number(std::string& text) {
  const auto v = number_in(text);
  return v && !std::isfinite(*v) ? "expected a finite number, got '" + text + "'" : "";
}

}  // namespace

CLI::Validator non_negative() {
  return CLI::Validator(
      [](std::string& text) {
        const auto v = number_in(text);
        return v && *v < 0 ? "expected a number >= 0, got " + text : std::string();
      },
      "NONNEGATIVE");
}

void add_common_options(CLI::App& command, CommonOptions& common) {
  for (CLI::Option* option : command.get_options())
    if (option->get_type_name().rfind("FLOAT", 0) == 0) option->check(CLI::Validator(finite_number, ""));
  if (command.get_option_no_throw("--threads") == nullptr)
    command.add_option("--threads", common.threads, "Worker threads (0 = all cores)")->check(CLI::Range(0, 4096));
  if (command.get_option_no_throw("--quiet") == nullptr) command.add_flag("--quiet", common.quiet, "No progress bar");
  if (command.get_option_no_throw("--stats") == nullptr)
    command.add_flag("--stats", common.stats, "Print key=value figures on stdout");
  // Nested commands (`tessera mesh info`) get them too, so that their --help lists them.
  for (CLI::App* sub : command.get_subcommands([](CLI::App*) { return true; })) add_common_options(*sub, common);
}

void print_stats(const std::vector<std::pair<std::string, std::string>>& stats) {
  for (const auto& [key, value] : stats) fmt::print("{}={}\n", key, value);
}

std::string stat_value(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) return fmt::format("{}", static_cast<long long>(v));
  return fmt::format("{:.9g}", v);
}

Rgb parse_color(const std::string& text, const std::string& what) {
  if (!text.empty() && text[0] == '#') {
    if (text.size() != 7 || text.find_first_not_of("0123456789abcdefABCDEF", 1) != std::string::npos)
      throw InvalidInput(fmt::format("{}: expected #rrggbb, got '{}'", what, text));
    const auto channel = [&](int i) { return float(std::stoi(text.substr(size_t(1 + 2 * i), 2), nullptr, 16)) / 255.0f; };
    return {channel(0), channel(1), channel(2)};
  }
  const auto v = parse_doubles(text, 3, what);
  for (double c : v)
    if (c < 0 || c > 1) throw InvalidInput(fmt::format("{}: color components must be in [0, 1], got '{}'", what, text));
  return {float(v[0]), float(v[1]), float(v[2])};
}

}  // namespace tessera::cli

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
