#pragma once
// The CLI's command interface. Each command lives in commands/<name>.cpp and exposes one setup function that adds its
// CLI11 subcommand; main.cpp holds the table of them (no if/else dispatch). docs/cli.md is the contract: the common
// options, the --stats vocabulary and the exit codes.
#include <CLI/CLI.hpp>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "tessera/image/image_io.hpp"

namespace tessera::cli {

/// Options every command accepts (and --srgb, which commands that write 8-bit images add).
struct CommonOptions {
  int threads = 0;                ///< --threads N (0 = all cores)
  bool quiet = false;             ///< --quiet: no progress
  bool stats = false;             ///< --stats: machine-readable key=value figures on stdout
  std::string progress = "auto";  ///< --progress auto|bar|plain|none
  bool srgb = false;              ///< --srgb: encode 8-bit output with the sRGB curve

  /// The image write options the command line asked for (--srgb).
  WriteOptions write_options() const {
    WriteOptions o;
    o.srgb = srgb;
    return o;
  }
};

/// Checks that a number option is >= 0 ("expected a number >= 0, got -1"; CLI::NonNegativeNumber's message lists its
/// range up to the largest double, digit by digit).
CLI::Validator non_negative();
/// Checks that a number option is > 0 ("expected a number > 0, got 0"; CLI::PositiveNumber's message lists its range up
/// to the largest double, digit by digit).
CLI::Validator positive();
/// Checks that an option is an image size "WxH" (both positive, at most 65536), so that `--size 800` is a usage error.
CLI::Validator size_format();
/// Checks that an option is a color that parse_color accepts, so that a misspelt color is a usage error.
CLI::Validator color_format();
/// Checks that an option is `count` comma-separated finite numbers (e.g. 3 for x,y,z).
CLI::Validator numbers_format(size_t count);

/// A command: its name, one-line summary and the function that adds its subcommand (options and callback) to the app.
struct Command {
  const char* name;
  const char* summary;
  void (*setup)(CLI::App& command, CommonOptions& common);
};

/// Adds --threads, --quiet, --progress and --stats to a command and to each of its nested subcommands, and makes
/// their floating-point options refuse "nan" and "inf" (CLI11 parses them, and its range checks let NaN through).
void add_common_options(CLI::App& command, CommonOptions& common);

/// Adds --srgb to a command that writes 8-bit images; pass common.write_options() to write_image. Float formats (PFM,
/// HDR) stay linear whatever it says.
void add_srgb_option(CLI::App& command, CommonOptions& common);

/// Adds an option that takes one of `names` (case-insensitive) and stores the matching value in `value`. --help and
/// errors list the names, never the values behind them; the default shown is the name of `value`'s initial value.
template <class T>
CLI::Option* add_choice(CLI::App& command, const std::string& flag, T& value,
                        const std::vector<std::pair<std::string, T>>& names, const std::string& description) {
  std::vector<std::string> keys;
  std::string initial;
  for (const auto& [key, v] : names) {
    keys.push_back(key);
    if (initial.empty() && v == value) initial = key;
  }
  CLI::Option* option = command.add_option_function<std::string>(
      flag,
      [&value, names](const std::string& text) {
        for (const auto& [key, v] : names)
          if (CLI::detail::to_lower(key) == CLI::detail::to_lower(text)) value = v;
      },
      description);
  option->check(CLI::IsMember(keys, CLI::ignore_case));
  if (!initial.empty()) option->default_str(initial);
  return option;
}

/// The rows of a --stats report: key, value.
using StatRows = std::vector<std::pair<std::string, std::string>>;

/// Marks the start of the command (main calls it first); `total_s` counts from here.
void start_command_clock();
/// Seconds since start_command_clock().
double command_seconds();

/// Prints `key=value` lines on stdout (the --stats contract, docs/cli.md), then `total_s` (the whole command so far)
/// unless a row already has it.
void print_stats(const StatRows& stats);

/// Formats a number for --stats: integers without a decimal point, others with up to 9 significant digits.
std::string stat_value(double v);

/// Times a command's phases for --stats: `read_s`, `compute_s`, `write_s` (docs/cli.md). A phase timed twice adds up.
class PhaseTimer {
 public:
  /// Runs f, adds its wall time to the phase `key` (also when f throws), and returns what f returns.
  template <class F>
  decltype(auto) time(const std::string& key, F&& f) {
    const Stopwatch watch{*this, key, std::chrono::steady_clock::now()};
    return std::forward<F>(f)();
  }
  /// Seconds timed under `key` so far (0 if never timed).
  double seconds(const std::string& key) const;
  /// The phases timed so far as --stats rows, in the order first timed.
  StatRows rows() const;

 private:
  struct Stopwatch {
    PhaseTimer& timer;
    std::string key;
    std::chrono::steady_clock::time_point start;
    ~Stopwatch() { timer.add(key, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()); }
  };
  void add(const std::string& key, double seconds);
  std::vector<std::pair<std::string, double>> phases_;
};

/// Parses a color: an SVG/CSS color name ("white", "cornflowerblue"), #rrggbb, or r,g,b floats in [0,1]. Throws
/// InvalidInput naming `what`.
struct Rgb {
  float r, g, b;
};
Rgb parse_color(const std::string& text, const std::string& what);

}  // namespace tessera::cli
