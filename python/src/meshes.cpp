// Meshes: files, primitives, normals, measures, topology and corner tables, smoothing, triangulation, subdivision.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "tessera/mesh/corner_table.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/smoothing.hpp"
#include "tessera/mesh/soup.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/mesh/triangulate.hpp"
#include "tessera/subdiv/limit.hpp"
#include "tessera/subdiv/subdivide.hpp"

namespace tessera::python {
namespace {

/// Vectors as an (N, k) float64 array (copied out of a temporary).
template <class V>
py::array_t<double> vector_rows(std::vector<V> v) {
  auto owner = std::make_shared<const std::vector<V>>(std::move(v));
  return owned_array<double>(owner, owner->empty() ? nullptr : &(*owner)[0][0],
                             {py::ssize_t(owner->size()), V::length()});
}

/// f(mesh) on a mesh argument with the GIL released, returned as a tessera.Mesh.
template <class F>
py::object mesh_op(py::handle value, F&& f) {
  PolyMesh m = mesh(value, "mesh");
  {
    py::gil_scoped_release release;
    m = f(std::move(m));
  }
  return to_python(std::move(m));
}

SubdivisionOptions subdivision_options(const std::string& scheme, int levels, const std::string& boundary,
                                       const std::string& crease_method, const std::string& loop_weights,
                                       const std::string& triangles) {
  SubdivisionOptions o;
  o.scheme = choice<SubdivisionScheme>(scheme,
                                       {{"catmull-clark", SubdivisionScheme::catmull_clark},
                                        {"loop", SubdivisionScheme::loop},
                                        {"midpoint", SubdivisionScheme::midpoint}},
                                       "scheme");
  o.levels = levels;
  o.boundary = choice<BoundaryInterpolation>(
      boundary,
      {{"edge-only", BoundaryInterpolation::edge_only}, {"edge-and-corner", BoundaryInterpolation::edge_and_corner}},
      "boundary");
  o.crease_method = choice<CreaseMethod>(
      crease_method, {{"uniform", CreaseMethod::uniform}, {"chaikin", CreaseMethod::chaikin}}, "crease_method");
  o.loop_weights =
      choice<LoopWeights>(loop_weights, {{"notes", LoopWeights::warren}, {"loop", LoopWeights::loop}}, "loop_weights");
  o.triangles = choice<TriangleSubdivision>(
      triangles, {{"catmark", TriangleSubdivision::catmark}, {"smooth", TriangleSubdivision::smooth}}, "triangles");
  return o;
}

void bind_corner_table(py::module_& m) {
  py::class_<CornerTable, std::shared_ptr<CornerTable>>(m, "CornerTable", R"(The notes' corner table of a triangle mesh.

Corner c (3 per triangle, triangle c // 3) has a vertex V[c] and an opposite corner O[c] across the edge it faces
(-1 as uint32, i.e. 4294967295, on a boundary). next/prev walk a triangle, swing/unswing walk around a vertex.)")
      .def(py::init([](py::handle value) { return std::make_shared<CornerTable>(mesh(value, "mesh")); }),
           py::arg("mesh"), "Builds the table of a triangle mesh. Raises TopologyError for other faces.")
      .def_property_readonly(
          "vertices",
          [](const std::shared_ptr<CornerTable>& t) {
            return owned_array<uint32_t>(t, t->vertices().data(), {py::ssize_t(t->corner_count())});
          },
          "V: the vertex of every corner (uint32, 3 per triangle)")
      .def_property_readonly(
          "opposites",
          [](const std::shared_ptr<CornerTable>& t) {
            return owned_array<uint32_t>(t, t->opposites().data(), {py::ssize_t(t->corner_count())});
          },
          "O: the opposite corner of every corner (uint32; 4294967295 on a boundary)")
      .def_property_readonly("corner_count", &CornerTable::corner_count, "The number of corners (3 per triangle).")
      .def_property_readonly("triangle_count", &CornerTable::triangle_count, "The number of triangles.")
      .def_property_readonly("vertex_count", &CornerTable::vertex_count, "The number of vertices.")
      .def_static("next", &CornerTable::next, py::arg("c"), "The next corner of c's triangle.")
      .def_static("prev", &CornerTable::prev, py::arg("c"), "The previous corner of c's triangle.")
      .def_static("triangle", &CornerTable::triangle, py::arg("c"), "The triangle of corner c.")
      .def("vertex", &CornerTable::vertex, py::arg("c"), "V[c].")
      .def("opposite", &CornerTable::opposite, py::arg("c"), "O[c].")
      .def("is_boundary", &CornerTable::is_boundary, py::arg("c"), "Whether c faces a boundary edge.")
      .def("left", &CornerTable::left, py::arg("c"), "O[prev(c)]: the corner across the edge left of c.")
      .def("right", &CornerTable::right, py::arg("c"), "O[next(c)]: the corner across the edge right of c.")
      .def("swing", &CornerTable::swing, py::arg("c"), "The next corner around V[c] (counterclockwise).")
      .def("unswing", &CornerTable::unswing, py::arg("c"), "The previous corner around V[c].");
}

}  // namespace

void bind_meshes(py::module_& m) {
  m.def(
      "read_mesh",
      [](const std::filesystem::path& path) {
        PolyMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = read_mesh(path);
        }
        return to_python(std::move(mesh));
      },
      py::arg("path"),
      "Reads an OBJ, PLY, OFF or STL file as a Mesh. Raises IoError or InvalidInput naming the file and line.");
  m.def(
      "write_mesh",
      [](const std::filesystem::path& path, py::handle value, bool binary, bool double_precision) {
        const PolyMesh polys = mesh(value, "mesh");
        py::gil_scoped_release release;
        write_mesh(path, polys, {.binary = binary, .double_precision = double_precision});
      },
      py::arg("path"), py::arg("mesh"), py::kw_only(), py::arg("binary") = true, py::arg("double_precision") = false,
      "Writes a Mesh as OBJ, PLY, OFF or STL (by extension); PLY and STL binary unless binary=False. Atomic.");

