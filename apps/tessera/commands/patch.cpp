// tessera patch IN.bpt -o OUT.obj --tess N [--tolerance T] [--orient outward|given|flip] [--no-weld] [--stats]:
// tessellates bicubic Bezier patches into one welded, outward-facing triangle mesh with normals and uvs
// (docs/curves.md).
#include <memory>
#include <string>

#include "command.hpp"
#include "commands/mesh_output.hpp"
#include "tessera/curves/bezier_patch.hpp"
#include "tessera/curves/bpt.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/soup.hpp"

namespace tessera::cli {
namespace {

/// Patch borders are welded when their samples agree to this fraction of the bounding box diagonal: the two sides
/// evaluate the same boundary curve, at parameters i/N and 1 - (N-i)/N, so they differ by round-off only.
constexpr double kWeldTolerance = 1e-9;

struct PatchOptions {
  std::string input;
  MeshOutput output;
  int tess = 8;
  double tolerance = 0;
  PatchOrientation orientation = PatchOrientation::outward;
  bool no_weld = false;
};

void run_patch(const PatchOptions& opt, const CommonOptions& common) {
  PhaseTimer timer;
  const std::vector<BezierPatch> patches = timer.time("read_s", [&] { return read_bpt(opt.input); });
  const PolyMesh mesh = timer.time("compute_s", [&] {
    PolyMesh m = to_poly_mesh(tessellate(
        patches, PatchTessellation{.steps = opt.tess, .tolerance = opt.tolerance, .orientation = opt.orientation}));
    if (!opt.no_weld) {
      const Bounds3 box = bounding_box(m);
      if (!box.empty()) weld_vertices(m, kWeldTolerance * glm::length(box.hi - box.lo));
      // Surfaces that only touch (the teapot's handle meets the body's equator in one point) stay apart.
      split_pinched_vertices(m);
    }
    return m;
  });
  timer.time("write_s", [&] { write_mesh_output(opt.output, mesh); });
  if (!common.stats) return;
  const std::string triangles = stat_value(double(mesh.face_count())),
                    vertices = stat_value(double(mesh.vertex_count()));
  StatRows rows{{"patches", stat_value(double(patches.size()))},
                {"vertices", vertices},
                {"faces", triangles},
                {"triangles", triangles},
                {"area", stat_value(surface_area(mesh))},
                {"volume", stat_value(signed_volume(mesh))}};
  const StatRows phases = timer.rows();
  rows.insert(rows.end(), phases.begin(), phases.end());
  rows.insert(rows.end(), {{"tris", triangles}, {"verts", vertices}, {"seconds", stat_value(command_seconds())}});
  print_stats(rows);
}

}  // namespace

void setup_patch(CLI::App& patch, CommonOptions& common) {
  auto opt = std::make_shared<PatchOptions>();
  patch.add_option("input", opt->input, "Bezier patches (.bpt)")->required()->check(CLI::ExistingFile);
  add_mesh_output(patch, opt->output);
  patch.add_option("--tess", opt->tess, "Samples per patch side: an (N+1)x(N+1) grid of (u, v) per patch")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  patch
      .add_option("--tolerance", opt->tolerance,
                  "Adaptive: per patch the fewest steps (at most --tess) keeping the mesh within this distance")
      ->check(non_negative());
  add_choice(patch, "--orient", opt->orientation,
             {{"outward", PatchOrientation::outward},
              {"given", PatchOrientation::as_given},
              {"flip", PatchOrientation::flipped}},
             "Which side the triangles and normals face: out of the model (outward: positive signed volume), du x dv "
             "as the data is wound (given), or reversed (flip)");
  patch.add_flag("--no-weld", opt->no_weld,
                 "Keep every patch's own vertices (default: vertices that patches share are merged, so the mesh is "
                 "connected across patch borders; their uvs, which differ per patch, become per-corner; surfaces that "
                 "touch in a single point stay apart)");
  patch.footer(
      "Stats (--stats): patches vertices faces triangles area volume read_s compute_s write_s total_s; tris, verts\n"
      "and seconds (the whole command) are deprecated aliases.\n"
      "Example: tessera patch teapot.bpt -o teapot.obj --tess 16 --stats\n"
      "(Newell's teapot data is wound so that du x dv points inside: --orient given gives an inside-out teapot.)");
  patch.callback([opt, &common] { run_patch(*opt, common); });
}

}  // namespace tessera::cli
