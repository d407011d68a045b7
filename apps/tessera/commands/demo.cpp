// tessera demo [-o DIR]: the embedded default, renders the built-in demo pictures (for now the whole gallery).
#include <fmt/format.h>

#include "command.hpp"
#include "gallery.hpp"

namespace tessera::cli {

void setup_demo(CLI::App& cmd, CommonOptions& common) {
  auto output = std::make_shared<std::string>("out");
  cmd.add_option("-o,--output", *output, "Folder for the pictures")->capture_default_str();
  cmd.callback([output, &common] {
    const size_t n = examples::run_examples(*output);
    if (common.stats) print_stats({{"pictures", stat_value(double(n))}});
    else fmt::print("{} pictures written to {}/ (open {}/index.html)\n", n, *output, *output);
  });
}

}  // namespace tessera::cli
