#include "command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/svg/svg.hpp"

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

/// A validator that accepts what `parse` accepts and reports the InvalidInput message of what it refuses. `parse` names
/// nothing (CLI11 puts the option's name in front), so the message's empty "<what>: " prefix is cut.
template <class Parse>
CLI::Validator parses_with(Parse parse, const std::string& name) {
  return CLI::Validator(
      [parse](std::string& text) {
        try {
          parse(text);
          return std::string();
        } catch (const InvalidInput& e) {
          const std::string message = e.what();
          return message.rfind(": ", 0) == 0 ? message.substr(2) : message;
        }
      },
      name);
}

std::chrono::steady_clock::time_point g_command_start = std::chrono::steady_clock::now();

}  // namespace

CLI::Validator non_negative() {
  return CLI::Validator(
      [](std::string& text) {
        const auto v = number_in(text);
        return v && *v < 0 ? "expected a number >= 0, got " + text : std::string();
      },
      "NONNEGATIVE");
}

CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) {
        const auto v = number_in(text);
        return v && !(*v > 0) ? "expected a number > 0, got " + text : std::string();
      },
      "POSITIVE");
}

CLI::Validator size_format() {
  return parses_with([](const std::string& text) { parse_size(text, ""); }, "WxH");
}

CLI::Validator color_format() {
  return parses_with([](const std::string& text) { parse_color(text, ""); }, "COLOR");
}

CLI::Validator numbers_format(size_t count) {
  return parses_with([count](const std::string& text) { parse_doubles(text, count, ""); }, "");
}

void add_common_options(CLI::App& command, CommonOptions& common) {
  for (CLI::Option* option : command.get_options())
    if (option->get_type_name().rfind("FLOAT", 0) == 0) option->check(CLI::Validator(finite_number, ""));
  if (command.get_option_no_throw("--threads") == nullptr)
    command.add_option("--threads", common.threads, "Worker threads (0 = all cores)")->check(CLI::Range(0, 4096));
  if (command.get_option_no_throw("--quiet") == nullptr) command.add_flag("--quiet", common.quiet, "No progress");
  if (command.get_option_no_throw("--progress") == nullptr)
    command
        .add_option("--progress", common.progress,
                    "Progress on stderr: a bar on a terminal (auto), always a bar, plain lines for logs, or none")
        ->check(CLI::IsMember({"auto", "bar", "plain", "none"}))
        ->capture_default_str();
  if (command.get_option_no_throw("--stats") == nullptr)
    command.add_flag("--stats", common.stats, "Print key=value figures on stdout (docs/cli.md)");
  if (command.get_option_no_throw("--max-memory") == nullptr)
    command
        .add_option_function<std::string>(
            "--max-memory", [](const std::string& text) { MemoryBudget::set_limit(parse_memory_size(text, "")); },
            "Refuse requests estimated to need more memory than SIZE (e.g. 512M, 4G; default: 3/4 of the memory "
            "this process may use)")
        ->check(parses_with([](const std::string& text) { parse_memory_size(text, ""); }, "SIZE"));
  // Nested commands (`tessera mesh info`) get them too, so that their --help lists them.
  for (CLI::App* sub : command.get_subcommands([](CLI::App*) { return true; })) add_common_options(*sub, common);
}

void add_srgb_option(CLI::App& command, CommonOptions& common) {
  command.add_flag("--srgb", common.srgb,
                   "Encode 8-bit output (PNG, JPG, BMP, TGA, PPM) with the sRGB curve instead of linear values");
}

void start_command_clock() { g_command_start = std::chrono::steady_clock::now(); }

double command_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - g_command_start).count();
}

void print_stats(const StatRows& stats) {
  bool has_total = false;
  for (const auto& [key, value] : stats) {
    fmt::print("{}={}\n", key, value);
    has_total = has_total || key == "total_s";
  }
  if (!has_total) fmt::print("total_s={}\n", stat_value(command_seconds()));
}

std::string stat_value(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) return fmt::format("{}", static_cast<long long>(v));
  return fmt::format("{:.9g}", v);
}

double PhaseTimer::seconds(const std::string& key) const {
  for (const auto& [k, s] : phases_)
    if (k == key) return s;
  return 0;
}

StatRows PhaseTimer::rows() const {
  StatRows rows;
  for (const auto& [key, s] : phases_) rows.emplace_back(key, stat_value(s));
  return rows;
}

void PhaseTimer::add(const std::string& key, double seconds) {
  for (auto& [k, s] : phases_)
    if (k == key) {
      s += seconds;
      return;
    }
  phases_.emplace_back(key, seconds);
}

Rgb parse_color(const std::string& text, const std::string& what) {
  if (text.find(',') != std::string::npos) {
    const auto v = parse_doubles(text, 3, what);
    for (double c : v)
      if (c < 0 || c > 1)
        throw InvalidInput(fmt::format("{}: color components must be in [0, 1], got '{}'", what, printable(text)));
    return {float(v[0]), float(v[1]), float(v[2])};
  }
  // Names and #rrggbb as SVG and CSS spell them.
  try {
    const Vec4f c = parse_svg_color(text);
    return {c.x, c.y, c.z};
  } catch (const InvalidInput&) {
    throw InvalidInput(
        fmt::format("{}: expected a color name (as SVG's: white, cornflowerblue), #rrggbb or r,g,b in [0,1], got '{}'",
                    what, printable(text)));
  }
}

}  // namespace tessera::cli
