// The main of each numbered example program: runs the example(s) linked into it and writes the pictures into the
// folder given as the first argument (default: the current folder). The shared data is found as `tessera gallery`
// finds it without --data (locate_shared_data).
//
// With --compare REFDIR (the example's ctest), each picture is then compared with REFDIR/<file> (docs/gallery, the
// reviewed references) within a Tolerance (--levels N, --pixels FRACTION, --min-psnr DB). Exit status: 0 when every
// picture matches, 1 when one differs or has no reference, 77 (ctest's SKIP_RETURN_CODE) when every picture was drawn
// with a stand-in for missing shared data, so that nothing could be compared.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "gallery.hpp"
#include "tessera/core/error.hpp"

namespace {

using namespace tessera::examples;

constexpr int kSkipped = 77;

struct Arguments {
  std::filesystem::path out = ".";
  std::filesystem::path references;  // empty: no comparison
  Tolerance tolerance;
};

Arguments parse(int argc, char** argv) {
  Arguments args;
  bool out_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw tessera::InvalidInput(fmt::format("{} needs a value", arg));
      return argv[++i];
    };
    if (arg == "--compare")
      args.references = value();
    else if (arg == "--levels")
      args.tolerance.levels = std::stoi(value());
    else if (arg == "--pixels")
      args.tolerance.pixels = std::stod(value());
    else if (arg == "--min-psnr")
      args.tolerance.min_psnr = std::stod(value());
    else if (!arg.starts_with("--") && !out_given)
      args.out = arg, out_given = true;
    else
      throw tessera::InvalidInput(fmt::format("unknown argument '{}'", arg));
  }
  return args;
}

// Compares every picture of `summary` with its reference; returns the exit status.
int compare(const RunSummary& summary, const Arguments& args) {
  int failed = 0, compared = 0, skipped = 0;
  for (const Picture& picture : summary.written) {
    const std::filesystem::path reference = args.references / picture.file;
    if (is_stand_in(picture)) {
      std::printf("%s: comparison skipped: drawn with a stand-in for missing shared data (set TESSERA_DATA)\n",
                  picture.file.c_str());
      ++skipped;
      continue;
    }
    if (!std::filesystem::exists(reference)) {
      std::printf("%s: FAILED: no reference %s (render it, look at it, copy it there)\n", picture.file.c_str(),
                  reference.c_str());
      ++failed;
      continue;
    }
    const Comparison result = compare_picture(tessera::to_rgba8(tessera::read_image(args.out / picture.file)),
                                              tessera::to_rgba8(tessera::read_image(reference)), args.tolerance);
    std::printf("%s: %s: %s\n", picture.file.c_str(), result.passed ? "matches" : "FAILED", result.message.c_str());
    failed += !result.passed;
    ++compared;
  }
  if (failed > 0) {
    std::printf("%d picture(s) differ from their references in %s\n", failed, args.references.c_str());
    return 1;
  }
  return compared == 0 && skipped > 0 ? kSkipped : 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Arguments args = parse(argc, argv);
    const RunSummary summary = run_examples(args.out);
    std::printf("%zu picture(s) written\n", summary.pictures);
    if (summary.pictures == 0) return 1;
    return args.references.empty() ? 0 : compare(summary, args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "example: error: %s\n", e.what());
    return 1;
  }
}
