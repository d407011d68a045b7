// tessera patch IN.bpt -o OUT.obj --tess N [--tolerance T] [--orient given|flip|outward] [--stats]: tessellates
// bicubic Bezier patches into a triangle mesh with normals and uvs (docs/curves.md).
#include <chrono>
#include <memory>
#include <string>

#include "command.hpp"
#include "tessera/curves/bezier_patch.hpp"
#include "tessera/curves/bpt.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera::cli {
namespace {

struct PatchOptions {
  std::string input, output;
  int tess = 8;
  double tolerance = 0;
  std::string orient = "given";
};

void run_patch(const PatchOptions& opt, const CommonOptions& common) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<BezierPatch> patches = read_bpt(opt.input);
  const PatchOrientation orientation = opt.orient == "flip"      ? PatchOrientation::Flipped
                                       : opt.orient == "outward" ? PatchOrientation::Outward
                                                                 : PatchOrientation::AsGiven;
  const TriMesh tris =
      tessellate(patches, PatchTessellation{.steps = opt.tess, .tolerance = opt.tolerance, .orientation = orientation});
  const PolyMesh mesh = to_poly_mesh(tris);
  write_mesh(opt.output, mesh);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (common.stats)
    print_stats({{"patches", stat_value(double(patches.size()))},
                 {"tris", stat_value(double(tris.triangle_count()))},
                 {"verts", stat_value(double(tris.vertex_count()))},
                 {"area", stat_value(surface_area(mesh))},
                 {"seconds", stat_value(seconds)}});
}

}  // namespace

void setup_patch(CLI::App& patch, CommonOptions& common) {
  auto opt = std::make_shared<PatchOptions>();
  patch.add_option("input", opt->input, "Bezier patches (.bpt)")->required()->check(CLI::ExistingFile);
  patch.add_option("-o,--output", opt->output, "Output mesh (.obj, .ply, .off, .stl)")->required();
  patch.add_option("--tess", opt->tess, "Samples per patch side: an (N+1)x(N+1) grid of (u, v) per patch")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  patch
      .add_option("--tolerance", opt->tolerance,
                  "Adaptive: per patch the fewest steps (at most --tess) keeping the mesh within this distance")
      ->check(non_negative());
  patch
      .add_option("--orient", opt->orient,
                  "Normals as du x dv (given), reversed (flip), or whichever points out of the model (outward)")
      ->check(CLI::IsMember({"given", "flip", "outward"}))
      ->capture_default_str();
  patch.footer(
      "Stats (--stats): patches tris verts area seconds.\n"
      "Example: tessera patch teapot.bpt -o teapot.obj --tess 16 --orient outward --stats\n"
      "(Newell's teapot data is wound so that du x dv points inside.)");
  patch.callback([opt, &common] { run_patch(*opt, common); });
}

}  // namespace tessera::cli
