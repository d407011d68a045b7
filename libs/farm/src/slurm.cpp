#include "tessera/farm/slurm.hpp"

#include <fmt/format.h>

#include "tessera/core/error.hpp"

namespace tessera {

namespace {

constexpr int kMaxArraySize = 1001;  // Slurm's default MaxArraySize: task ids 0..1000

// The #SBATCH lines both scripts share.
std::string sbatch_header(const SlurmJob& job, std::string_view name, std::string_view log) {
  std::string s =
      fmt::format("#!/bin/bash\n#SBATCH --job-name={}\n#SBATCH --output={}\n", name, (job.log_folder / log).string());
  if (!job.partition.empty()) s += fmt::format("#SBATCH --partition={}\n", job.partition);
  if (!job.account.empty()) s += fmt::format("#SBATCH --account={}\n", job.account);
  if (!job.time_limit.empty()) s += fmt::format("#SBATCH --time={}\n", job.time_limit);
  return s;
}

}  // namespace

std::string shell_quote(std::string_view text) {
  std::string quoted = "'";
  for (const char c : text) {
    if (c == '\'')
      quoted += "'\\''";  // close the quote, an escaped quote, reopen
    else
      quoted += c;
  }
  return quoted + "'";
}

int slurm_task_count(const SlurmJob& job) {
  if (job.frames_per_task < 1) throw InvalidInput("--frames-per-task: expected at least 1");
  if (job.frames_per_task > 1 && job.tiles > 1)
    throw InvalidInput("--frames-per-task: a task renders whole frames; with --tiles each task renders one tile");
  const long long runs = (job.frames.count() + job.frames_per_task - 1) / job.frames_per_task;
  const long long tasks = runs * job.tiles;
  if (tasks > kMaxArraySize)
    throw InvalidInput(
        fmt::format("{} array tasks ({} frames{}) pass Slurm's default MaxArraySize of {}: render "
                    "several frames per task (--frames-per-task {})",
                    tasks, job.frames.count(), job.tiles > 1 ? fmt::format(" x {} tiles", job.tiles) : "",
                    kMaxArraySize, (job.frames.count() * job.tiles + kMaxArraySize - 1) / kMaxArraySize));
  return int(tasks);
}

std::string slurm_render_script(const SlurmJob& job) {
  const int tasks = slurm_task_count(job);
  std::string s = sbatch_header(job, "tessera-render", "render-%A_%a.log");
  s += fmt::format("#SBATCH --array=0-{}{}\n", tasks - 1,
                   job.max_running > 0 ? fmt::format("%{}", job.max_running) : "");
  if (job.cpus_per_task > 0) s += fmt::format("#SBATCH --cpus-per-task={}\n", job.cpus_per_task);
  s +=
      "# Written by `tessera farm slurm` (docs/farm.md). Each task renders its part of the animation; --skip-existing\n"
      "# makes a resubmitted or requeued task skip frames and tiles already written whole (frames.json).\n"
      "set -euo pipefail\n";
  s += fmt::format("task=$SLURM_ARRAY_TASK_ID\nfirst=$(( {} + task / {} * {} ))\n", job.frames.first, job.tiles,
                   job.frames_per_task);
  s += fmt::format("last=$(( first + {} ))\nif (( last > {} )); then last={}; fi\n", job.frames_per_task - 1,
                   job.frames.last, job.frames.last);
  std::string command = fmt::format("{} render {} -o {} --frames \"$first:$last\"", shell_quote(job.tessera.string()),
                                    shell_quote(job.scene), shell_quote(job.output.string()));
  if (job.tiles > 1) command += fmt::format(" --tile \"$(( task % {} ))/{}\"", job.tiles, job.tiles);
  command += " --skip-existing --progress plain";
  if (job.cpus_per_task > 0) command += " --threads \"$SLURM_CPUS_PER_TASK\"";
  for (const std::string& option : job.render_options) command += fmt::format(" {}", shell_quote(option));
  return fmt::format("{}exec {}\n", s, command);
}

std::string slurm_assemble_script(const SlurmJob& job) {
  std::string s = sbatch_header(job, "tessera-assemble", "assemble-%j.log");
  s += "# Written by `tessera farm slurm`: runs after every render task succeeded (--dependency=afterok).\n"
       "set -euo pipefail\n";
  s += fmt::format("exec {} assemble {} --frames {}:{} --tiles {}", shell_quote(job.tessera.string()),
                   shell_quote(job.output.string()), job.frames.first, job.frames.last, job.tiles);
  if (!job.movie.empty()) s += fmt::format(" --movie {} --fps {}", shell_quote(job.movie.string()), job.fps);
  return s + "\n";
}

}  // namespace tessera