  m.def(
      "tetrahedron", [] { return to_python(make_tetrahedron()); }, "A regular tetrahedron, circumradius 1.");
  m.def(
      "cube", [] { return to_python(make_cube()); }, "A cube of 6 quads, circumradius 1.");
  m.def(
      "octahedron", [] { return to_python(make_octahedron()); }, "A regular octahedron, circumradius 1.");
  m.def(
      "dodecahedron", [] { return to_python(make_dodecahedron()); }, "A regular dodecahedron (12 pentagons).");
  m.def(
      "icosahedron", [] { return to_python(make_icosahedron()); }, "A regular icosahedron, circumradius 1.");
  m.def(
      "box", [] { return to_python(make_box()); }, "The box [-1, 1]^3 of 6 quads.");
  m.def(
      "uv_sphere", [](int slices, int stacks) { return to_python(make_uv_sphere(slices, stacks)); },
      py::arg("slices") = 32, py::arg("stacks") = 16, "A unit sphere of slices x stacks (poles triangles).");
  m.def(
      "quad_sphere", [](int n) { return to_python(make_quad_sphere(n)); }, py::arg("n") = 8,
      "A unit sphere of quads: a cube's faces split n x n and projected.");
  m.def(
      "cylinder", [](int segments, bool caps) { return to_python(make_cylinder(segments, caps)); },
      py::arg("segments") = 32, py::arg("caps") = true, "A cylinder of radius 1 and height 2 along y.");
  m.def(
      "cone", [](int segments, bool cap) { return to_python(make_cone(segments, cap)); }, py::arg("segments") = 32,
      py::arg("cap") = true, "A cone of radius 1 and height 2 along y.");
  m.def(
      "torus", [](double major, double minor, int n, int m2) { return to_python(make_torus(major, minor, n, m2)); },
      py::arg("major_radius") = 1.0, py::arg("minor_radius") = 0.4, py::arg("n") = 48, py::arg("m") = 24,
      "A torus about y of quads: n around the ring, m around the tube.");
  m.def(
      "grid", [](int nx, int ny) { return to_python(make_grid(nx, ny)); }, py::arg("nx") = 10, py::arg("ny") = 10,
      "A flat grid of nx x ny quads over [-1, 1]^2 in the xz plane.");

  m.def(
      "vertex_normals",
      [](py::handle value, const std::string& weighting) {
        const NormalWeighting w = choice<NormalWeighting>(
            weighting, {{"area", NormalWeighting::area}, {"angle", NormalWeighting::angle}}, "weighting");
        const PolyMesh polys = mesh(value, "mesh");
        std::vector<Vec3> normals;
        {
          py::gil_scoped_release release;
          normals = vertex_normals(polys, w);
        }
        return vector_rows(std::move(normals));
      },
      py::arg("mesh"), py::arg("weighting") = "area",
      "Unit vertex normals (N, 3): the faces' normals around each vertex weighted by area or by angle.");
  m.def(
      "face_normals",
      [](py::handle value) {
        const PolyMesh polys = mesh(value, "mesh");
        return vector_rows(face_normals(polys));
      },
      py::arg("mesh"), "Unit face normals (M, 3) (Newell's method for polygons).");
  m.def(
      "surface_area", [](py::handle value) { return surface_area(mesh(value, "mesh")); }, py::arg("mesh"),
      "The total area of the faces.");
  m.def(
      "signed_volume", [](py::handle value) { return signed_volume(mesh(value, "mesh")); }, py::arg("mesh"),
      "The enclosed volume of a closed mesh (negative when its faces wind inward).");
  m.def(
      "topology",
      [](py::handle value) {
        const TopologyReport r = analyze_topology(mesh(value, "mesh"));
        py::dict d;
        d["vertices"] = r.vertices;
        d["unreferenced_vertices"] = r.unreferenced_vertices;
        d["faces"] = r.faces;
        d["edges"] = r.edges;
        d["boundary_edges"] = r.boundary_edges;
        d["nonmanifold_edges"] = r.nonmanifold_edges;
        d["boundary_loops"] = r.boundary_loops;
        d["components"] = r.components;
        d["nonmanifold_vertices"] = r.nonmanifold_vertices;
        d["inconsistent_edges"] = r.inconsistent_edges;
        d["euler"] = r.euler;
        d["genus"] = r.genus ? py::object(py::int_(*r.genus)) : py::object(py::none());
        d["manifold"] = r.manifold();
        d["closed"] = r.closed();
        d["oriented"] = r.oriented();
        return d;
      },
      py::arg("mesh"),
      "The mesh's topology as a dict: vertices, edges, faces, boundary edges and loops, components, non-manifold\n"
      "edges and vertices, the Euler characteristic and genus (as `tessera mesh info` reports them).");
  bind_corner_table(m);

