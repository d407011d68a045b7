// tessera farm slurm|status: render an animation as a Slurm job array and follow it through the frames manifest
// (docs/farm.md).
#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/farm/frames.hpp"
#include "tessera/farm/manifest.hpp"
#include "tessera/farm/slurm.hpp"
#include "tessera/image/animation.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

struct SlurmArgs {
  std::string scene, output, frames, movie, partition, time_limit, account, size, backend;
  int tiles = 1, frames_per_task = 1, cpus_per_task = 0, max_running = 0;
  std::optional<int> spp, depth;
  std::optional<uint64_t> seed;
  std::optional<double> fps;
  bool submit = false;
};

// Runs `command` through the shell and returns its standard output; throws IoError with `what` when it fails.
std::string run_shell(const std::string& command, const std::string& what) {
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw IoError(fmt::format("{}: cannot run a shell", what));
  std::string out;
  char buffer[4096];
  while (const size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = ::pclose(pipe);
  if (status != 0)
    throw IoError(fmt::format("{} failed ({}): {}", what,
                              WIFEXITED(status) ? fmt::format("exit {}", WEXITSTATUS(status)) : "killed",
                              printable(trim(out), 400)));
  return std::string(trim(out));
}

// sbatch --parsable prints "jobid" or "jobid;cluster".
std::string submit(const fs::path& script, const std::string& dependency) {
  const std::string command =
      fmt::format("sbatch --parsable{} {} 2>&1", dependency.empty() ? "" : " --dependency=afterok:" + dependency,
                  shell_quote(script.string()));
  const std::string out = run_shell(command, fmt::format("sbatch {}", script.string()));
  return out.substr(0, out.find(';'));
}

void run_farm_slurm(const SlurmArgs& a, const CommonOptions& common) {
  SlurmJob job;
  job.frames = parse_frame_range(a.frames, "--frames");
  job.tiles = a.tiles;
  job.frames_per_task = a.frames_per_task;
  if (a.tiles < 1 || a.tiles > 4096) throw InvalidInput(fmt::format("--tiles: expected 1 to 4096, got {}", a.tiles));
  job.output = fs::absolute(a.output).lexically_normal();
  if (job.frames.count() > 1 && numbered_frame_path(job.output, 0) == job.output)
    throw InvalidInput(fmt::format("-o {}: several frames need a numbered file name (frame_%04d.png)", a.output));
  if (a.tiles > 1) check_lossless_image_path(job.output);
  if (!a.movie.empty()) {
    animation_format(a.movie);
    job.movie = fs::absolute(a.movie).lexically_normal();
  }
  // The scene is checked here, where a mistake costs nothing, rather than in a thousand tasks.
  const AnimatedScene scene = load_animated_scene(a.scene);
  if (job.frames.first < scene.animation().first || job.frames.last > scene.animation().last)
    throw InvalidInput(fmt::format("--frames {}:{}: the scene '{}' has frames {}:{}", job.frames.first, job.frames.last,
                                   a.scene, scene.animation().first, scene.animation().last));
  job.scene = fs::exists(a.scene) ? fs::absolute(a.scene).lexically_normal().string() : a.scene;
  job.tessera = fs::read_symlink("/proc/self/exe");
  job.fps = a.fps.value_or(scene.animation().fps);
  // Values written into #SBATCH lines: one word of Slurm's characters (a newline would add lines to the script).
  for (const auto& [flag, value] :
       {std::pair{"--partition", &a.partition}, std::pair{"--time", &a.time_limit}, std::pair{"--account", &a.account}})
    if (value->find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.:,+-") !=
        std::string::npos)
      throw InvalidInput(fmt::format("{}: expected a Slurm name or time (letters, digits, _ . : , + -), got '{}'", flag,
                                     printable(*value)));
  if (a.cpus_per_task < 0 || a.max_running < 0)
    throw InvalidInput("--cpus-per-task and --max-running: expected a positive number (0: Slurm's default)");
  job.partition = a.partition;
  job.time_limit = a.time_limit;
  job.account = a.account;
  job.cpus_per_task = a.cpus_per_task;
  job.max_running = a.max_running;
  if (a.spp) job.render_options.insert(job.render_options.end(), {"--spp", std::to_string(*a.spp)});
  if (a.depth) job.render_options.insert(job.render_options.end(), {"--depth", std::to_string(*a.depth)});
  if (a.seed) job.render_options.insert(job.render_options.end(), {"--seed", std::to_string(*a.seed)});
  if (!a.size.empty()) job.render_options.insert(job.render_options.end(), {"--size", a.size});
  if (!a.backend.empty()) job.render_options.insert(job.render_options.end(), {"--backend", a.backend});
  if (common.srgb) job.render_options.emplace_back("--srgb");
  const fs::path folder = job.output.parent_path() / "slurm";
  job.log_folder = folder / "logs";
  const int tasks = slurm_task_count(job);
  const bool follow_up = job.tiles > 1 || !job.movie.empty();
  fs::create_directories(job.log_folder);
  const fs::path render_script = folder / "render.sbatch", assemble_script = folder / "assemble.sbatch";
  write_file_atomic(render_script, slurm_render_script(job));
  if (follow_up)
    write_file_atomic(assemble_script, slurm_assemble_script(job));
  else
    fs::remove(assemble_script);  // a stale one from an earlier run with tiles or a movie
  std::string report =
      fmt::format("tessera farm: {} ({} array task{}){}\n", render_script.string(), tasks, tasks == 1 ? "" : "s",
                  follow_up ? fmt::format(", then {}", assemble_script.string()) : "");
  StatRows stats = {{"tasks", stat_value(tasks)}};
  if (a.submit) {
    const std::string render_id = submit(render_script, "");
    report += fmt::format("submitted render job {}\n", render_id);
    stats.emplace_back("render_job", render_id);
    if (follow_up) {
      const std::string assemble_id = submit(assemble_script, render_id);
      report += fmt::format("submitted assemble job {} (after job {} succeeds)\n", assemble_id, render_id);
      stats.emplace_back("assemble_job", assemble_id);
    }
  } else {
    report += fmt::format(
        "submit with: sbatch {}{}\n", shell_quote(render_script.string()),
        follow_up ? fmt::format(", then sbatch --dependency=afterok:<job id> {}", shell_quote(assemble_script.string()))
                  : "");
  }
  if (common.stats)
    print_stats(stats);
  else if (!common.quiet)
    std::fputs(report.c_str(), stderr);
}

struct StatusArgs {
  std::string output, frames;
  int tiles = 1;
};

// Counts the frames (or tiles) of a farm's output that are written whole, missing or damaged.
void run_farm_status(const StatusArgs& a, const CommonOptions& common) {
  const FrameRange range = parse_frame_range(a.frames, "--frames");
  if (a.tiles < 1 || a.tiles > 4096) throw InvalidInput(fmt::format("--tiles: expected 1 to 4096, got {}", a.tiles));
  const fs::path pattern(a.output);
  const fs::path folder = pattern.parent_path().empty() ? fs::path(".") : pattern.parent_path();
  const Manifest manifest = Manifest::read(folder);
  int done = 0, missing = 0, damaged = 0;
  double seconds = 0;
  std::string missing_list;
  for (int f = range.first; f <= range.last; ++f)
    for (int k = 0; k < a.tiles; ++k) {
      const fs::path frame = numbered_frame_path(pattern, f);
      const std::string name = tile_file(frame, {k, a.tiles}).filename().string();
      std::error_code ec;
      // Files are written whole (atomically), so one without an entry is done, as for render --skip-existing; so
      // is a tile whose stitched frame is there.
      const bool recorded = manifest.find(name) != nullptr;
      const bool unrecorded =
          !recorded && (fs::is_regular_file(folder / name, ec) || (a.tiles > 1 && fs::is_regular_file(frame, ec)));
      if (manifest.verified(folder, name)) {
        ++done;
        seconds += manifest.find(name)->seconds;
      } else if (unrecorded) {
        ++done;
      } else if (recorded && fs::exists(folder / name, ec)) {
        ++damaged;
      } else {
        if (++missing <= 10) missing_list += " " + name;
      }
    }
  const int parts = range.count() * a.tiles;
  if (common.stats) {
    print_stats({{"parts", stat_value(parts)},
                 {"done", stat_value(done)},
                 {"missing", stat_value(missing)},
                 {"damaged", stat_value(damaged)},
                 {"render_s", stat_value(seconds)}});
    return;
  }
  std::string text = fmt::format("frames {}:{}{}: {} of {} done, {} missing, {} damaged; {:.1f} s of rendering\n",
                                 range.first, range.last, a.tiles > 1 ? fmt::format(" x {} tiles", a.tiles) : "", done,
                                 parts, missing, damaged, seconds);
  if (missing > 0) text += fmt::format("missing:{}{}\n", missing_list, missing > 10 ? " ..." : "");
  std::fputs(text.c_str(), stdout);
}

void setup_farm_slurm(CLI::App& farm, CommonOptions& common) {
  auto a = std::make_shared<SlurmArgs>();
  auto* cmd = farm.add_subcommand("slurm", "Write (and with --submit, submit) a Slurm job array rendering the frames");
  cmd->add_option("scene", a->scene, "Scene file or built-in scene (tessera render --list)")->required();
  cmd->add_option("-o,--output", a->output, "The frames' numbered file name (frames/frame_%04d.png)")->required();
  cmd->add_option("--frames", a->frames, "Frames A:B (or one frame N)")->required();
  cmd->add_option("--tiles", a->tiles, "Split each frame into N tiles, one task each; a follow-up job stitches them");
  cmd->add_option("--frames-per-task", a->frames_per_task, "Consecutive frames per task (whole frames only)");
  cmd->add_option("--movie", a->movie, "Also encode a movie (.gif, .mp4, ...) in the follow-up job");
  cmd->add_option("--fps", a->fps, "The movie's frame rate (default: the scene's)")->check(positive());
  cmd->add_option("--partition", a->partition, "sbatch --partition");
  cmd->add_option("--time", a->time_limit, "sbatch --time per task (e.g. 00:30:00)");
  cmd->add_option("--account", a->account, "sbatch --account");
  cmd->add_option("--cpus-per-task", a->cpus_per_task, "sbatch --cpus-per-task (render --threads follows it)");
  cmd->add_option("--max-running", a->max_running, "At most this many tasks at once (sbatch --array=...%N)");
  cmd->add_option("--spp", a->spp, "render --spp");
  cmd->add_option("--size", a->size, "render --size WxH")->check(size_format());
  cmd->add_option("--depth", a->depth, "render --depth");
  cmd->add_option("--seed", a->seed, "render --seed");
  cmd->add_option("--backend", a->backend, "render --backend")->check(CLI::IsMember({"raytrace", "raster"}));
  cmd->add_flag("--submit", a->submit, "Submit the jobs with sbatch (the array, then the follow-up job after it)");
  add_srgb_option(*cmd, common);
  cmd->callback([a, &common] { run_farm_slurm(*a, common); });
}

void setup_farm_status(CLI::App& farm, CommonOptions& common) {
  auto a = std::make_shared<StatusArgs>();
  auto* cmd = farm.add_subcommand("status", "How much of a farm's output is written whole (from frames.json)");
  cmd->add_option("output", a->output, "The frames' numbered file name, as given to farm slurm -o")->required();
  cmd->add_option("--frames", a->frames, "Frames A:B (or one frame N)")->required();
  cmd->add_option("--tiles", a->tiles, "Tiles per frame");
  cmd->callback([a, &common] { run_farm_status(*a, common); });
}

}  // namespace

void setup_farm(CLI::App& farm, CommonOptions& common) {
  farm.require_subcommand(1);
  setup_farm_slurm(farm, common);
  setup_farm_status(farm, common);
}

}  // namespace tessera::cli
