// tessera mesh info|convert|normals|smooth|subdivide|triangulate
#include <fmt/format.h>

#include <memory>
#include <string>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/smoothing.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera::cli {

void setup_mesh_subdivide(CLI::App& mesh, CommonOptions& common);  // commands/mesh_subdivide.cpp

namespace {

/// Input and output paths shared by the mesh commands that write a mesh.
struct InOut {
  std::string input, output;
  bool ascii = false;
};

void add_in_out(CLI::App& command, InOut& io) {
  command.add_option("input", io.input, "Input mesh (.obj, .ply, .off, .stl)")->required();
  command.add_option("-o,--output", io.output, "Output mesh; the extension picks the format")->required();
  command.add_flag("--ascii", io.ascii, "Write PLY and STL as text instead of binary");
}

void write_output(const InOut& io, const PolyMesh& mesh) { write_mesh(io.output, mesh, {!io.ascii}); }

std::string vec_value(const Vec3& v) {
  return fmt::format("{},{},{}", stat_value(v.x), stat_value(v.y), stat_value(v.z));
}

void run_info(const std::string& input, bool stats) {
  const PolyMesh mesh = read_mesh(input);
  const TopologyReport r = analyze_topology(mesh);
  const Bounds3 box = bounding_box(mesh);
  std::vector<std::pair<std::string, std::string>> rows{
      {"vertices", stat_value(double(r.vertices))},
      {"faces", stat_value(double(r.faces))},
      {"edges", stat_value(double(r.edges))},
      {"boundary_edges", stat_value(double(r.boundary_edges))},
      {"boundary_loops", stat_value(double(r.boundary_loops))},
      {"components", stat_value(double(r.components))},
      {"euler", stat_value(double(r.euler))},
  };
  if (r.genus) rows.emplace_back("genus", stat_value(double(*r.genus)));
  rows.insert(rows.end(), {{"nonmanifold_edges", stat_value(double(r.nonmanifold_edges))},
                           {"nonmanifold_vertices", stat_value(double(r.nonmanifold_vertices))},
                           {"unreferenced_vertices", stat_value(double(r.unreferenced_vertices))},
                           {"oriented", r.oriented() ? "1" : "0"}});
  if (!box.empty()) rows.insert(rows.end(), {{"bbox_min", vec_value(box.lo)}, {"bbox_max", vec_value(box.hi)}});
  rows.emplace_back("area", stat_value(surface_area(mesh)));
  if (r.closed() && r.oriented()) rows.emplace_back("volume", stat_value(signed_volume(mesh)));
  if (stats) {
    print_stats(rows);
    return;
  }
  fmt::print("{}\n", input);
  for (const auto& [key, value] : rows) fmt::print("  {:<22} {}\n", key, value);
  if (!r.genus) fmt::print("  (genus is defined for consistently oriented manifolds only)\n");
  if (!r.closed()) fmt::print("  (volume is defined for closed meshes only)\n");
}

void setup_info(CLI::App& mesh, CommonOptions& common) {
  CLI::App* cmd = mesh.add_subcommand("info",
                                      "Print counts, topology (Euler characteristic, genus, boundaries), bounds, "
                                      "area and volume; --stats for key=value lines");
  auto input = std::make_shared<std::string>();
  cmd->add_option("input", *input, "Input mesh")->required();
  cmd->callback([input, &common] { run_info(*input, common.stats); });
}

void setup_convert(CLI::App& mesh) {
  CLI::App* cmd = mesh.add_subcommand("convert", "Convert between OBJ, PLY, OFF and STL (format by extension)");
  auto io = std::make_shared<InOut>();
  add_in_out(*cmd, *io);
  cmd->callback([io] { write_output(*io, read_mesh(io->input)); });
}

void setup_normals(CLI::App& mesh) {
  CLI::App* cmd = mesh.add_subcommand("normals", "Compute per-vertex normals (area- or angle-weighted face normals)");
  auto io = std::make_shared<InOut>();
  auto weighting = std::make_shared<NormalWeighting>(NormalWeighting::Area);
  add_in_out(*cmd, *io);
  cmd->add_option("--weighting", *weighting, "Face normal weights: area or angle")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, NormalWeighting>{{"area", NormalWeighting::Area}, {"angle", NormalWeighting::Angle}}));
  cmd->callback([io, weighting] {
    PolyMesh m = read_mesh(io->input);
    compute_vertex_normals(m, *weighting);
    write_output(*io, m);
  });
}

void setup_smooth(CLI::App& mesh) {
  CLI::App* cmd = mesh.add_subcommand("smooth", "Laplacian (uniform or cotangent) or Taubin lambda|mu smoothing");
  auto io = std::make_shared<InOut>();
  auto options = std::make_shared<SmoothingOptions>();
  add_in_out(*cmd, *io);
  cmd->add_option("--method", options->method, "laplacian, cotangent or taubin")
      ->transform(
          CLI::CheckedTransformer(std::map<std::string, SmoothingMethod>{{"laplacian", SmoothingMethod::Laplacian},
                                                                         {"cotangent", SmoothingMethod::Cotangent},
                                                                         {"taubin", SmoothingMethod::Taubin}}))
      ->required();
  cmd->add_option("--iterations", options->iterations, "Smoothing steps (Taubin: lambda/mu pairs)")
      ->required()
      ->check(non_negative());
  cmd->add_option("--lambda", options->lambda, "Step toward the neighbours' average, in (0, 1]")->capture_default_str();
  cmd->add_option("--mu", options->mu, "Taubin's inflating step, < -lambda")->capture_default_str();
  cmd->add_flag("!--move-boundary", options->fix_boundary, "Smooth boundary vertices too (default: they stay)");
  cmd->callback([io, options] {
    PolyMesh m = read_mesh(io->input);
    Progress progress("smooth", options->iterations);
    smooth(m, *options, [&](int) { progress.advance(); });
    progress.done();
    write_output(*io, m);
  });
}

void setup_triangulate(CLI::App& mesh) {
  CLI::App* cmd =
      mesh.add_subcommand("triangulate", "Split polygons into triangles (fan if convex, ear clipping if not)");
  auto io = std::make_shared<InOut>();
  add_in_out(*cmd, *io);
  cmd->callback([io] { write_output(*io, triangulate(read_mesh(io->input))); });
}

}  // namespace

void setup_mesh(CLI::App& mesh, CommonOptions& common) {
  mesh.require_subcommand(1);
  setup_info(mesh, common);
  setup_convert(mesh);
  setup_normals(mesh);
  setup_smooth(mesh);
  setup_triangulate(mesh);
  setup_mesh_subdivide(mesh, common);
}

}  // namespace tessera::cli
