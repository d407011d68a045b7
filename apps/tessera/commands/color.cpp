// tessera color convert --from M --to M [--values a,b,c] [--hue degrees|turns|radians]: color-model conversions of
// one color (--values) or of CSV rows read from stdin, one converted row per line on stdout (docs/color.md).
#include "tessera/color/color.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "tessera/color/model.hpp"
#include "tessera/core/error.hpp"

namespace tessera::cli {
namespace {

struct ConvertOptions {
  std::string from, to;
  std::string values;  // empty: read stdin
  std::string hue = "degrees";
};

// Parses one row of component_count(model) comma-separated numbers; `where` names it in the error.
std::vector<double> parse_row(const std::string& row, ColorModel model, const std::string& where) {
  const size_t n = size_t(component_count(model));
  try {
    return parse_doubles(row, n, where);
  } catch (const InvalidInput&) {
    throw InvalidInput(fmt::format("{}: expected {} comma-separated numbers, got '{}'", where, n, row));
  }
}

// One number with up to 9 significant digits; magnitudes below 1e-12 (round-off around 0) print as 0.
std::string format_number(double v) {
  if (std::abs(v) < 1e-12) return "0";
  return fmt::format("{:.9g}", v);
}

// Converts one row; the hue component (if any) is read and written in `unit`. Returns the output line.
std::string convert_row(const std::vector<double>& in, ColorModel from, ColorModel to, HueUnit unit) {
  std::vector<double> values = in;
  if (hue_index(from) >= 0) values[size_t(hue_index(from))] /= full_turn(unit);
  std::vector<double> out = convert(from, to, values);
  std::string line;
  for (size_t i = 0; i < out.size(); ++i) {
    std::string text = format_number(out[i]);
    if (int(i) == hue_index(to)) {
      // Hues print in [0, full turn): wrapped (also when from == to), and 0 where printing would round up to a turn.
      text = format_number(wrap_hue(out[i]) * full_turn(unit));
      if (std::stod(text) >= full_turn(unit)) text = "0";
    }
    line += (i ? "," : "") + text;
  }
  return line;
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (ColorModel m : kColorModels) names.emplace_back(model_name(m));
  return names;
}

}  // namespace

void setup_color(CLI::App& color, CommonOptions&) {
  color.require_subcommand(1);
  CLI::App* convert_cmd = color.add_subcommand(
      "convert", "Convert colors between models: --values a,b,c, or CSV rows on stdin to stdout, one per line");
  auto opt = std::make_shared<ConvertOptions>();
  const std::vector<std::string> names = model_names();
  convert_cmd->add_option("--from", opt->from, "Model of the input")->required()->check(CLI::IsMember(names));
  convert_cmd->add_option("--to", opt->to, "Model of the output")->required()->check(CLI::IsMember(names));
  convert_cmd->add_option("--values", opt->values, "One color as comma-separated numbers (else stdin rows)");
  convert_cmd->add_option("--hue", opt->hue, "Unit of HSV/HLS hue in input and output")
      ->check(CLI::IsMember({"degrees", "turns", "radians"}))
      ->capture_default_str();
  convert_cmd->footer(
      "Models: rgb (linear, [0,1]) cmy cmyk hsv hls yiq xyz xyy srgb. Hue in [0,360) degrees unless --hue.\n"
      "Example: echo 1,0.5,0 | tessera color convert --from rgb --to hsv   ->   30,1,1");
  convert_cmd->callback([opt] {
    const ColorModel from = parse_color_model(opt->from), to = parse_color_model(opt->to);
    const HueUnit unit = parse_hue_unit(opt->hue);
    if (!opt->values.empty()) {
      fmt::print("{}\n", convert_row(parse_row(opt->values, from, "--values"), from, to, unit));
      return;
    }
    std::string row;
    for (long line = 1; std::getline(std::cin, row); ++line) {
      if (trim(row).empty()) {
        fmt::print("\n");  // blank rows stay blank, so output line k answers input line k
        continue;
      }
      fmt::print("{}\n", convert_row(parse_row(row, from, at_line("stdin", line)), from, to, unit));
    }
  });
}

}  // namespace tessera::cli