  m.def(
      "triangulate", [](py::handle value) { return mesh_op(value, [](const PolyMesh& p) { return triangulate(p); }); },
      py::arg("mesh"), "Triangles of every polygon (ear clipping; convex ones as fans).");
  m.def(
      "weld",
      [](py::handle value, double tolerance) {
        return mesh_op(value, [=](PolyMesh p) {
          weld_vertices(p, tolerance);
          return p;
        });
      },
      py::arg("mesh"), py::arg("tolerance") = 0.0, "Merges vertices closer than tolerance (0: equal positions).");
  m.def(
      "with_normals",
      [](py::handle value, const std::string& weighting) {
        const NormalWeighting w = choice<NormalWeighting>(
            weighting, {{"area", NormalWeighting::area}, {"angle", NormalWeighting::angle}}, "weighting");
        return mesh_op(value, [=](PolyMesh p) {
          compute_vertex_normals(p, w);
          return p;
        });
      },
      py::arg("mesh"), py::arg("weighting") = "area", "The mesh with vertex normals (vertex_normals) set.");
  m.def(
      "smooth",
      [](py::handle value, const std::string& method, int iterations, double lam, double mu, bool fix_boundary) {
        SmoothingOptions o;
        o.method = choice<SmoothingMethod>(method,
                                           {{"laplacian", SmoothingMethod::laplacian},
                                            {"cotangent", SmoothingMethod::cotangent},
                                            {"taubin", SmoothingMethod::taubin}},
                                           "method");
        o.iterations = iterations;
        o.lambda = lam;
        o.mu = mu;
        o.fix_boundary = fix_boundary;
        return mesh_op(value, [&](PolyMesh p) {
          tessera::smooth(p, o);
          return p;
        });
      },
      py::arg("mesh"), py::arg("method") = "laplacian", py::arg("iterations") = 10, py::arg("lam") = 0.5,
      py::arg("mu") = -0.53, py::arg("fix_boundary") = true,
      "Smoothed vertex positions: laplacian (the notes' umbrella), cotangent or taubin steps (as `tessera mesh\n"
      "smooth`). Normals, where the mesh had them, are recomputed.");
  m.def(
      "subdivide",
      [](py::handle value, const std::string& scheme, int levels, bool limit, const std::string& boundary,
         const std::string& crease_method, const std::string& loop_weights, const std::string& triangles) {
        const SubdivisionOptions o =
            subdivision_options(scheme, levels, boundary, crease_method, loop_weights, triangles);
        return mesh_op(value, [&](const PolyMesh& input) {
          PolyMesh refined = tessera::subdivide(input, o);
          if (limit) {
            LimitSurface surface = limit_surface(refined, o);
            refined.positions = std::move(surface.positions);
            refined.normals = std::move(surface.normals);
          } else if (!input.normals.empty() || !input.corner_normals.empty()) {
            refined.normals = vertex_normals(refined);
          }
          return refined;
        });
      },
      py::arg("mesh"), py::arg("scheme") = "catmull-clark", py::arg("levels") = 1, py::kw_only(),
      py::arg("limit") = false, py::arg("boundary") = "edge-only", py::arg("crease_method") = "uniform",
      py::arg("loop_weights") = "notes", py::arg("triangles") = "catmark",
      R"(Subdivides a mesh `levels` times: scheme 'catmull-clark', 'loop' (triangles) or 'midpoint'.

Creases and corners (the mesh's crease_edges/crease_sharpness, corner_vertices/corner_sharpness) are sharp or
semi-sharp (sharpness >= 10 infinite); boundary 'edge-only' (the notes) or 'edge-and-corner'; crease_method 'uniform'
or 'chaikin'; loop_weights 'notes' (Warren's beta) or 'loop' (Loop's original, as OpenSubdiv); triangles 'catmark' or
'smooth' (Catmull-Clark next to triangles). limit=True moves the vertices to their limit positions and sets the limit
normals. The same as `tessera mesh subdivide`, bit for bit. Raises InvalidInput (Loop on polygons, levels out of
0..12, a request over the memory budget) or TopologyError (non-manifold input).)");
}

}  // namespace tessera::python
