#pragma once
// The CLI's command interface. Each command lives in commands/<name>.cpp and exposes one setup function that adds its
// CLI11 subcommand; main.cpp holds the table of them (no if/else dispatch).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "tessera/core/parse.hpp"
#include "tessera/math/camera.hpp"

namespace tessera::cli {

/// Options every command accepts.
struct CommonOptions {
  int threads = 0;     ///< --threads N (0 = all cores)
  bool quiet = false;  ///< --quiet: no progress bars
  bool stats = false;  ///< --stats: machine-readable key=value figures on stdout
};

/// Checks that a number option is >= 0 ("expected a number >= 0, got -1"; CLI::NonNegativeNumber's message lists its
/// range up to the largest double, digit by digit).
CLI::Validator non_negative();

/// A command: its name, one-line summary and the function that adds its subcommand (options and callback) to the app.
struct Command {
  const char* name;
  const char* summary;
  void (*setup)(CLI::App& command, CommonOptions& common);
};

/// Adds --threads, --quiet and --stats to a command and to each of its nested subcommands, and makes their
/// floating-point options refuse "nan" and "inf" (CLI11 parses them, and its range checks let NaN through).
void add_common_options(CLI::App& command, CommonOptions& common);

/// Prints `key=value` lines on stdout (the --stats contract of DESIGN.md section 4).
void print_stats(const std::vector<std::pair<std::string, std::string>>& stats);

/// Formats a number for --stats: integers without a decimal point, others with up to 9 significant digits.
std::string stat_value(double v);

/// Parses a color given as r,g,b floats in [0,1] or #rrggbb. Throws InvalidInput naming `what`.
struct Rgb {
  float r, g, b;
};
Rgb parse_color(const std::string& text, const std::string& what);

/// The camera options shared by every 3D command (DESIGN.md section 4):
/// `--eye x,y,z --center x,y,z --up x,y,z --fovy DEG --near N --far F --size WxH`.
struct CameraOptions {
  std::string eye, center, up, size;
  double fovy = 45, near = 0, far = 0;  ///< near/far 0: chosen from the framed bounds

  /// Adds the options to `command`; `default_size` is the --size default ("WxH").
  void add(CLI::App& command, const std::string& default_size = "512x512");
  /// The image size from --size.
  Size2 image_size() const;
  /// The camera: options that were given win; the rest frame the bounding sphere of the box [lo, hi] from the +z side
  /// (eye on `view_dir` from the center, so that the sphere fills the view). The aspect is the image's.
  Camera camera(const Vec3& lo, const Vec3& hi, const Vec3& view_dir = {0, 0, 1}) const;
};

}  // namespace tessera::cli
