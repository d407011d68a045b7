// tessera gallery -o DIR [--only PREFIX...]: every example and algorithm as a picture, with an index.html.
#include <fmt/format.h>

#include "command.hpp"
#include "gallery.hpp"

namespace tessera::cli {

void setup_gallery(CLI::App& cmd, CommonOptions& common) {
  struct Options {
    std::string output = "gallery";
    std::vector<std::string> only;
  };
  auto opt = std::make_shared<Options>();
  cmd.add_option("-o,--output", opt->output, "Folder for the pictures and index.html")->capture_default_str();
  cmd.add_option("--only", opt->only, "Only examples whose name starts with these prefixes (e.g. 01 07)");
  cmd.callback([opt, &common] {
    const size_t n = examples::run_examples(opt->output, opt->only);
    if (common.stats) print_stats({{"pictures", stat_value(double(n))}});
    else fmt::print("{} pictures written to {}/index.html\n", n, opt->output);
  });
}

}  // namespace tessera::cli
