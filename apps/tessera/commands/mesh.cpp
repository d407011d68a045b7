// tessera mesh info|convert|normals|smooth|subdivide|triangulate|weld
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>

#include "command.hpp"
#include "commands/mesh_output.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/smoothing.hpp"
#include "tessera/mesh/soup.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera::cli {

void setup_mesh_subdivide(CLI::App& mesh, CommonOptions& common);  // commands/mesh_subdivide.cpp

namespace {

/// Input and output of the mesh commands that write a mesh.
struct InOut {
  std::string input;
  MeshOutput output;
};

void add_in_out(CLI::App& command, InOut& io) {
  command.add_option("input", io.input, "Input mesh (.obj, .ply, .off, .stl)")->required();
  add_mesh_output(command, io.output);
}

/// Reads the input (with progress), runs `compute` on it, writes the result, and prints --stats: the output's
/// `vertices` and `faces`, `extra` rows, then the phases (read_s compute_s write_s) and total_s.
template <class Compute>
void run_in_out(const InOut& io, const CommonOptions& common, Compute&& compute, StatRows extra = {}) {
  PhaseTimer timer;
  PolyMesh mesh = timer.time("read_s", [&] { return read_mesh_with_progress(io.input); });
  timer.time("compute_s", [&] { compute(mesh, extra); });
  timer.time("write_s", [&] { write_mesh_output(io.output, mesh); });
  if (!common.stats) return;
  StatRows rows{{"vertices", stat_value(double(mesh.vertex_count()))},
                {"faces", stat_value(double(mesh.face_count()))}};
  rows.insert(rows.end(), extra.begin(), extra.end());
  const StatRows phases = timer.rows();
  rows.insert(rows.end(), phases.begin(), phases.end());
  print_stats(rows);
}

std::string vec_value(const Vec3& v) {
  return fmt::format("{},{},{}", stat_value(v.x), stat_value(v.y), stat_value(v.z));
}

void run_info(const std::string& input, bool stats) {
  PhaseTimer timer;
  const PolyMesh mesh = timer.time("read_s", [&] { return read_mesh_with_progress(input); });
  StatRows rows;
  timer.time("compute_s", [&] {
    const TopologyReport r = analyze_topology(mesh);
    const Bounds3 box = bounding_box(mesh);
    rows = {
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
  });
  if (stats) {
    const StatRows phases = timer.rows();
    rows.insert(rows.end(), phases.begin(), phases.end());
    print_stats(rows);
    return;
  }
  fmt::print("{}\n", input);
  for (const auto& [key, value] : rows) fmt::print("  {:<22} {}\n", key, value);
  if (std::none_of(rows.begin(), rows.end(), [](const auto& row) { return row.first == "genus"; }))
    fmt::print("  (genus is defined for consistently oriented manifolds only)\n");
  if (std::none_of(rows.begin(), rows.end(), [](const auto& row) { return row.first == "volume"; }))
    fmt::print("  (volume is defined for closed, consistently oriented meshes only)\n");
}

void setup_info(CLI::App& mesh, CommonOptions& common) {
  CLI::App* cmd = mesh.add_subcommand("info",
                                      "Print counts, topology (Euler characteristic, genus, boundaries), bounds, "
                                      "area and volume; --stats for key=value lines");
  auto input = std::make_shared<std::string>();
  cmd->add_option("input", *input, "Input mesh")->required();
  cmd->footer(
      "Stats (--stats): vertices faces edges boundary_edges boundary_loops components euler [genus] "
      "nonmanifold_edges nonmanifold_vertices unreferenced_vertices oriented bbox_min bbox_max area [volume] read_s "
      "compute_s total_s.");
  cmd->callback([input, &common] { run_info(*input, common.stats); });
}

void setup_convert(CLI::App& mesh, CommonOptions& common) {
  CLI::App* cmd = mesh.add_subcommand(
      "convert",
      "Convert between OBJ, PLY, OFF and STL (format by extension), keeping uvs, normals and colors where the output "
      "can hold them (a warning names what it cannot)");
  auto io = std::make_shared<InOut>();
  add_in_out(*cmd, *io);
  cmd->footer("Stats (--stats): vertices faces read_s compute_s write_s total_s.");
  cmd->callback([io, &common] { run_in_out(*io, common, [](PolyMesh&, StatRows&) {}); });
}

void setup_normals(CLI::App& mesh, CommonOptions& common) {
  CLI::App* cmd = mesh.add_subcommand("normals", "Compute per-vertex normals (area- or angle-weighted face normals)");
  auto io = std::make_shared<InOut>();
  auto weighting = std::make_shared<NormalWeighting>(NormalWeighting::area);
  add_in_out(*cmd, *io);
  add_choice(*cmd, "--weighting", *weighting, {{"area", NormalWeighting::area}, {"angle", NormalWeighting::angle}},
             "Face normal weights");
  cmd->footer("Stats (--stats): vertices faces read_s compute_s write_s total_s.");
  cmd->callback([io, weighting, &common] {
    run_in_out(*io, common, [&](PolyMesh& m, StatRows&) { compute_vertex_normals(m, *weighting); });
  });
}

void setup_smooth(CLI::App& mesh, CommonOptions& common) {
  CLI::App* cmd = mesh.add_subcommand("smooth", "Laplacian (uniform or cotangent) or Taubin lambda|mu smoothing");
  auto io = std::make_shared<InOut>();
  auto options = std::make_shared<SmoothingOptions>();
  add_in_out(*cmd, *io);
  add_choice(*cmd, "--method", options->method,
             {{"laplacian", SmoothingMethod::laplacian},
              {"cotangent", SmoothingMethod::cotangent},
              {"taubin", SmoothingMethod::taubin}},
             "Smoothing method")
      ->required();
  cmd->add_option("--iterations", options->iterations, "Smoothing steps (Taubin: lambda/mu pairs)")
      ->required()
      ->check(non_negative());
  cmd->add_option("--lambda", options->lambda, "Step toward the neighbours' average, in (0, 1]")->capture_default_str();
  cmd->add_option("--mu", options->mu, "Taubin's inflating step, < -lambda")->capture_default_str();
  cmd->add_flag("!--move-boundary", options->fix_boundary, "Smooth boundary vertices too (default: they stay)");
  cmd->footer("Stats (--stats): vertices faces iterations read_s compute_s write_s total_s.");
  cmd->callback([io, options, &common] {
    run_in_out(*io, common, [&](PolyMesh& m, StatRows& extra) {
      Progress progress("smooth", options->iterations);
      smooth(m, *options, [&](int) { progress.advance(); });
      progress.done();
      extra.emplace_back("iterations", stat_value(options->iterations));
    });
  });
}

void setup_triangulate(CLI::App& mesh, CommonOptions& common) {
  CLI::App* cmd =
      mesh.add_subcommand("triangulate", "Split polygons into triangles (fan if convex, ear clipping if not)");
  auto io = std::make_shared<InOut>();
  add_in_out(*cmd, *io);
  cmd->footer("Stats (--stats): vertices faces triangles read_s compute_s write_s total_s.");
  cmd->callback([io, &common] {
    run_in_out(*io, common, [](PolyMesh& m, StatRows& extra) {
      m = triangulate(m);
      extra.emplace_back("triangles", stat_value(double(m.face_count())));
    });
  });
}

void setup_weld(CLI::App& mesh, CommonOptions& common) {
  CLI::App* cmd = mesh.add_subcommand(
      "weld", "Merge coincident vertices (exactly equal, or within --tolerance): a soup of faces becomes connected");
  auto io = std::make_shared<InOut>();
  auto tolerance = std::make_shared<double>(0.0);
  add_in_out(*cmd, *io);
  cmd->add_option("--tolerance", *tolerance,
                  "Merge vertices closer than this distance (default 0: bit-identical coordinates only)")
      ->check(non_negative());
  cmd->footer(
      "uvs and normals that differ at a merged vertex (texture seams) become per-corner, so nothing is lost.\n"
      "Stats (--stats): vertices faces merged_vertices read_s compute_s write_s total_s.");
  cmd->callback([io, tolerance, &common] {
    run_in_out(*io, common, [&](PolyMesh& m, StatRows& extra) {
      extra.emplace_back("merged_vertices", stat_value(double(weld_vertices(m, *tolerance))));
    });
  });
}

}  // namespace

void setup_mesh(CLI::App& mesh, CommonOptions& common) {
  mesh.require_subcommand(1);
  setup_info(mesh, common);
  setup_convert(mesh, common);
  setup_normals(mesh, common);
  setup_smooth(mesh, common);
  setup_triangulate(mesh, common);
  setup_weld(mesh, common);
  setup_mesh_subdivide(mesh, common);
}

}  // namespace tessera::cli
