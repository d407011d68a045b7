// tessera mesh subdivide IN -o OUT --scheme midpoint|loop|catmull-clark --levels N [--boundary
// edge-only|edge-and-corner]
//                        [--crease-method uniform|chaikin] [--loop-beta notes|loop] [--limit] [--ascii] [--double]
//                        [--stats]
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "commands/mesh_output.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/subdiv/limit.hpp"
#include "tessera/subdiv/subdivide.hpp"

namespace tessera::cli {
namespace {

struct SubdivideArgs {
  std::string input;
  MeshOutput output;
  SubdivisionOptions options;
  bool limit = false;
};

}  // namespace

void setup_mesh_subdivide(CLI::App& mesh, CommonOptions& common) {
  auto args = std::make_shared<SubdivideArgs>();
  CLI::App* cmd = mesh.add_subcommand(
      "subdivide", "Subdivision surfaces: midpoint (face) subdivision, Loop, Catmull-Clark with creases and corners");
  cmd->add_option("input", args->input, "Input mesh (OBJ, PLY, OFF, STL; OBJ `t crease`/`t corner` tags are used)")
      ->required();
  add_mesh_output(*cmd, args->output);
  add_choice(*cmd, "--scheme", args->options.scheme,
             {{"midpoint", SubdivisionScheme::midpoint},
              {"loop", SubdivisionScheme::loop},
              {"catmull-clark", SubdivisionScheme::catmull_clark}},
             "Subdivision scheme");
  cmd->add_option("--levels", args->options.levels, "Refinement steps (default 1)")->check(CLI::Range(0, 12));
  add_choice(
      *cmd, "--boundary", args->options.boundary,
      {{"edge-only", BoundaryInterpolation::edge_only}, {"edge-and-corner", BoundaryInterpolation::edge_and_corner}},
      "edge-only: boundary vertices follow the crease rule; edge-and-corner: vertices with one face stay put");
  add_choice(*cmd, "--crease-method", args->options.crease_method,
             {{"uniform", CreaseMethod::uniform}, {"chaikin", CreaseMethod::chaikin}},
             "How semi-sharp creases decay: uniform (s - 1 per level) or chaikin");
  add_choice(*cmd, "--loop-beta", args->options.loop_weights,
             {{"notes", LoopWeights::warren}, {"loop", LoopWeights::loop}},
             "Loop's vertex weight: notes (3/(8k), Warren) or loop (Loop's original, as OpenSubdiv)");
  cmd->add_flag("--limit", args->limit, "Move the vertices to their limit positions and add limit normals");
  cmd->footer(
      "Texture coordinates are carried: per-vertex ones with the scheme's masks, per-corner ones (seams) linearly\n"
      "inside each face (OpenSubdiv's FVAR_LINEAR_ALL). Normals do not subdivide: an input with normals gets the\n"
      "refined mesh's area-weighted vertex normals (--limit: the limit normals).\n"
      "Stats (--stats): vertices faces levels read_s compute_s write_s total_s; seconds (deprecated: the whole "
      "command).");

  cmd->callback([args, &common] {
    PhaseTimer timer;
    const PolyMesh input = timer.time("read_s", [&] { return read_mesh_with_progress(args->input); });
    SubdivisionOptions options = args->options;
    PolyMesh result = timer.time("compute_s", [&] {
      Progress progress("subdivide", options.levels);
      options.progress = &progress;
      try {
        PolyMesh refined = subdivide(input, options);
        if (args->limit) {
          LimitSurface limit = limit_surface(refined, options);
          refined.positions = std::move(limit.positions);
          refined.normals = std::move(limit.normals);
        } else if (!input.normals.empty() || !input.corner_normals.empty()) {
          refined.normals = vertex_normals(refined);
        }
        progress.done();
        return refined;
      } catch (const InvalidInput& e) {
        // A result that is not finite is an error that names the input, never a file.
        throw InvalidInput(fmt::format("{}: {}", args->input, e.what()));
      }
    });
    timer.time("write_s", [&] { write_mesh_output(args->output, result); });
    if (common.stats) {
      StatRows rows{{"vertices", stat_value(double(result.vertex_count()))},
                    {"faces", stat_value(double(result.face_count()))},
                    {"levels", stat_value(options.levels)}};
      const StatRows phases = timer.rows();
      rows.insert(rows.end(), phases.begin(), phases.end());
      rows.emplace_back("seconds", stat_value(command_seconds()));
      print_stats(rows);
    }
  });
}

}  // namespace tessera::cli
