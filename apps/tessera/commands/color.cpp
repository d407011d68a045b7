// tessera color convert --from M --to M [--values a,b,c] [--hue degrees|turns|radians] [--stats]: color-model
// conversions of one color (--values, whose errors are usage errors) or of CSV rows read from stdin (errors name the
// line), one converted row per line on stdout (docs/color.md).
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
#include "tessera/core/parse.hpp"

namespace tessera::cli {
namespace {

struct ConvertOptions {
  ColorModel from = ColorModel::rgb, to = ColorModel::rgb;
  std::string values;  // empty: read stdin
  HueUnit hue = HueUnit::degrees;
};

// Whether the model's components (but a hue, which wraps) all lie in [0, 1]: RGB, CMY(K), sRGB, HSV, HLS. YIQ's
// chroma is signed and XYZ/xyY are unbounded, so they are not checked.
bool unit_range(ColorModel model) {
  return model != ColorModel::yiq && model != ColorModel::xyz && model != ColorModel::xyy;
}

// Parses one row of component_count(model) comma-separated numbers, each in the model's range; `where` names it in the
// error.
std::vector<double> parse_row(const std::string& row, ColorModel model, const std::string& where) {
  const size_t n = size_t(component_count(model));
  std::vector<double> values;
  try {
    values = parse_doubles(row, n, where);
  } catch (const InvalidInput&) {
    throw InvalidInput(fmt::format("{}: expected {} comma-separated numbers, got '{}'", where, n, printable(row)));
  }
  if (unit_range(model))
    for (size_t i = 0; i < n; ++i)
      if (int(i) != hue_index(model) && !(values[i] >= 0 && values[i] <= 1))
        throw InvalidInput(fmt::format("{}: {} components must be in [0, 1]{}, got '{}'", where, model_name(model),
                                       hue_index(model) >= 0 ? " (but the hue)" : "", printable(row)));
  return values;
}

// One number with up to 9 significant digits; magnitudes below 1e-12 (round-off around 0) print as 0.
std::string format_number(double v) {
  if (std::abs(v) < 1e-12) return "0";
  return fmt::format("{:.9g}", v);
}

// Converts one row; the hue component (if any) is read and written in `unit`. Returns the output line; errors name
// `where`.
std::string convert_row(const std::vector<double>& in, ColorModel from, ColorModel to, HueUnit unit,
                        const std::string& where) {
  std::vector<double> values = in;
  if (hue_index(from) >= 0) values[size_t(hue_index(from))] /= full_turn(unit);
  std::vector<double> out;
  try {
    out = convert(from, to, values);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: {}", where, e.what()));
  }
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

std::vector<std::pair<std::string, ColorModel>> model_names() {
  std::vector<std::pair<std::string, ColorModel>> names;
  for (ColorModel m : kColorModels) names.emplace_back(model_name(m), m);
  return names;
}

}  // namespace

void setup_color(CLI::App& color, CommonOptions& common) {
  color.require_subcommand(1);
  CLI::App* convert_cmd = color.add_subcommand(
      "convert", "Convert colors between models: --values a,b,c, or CSV rows on stdin to stdout, one per line");
  auto opt = std::make_shared<ConvertOptions>();
  add_choice(*convert_cmd, "--from", opt->from, model_names(), "Model of the input")->required();
  add_choice(*convert_cmd, "--to", opt->to, model_names(), "Model of the output")->required();
  convert_cmd->add_option("--values", opt->values, "One color as comma-separated numbers (else stdin rows)");
  add_choice(*convert_cmd, "--hue", opt->hue,
             {{"degrees", HueUnit::degrees}, {"turns", HueUnit::turns}, {"radians", HueUnit::radians}},
             "Unit of HSV/HLS hue in input and output");
  convert_cmd->footer(
      "Models: rgb (linear, [0,1]) cmy cmyk hsv hls yiq xyz xyy srgb. Hue in [0,360) degrees unless --hue.\n"
      "Stats (--stats, after the rows): colors compute_s total_s.\n"
      "Example: echo 1,0.5,0 | tessera color convert --from rgb --to hsv   ->   30,1,1");
  convert_cmd->callback([opt, &common] {
    const ColorModel from = opt->from, to = opt->to;
    PhaseTimer timer;
    long colors = 0;
    if (!opt->values.empty()) {
      // --values depends on --from for its count, so it is checked here, as a usage error all the same.
      std::string line;
      try {
        line = timer.time("compute_s", [&] {
          return convert_row(parse_row(opt->values, from, "--values"), from, to, opt->hue, "--values");
        });
      } catch (const InvalidInput& e) {
        throw CLI::ValidationError(e.what());
      }
      fmt::print("{}\n", line);
      colors = 1;
    } else {
      std::string row;
      for (long line = 1; std::getline(std::cin, row); ++line) {
        if (trim(row).empty()) {
          fmt::print("\n");  // blank rows stay blank, so output line k answers input line k
          continue;
        }
        const std::string where = at_line("stdin", line);
        fmt::print("{}\n", timer.time("compute_s", [&] {
          return convert_row(parse_row(row, from, where), from, to, opt->hue, where);
        }));
        ++colors;
      }
    }
    if (common.stats) {
      StatRows rows{{"colors", stat_value(double(colors))}};
      for (const auto& r : timer.rows()) rows.push_back(r);
      print_stats(rows);
    }
  });
}

}  // namespace tessera::cli
