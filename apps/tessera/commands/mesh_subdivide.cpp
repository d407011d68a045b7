// tessera mesh subdivide IN -o OUT --scheme midpoint|loop|catmull-clark --levels N [--boundary edge-only|edge-and-corner]
//                        [--crease-method uniform|chaikin] [--loop-beta notes|loop] [--limit] [--stats]
#include <chrono>
#include <map>
#include <memory>
#include <string>

#include "command.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/subdiv/limit.hpp"
#include "tessera/subdiv/subdivide.hpp"

namespace tessera::cli {
namespace {

struct SubdivideArgs {
  std::string input, output;
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
  cmd->add_option("-o,--output", args->output, "Output mesh; its extension picks the format")->required();
  const std::map<std::string, SubdivisionScheme> schemes{{"midpoint", SubdivisionScheme::midpoint},
                                                         {"loop", SubdivisionScheme::loop},
                                                         {"catmull-clark", SubdivisionScheme::catmull_clark}};
  cmd->add_option("--scheme", args->options.scheme, "midpoint, loop or catmull-clark (default)")
      ->transform(CLI::CheckedTransformer(schemes, CLI::ignore_case));
  cmd->add_option("--levels", args->options.levels, "Refinement steps (default 1)")->check(CLI::Range(0, 12));
  const std::map<std::string, BoundaryInterpolation> boundaries{
      {"edge-only", BoundaryInterpolation::edge_only}, {"edge-and-corner", BoundaryInterpolation::edge_and_corner}};
  cmd->add_option("--boundary", args->options.boundary,
                  "edge-only (default: boundary vertices follow the crease rule) or edge-and-corner (vertices with "
                  "one face stay put)")
      ->transform(CLI::CheckedTransformer(boundaries, CLI::ignore_case));
  const std::map<std::string, CreaseMethod> methods{{"uniform", CreaseMethod::uniform},
                                                    {"chaikin", CreaseMethod::chaikin}};
  cmd->add_option("--crease-method", args->options.crease_method,
                  "How semi-sharp creases decay: uniform (default, s - 1 per level) or chaikin")
      ->transform(CLI::CheckedTransformer(methods, CLI::ignore_case));
  const std::map<std::string, LoopWeights> betas{{"notes", LoopWeights::warren}, {"loop", LoopWeights::loop}};
  cmd->add_option("--loop-beta", args->options.loop_weights,
                  "Loop's vertex weight: notes (default, 3/(8k), Warren) or loop (Loop's original, as OpenSubdiv)")
      ->transform(CLI::CheckedTransformer(betas, CLI::ignore_case));
  cmd->add_flag("--limit", args->limit, "Move the vertices to their limit positions and add limit normals");

  cmd->callback([args, &common] {
    const auto start = std::chrono::steady_clock::now();
    const PolyMesh input = read_mesh(args->input);
    SubdivisionOptions options = args->options;
    Progress progress("subdivide", options.levels);
    options.progress = &progress;
    PolyMesh result = subdivide(input, options);
    if (args->limit) {
      LimitSurface limit = limit_surface(result, options);
      result.positions = std::move(limit.positions);
      result.normals = std::move(limit.normals);
    }
    progress.done();
    write_mesh(args->output, result);
    if (common.stats) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      print_stats({{"vertices", stat_value(double(result.vertex_count()))},
                   {"faces", stat_value(double(result.face_count()))},
                   {"levels", stat_value(options.levels)},
                   {"seconds", stat_value(seconds)}});
    }
  });
}

}  // namespace tessera::cli
