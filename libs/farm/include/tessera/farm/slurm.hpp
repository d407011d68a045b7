#pragma once
// Slurm job arrays for `tessera farm slurm` (docs/farm.md): one array task per frame (or run of frames) and tile, each
// running `tessera render ... --frame F [--tile K/N] --skip-existing`, and a job that runs after the whole array
// succeeded to stitch the tiles and encode the movie. Slurm schedules; Tessera only writes the scripts.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/farm/frames.hpp"

namespace tessera {

/// What to render on the cluster and how to ask Slurm for it.
struct SlurmJob {
  std::filesystem::path tessera;            ///< the tessera executable the tasks run (absolute: tasks start elsewhere)
  std::string scene;                        ///< a scene file (absolute path) or a built-in scene's name
  std::filesystem::path output;             ///< the frames' numbered file name (absolute), as render -o takes it
  FrameRange frames;                        ///< the frames to render
  int tiles = 1;                            ///< tiles per frame (render --tile K/N)
  int frames_per_task = 1;                  ///< consecutive frames one task renders (whole frames only: tiles == 1)
  std::vector<std::string> render_options;  ///< more render arguments, one word each ("--spp", "64")
  std::filesystem::path movie;              ///< a movie the assemble job encodes from the frames; empty for none
  double fps = 24;                          ///< the movie's frame rate
  std::string partition;                    ///< sbatch --partition; empty: the cluster's default
  std::string time_limit;                   ///< sbatch --time per task ("00:30:00"); empty: the partition's default
  std::string account;                      ///< sbatch --account; empty: the user's default
  int cpus_per_task = 0;                    ///< sbatch --cpus-per-task, also render --threads; 0: Slurm's default
  int max_running = 0;                      ///< at most this many tasks at once (--array=...%N); 0: no limit
  std::filesystem::path log_folder;         ///< where task logs go (absolute)
};

/// Array tasks the job needs: ceil(frames / frames_per_task) x tiles. Throws InvalidInput when frames_per_task > 1
/// with tiles, or when the count passes Slurm's default MaxArraySize (1001 tasks: raise frames_per_task).
int slurm_task_count(const SlurmJob& job);

/// The sbatch script of the render array: task i renders frame (run) i / tiles and tile i % tiles.
std::string slurm_render_script(const SlurmJob& job);

/// The sbatch script of the job that follows the array (submitted with --dependency=afterok): `tessera assemble` of
/// the tiles and the movie, if any.
std::string slurm_assemble_script(const SlurmJob& job);

/// `text` quoted for bash (single quotes; a quote inside becomes '\'').
std::string shell_quote(std::string_view text);

}  // namespace tessera
