#include "command.hpp"

#include <cmath>

#include <fmt/format.h>

#include "tessera/core/error.hpp"

namespace tessera::cli {

void add_common_options(CLI::App& command, CommonOptions& common) {
  if (command.get_option_no_throw("--threads") == nullptr)
    command.add_option("--threads", common.threads, "Worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
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
