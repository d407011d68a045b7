// tessera assemble PATTERN --frames A:B --tiles N [--movie OUT]: stitch the tiles `tessera render --tile K/N` wrote
// into whole frames, checking each tile against the folder's manifest, and optionally encode the frames as a movie
// (docs/farm.md).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/farm/frames.hpp"
#include "tessera/farm/manifest.hpp"
#include "tessera/image/animation.hpp"
#include "tessera/image/image_io.hpp"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

struct AssembleArgs {
  std::string pattern, frames, movie;
  int tiles = 1;
  double fps = 24;
};

void run_assemble(const AssembleArgs& a, const CommonOptions& common) {
  const FrameRange range = parse_frame_range(a.frames, "--frames");
  if (a.tiles < 1 || a.tiles > 4096) throw InvalidInput(fmt::format("--tiles: expected 1 to 4096, got {}", a.tiles));
  const fs::path pattern(a.pattern);
  if (range.count() > 1 && numbered_frame_path(pattern, 0) == pattern)
    throw InvalidInput(fmt::format("{}: several frames need a numbered file name (frame_%04d.png)", a.pattern));
  if (!a.movie.empty()) animation_format(a.movie);  // an unknown movie format fails before any work
  const fs::path folder = pattern.parent_path().empty() ? fs::path(".") : pattern.parent_path();
  PhaseTimer timer;
  const Manifest manifest = timer.time("read_s", [&] { return Manifest::read(folder); });
  // Every tile must be there and, where the manifest has it, be the file its task wrote: all are checked before any
  // frame is written, so a failed assembly names everything missing at once.
  std::string problems;
  int problem_count = 0;
  timer.time("read_s", [&] {
    for (int f = range.first; f <= range.last; ++f)
      for (int k = 0; k < a.tiles; ++k) {  // with one tile: the frame file itself
        const std::string name = tile_file(numbered_frame_path(pattern, f), {k, a.tiles}).filename().string();
        std::error_code ec;
        const char* problem = !fs::is_regular_file(folder / name, ec)                   ? "missing"
                              : manifest.find(name) && !manifest.verified(folder, name) ? "differs from frames.json"
                                                                                        : nullptr;
        if (problem && ++problem_count <= 20) problems += fmt::format("\n  {}: {}", name, problem);
      }
  });
  if (problem_count > 0)
    throw IoError(fmt::format("assemble: {} tile{} of frames {}:{} cannot be used:{}{}", problem_count,
                              problem_count == 1 ? "" : "s", range.first, range.last, problems,
                              problem_count > 20 ? "\n  ..." : ""));
  std::optional<AnimationWriter> writer;
  if (!a.movie.empty()) writer.emplace(a.movie, AnimationOptions{.fps = a.fps, .srgb = false});
  for (int f = range.first; f <= range.last; ++f) {
    const fs::path frame = numbered_frame_path(pattern, f);
    if (a.tiles > 1) timer.time("compute_s", [&] { assemble_tiles(frame, a.tiles); });
    if (writer) timer.time("write_s", [&] { writer->add(read_image(frame)); });
  }
  if (writer) timer.time("write_s", [&] { writer->finish(); });
  if (!common.stats) return;
  StatRows figures = {{"frames", stat_value(range.count())}, {"tiles", stat_value(a.tiles)}};
  const StatRows phases = timer.rows();
  figures.insert(figures.end(), phases.begin(), phases.end());
  print_stats(figures);
}

}  // namespace

void setup_assemble(CLI::App& cmd, CommonOptions& common) {
  auto a = std::make_shared<AssembleArgs>();
  cmd.add_option("pattern", a->pattern, "The frames' numbered file name, as given to render -o (frames/frame_%04d.png)")
      ->required();
  cmd.add_option("--frames", a->frames, "Frames A:B (or one frame N)")->required();
  cmd.add_option("--tiles", a->tiles, "Tiles per frame, as render --tile K/N was given N (1: frames are whole)");
  cmd.add_option("--movie", a->movie, "Also encode the frames as a movie (.gif, .mp4, .mov, .mkv, .webm)");
  cmd.add_option("--fps", a->fps, "Frames per second of the movie")->check(positive());
  cmd.callback([a, &common] { run_assemble(*a, common); });
}

}  // namespace tessera::cli
