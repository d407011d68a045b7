// tessera gallery -o DIR [--only PREFIX...] [--data DIR]: every example and algorithm as a picture, with an index.html.
#include "gallery.hpp"

#include <fmt/format.h>

#include "command.hpp"
#include "data_option.hpp"

namespace tessera::cli {

void setup_gallery(CLI::App& cmd, CommonOptions& common) {
  struct Options {
    std::string output = "gallery";
    std::vector<std::string> only;
    std::string data;
  };
  auto opt = std::make_shared<Options>();
  cmd.add_option("-o,--output", opt->output, "Folder for the pictures and index.html")->capture_default_str();
  cmd.add_option("--only", opt->only, "Only examples whose name starts with these prefixes (e.g. 01 07)")
      ->check(CLI::Validator(
          [](std::string& prefix) -> std::string {
            std::string numbers;  // the examples' numbers, for the message
            for (const examples::Example& e : examples::all_examples()) {
              const std::string name = e.name;
              if (name.rfind(prefix, 0) == 0) return "";
              numbers += (numbers.empty() ? "" : " ") + name.substr(0, 2);
            }
            return fmt::format("no example's name starts with '{}' (the examples are {})", prefix, numbers);
          },
          "PREFIX"));
  add_data_option(cmd, opt->data);
  add_srgb_option(cmd, common);
  cmd.callback([opt, &common] {
    const examples::DataFolder data = examples::locate_shared_data(opt->data);
    const examples::RunSummary run = examples::run_examples(opt->output, {opt->only, data, common.write_options()});
    if (common.stats)
      print_stats({{"pictures", stat_value(double(run.pictures))}, {"stand_ins", stat_value(double(run.stand_ins))}});
    else
      fmt::print("{} pictures written to {}/index.html{}\n", run.pictures, opt->output, stand_in_note(run, data));
  });
}

}  // namespace tessera::cli
