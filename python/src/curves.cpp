// Bezier curves (2D and 3D, any degree) and bicubic Bezier patches (the teapot's .bpt files).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "tessera/curves/bezier.hpp"
#include "tessera/curves/bezier_patch.hpp"
#include "tessera/curves/bpt.hpp"
#include "tessera/mesh/convert.hpp"

namespace tessera::python {
namespace {

/// Control points (n + 1, 2) or (n + 1, 3) as a curve.
template <class P>
BezierCurve<P> curve(const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  BezierCurve<P> c;
  c.points.resize(size_t(a.shape(0)));
  for (size_t i = 0; i < c.points.size(); ++i)
    for (int k = 0; k < P::length(); ++k) c.points[i][k] = a.data()[i * P::length() + size_t(k)];
  return c;
}

/// The control points of `value`, (n + 1, 2) or (n + 1, 3), and their dimension.
std::pair<py::array_t<double, py::array::c_style | py::array::forcecast>, int> control_points(py::handle value) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  const int d = a && a.ndim() == 2 ? int(a.shape(1)) : 0;
  if (d != 2 && d != 3) {
    PyErr_Clear();
    throw InvalidInput("points: expected control points (n + 1, 2) or (n + 1, 3)");
  }
  return {rows(a, d, "points"), d};
}

/// Points as an (N, d) array.
template <class P>
py::array_t<double> points_array(const std::vector<P>& points) {
  py::array_t<double> out(std::vector<py::ssize_t>{py::ssize_t(points.size()), P::length()});
  for (size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < P::length(); ++k) out.mutable_data()[i * P::length() + k] = points[i][k];
  return out;
}

/// f<Vec2> or f<Vec3> for the curve's dimension.
template <class F>
py::object on_curve(py::handle value, F&& f) {
  const auto [a, d] = control_points(value);
  if (d == 2) return f(curve<Vec2>(a));
  return f(curve<Vec3>(a));
}

std::vector<BezierPatch> patches(py::handle value) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 4 || a.shape(1) != 4 || a.shape(2) != 4 || a.shape(3) != 3) {
    PyErr_Clear();
    throw InvalidInput("patches: expected an array (P, 4, 4, 3) of control points (row i along u, column j along v)");
  }
  std::vector<BezierPatch> out(size_t(a.shape(0)));
  for (size_t p = 0; p < out.size(); ++p)
    for (size_t i = 0; i < 16; ++i)
      out[p].points[i] = Vec3(a.data()[48 * p + 3 * i], a.data()[48 * p + 3 * i + 1], a.data()[48 * p + 3 * i + 2]);
  return out;
}

py::array_t<double> patches_array(const std::vector<BezierPatch>& ps) {
  py::array_t<double> out(std::vector<py::ssize_t>{py::ssize_t(ps.size()), 4, 4, 3});
  for (size_t p = 0; p < ps.size(); ++p)
    for (size_t i = 0; i < 16; ++i)
      for (int k = 0; k < 3; ++k) out.mutable_data()[48 * p + 3 * i + size_t(k)] = ps[p].points[i][k];
  return out;
}

}  // namespace

void bind_curves(py::module_& m) {
  m.def(
      "bezier",
      [](py::handle points, py::handle t, const std::string& method) {
        const auto ts = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(t);
        const int how = choice<int>(method, {{"de-casteljau", 0}, {"bernstein", 1}, {"horner", 2}}, "method");
        return on_curve(points, [&](const auto& c) -> py::object {
          using P = std::decay_t<decltype(c.points[0])>;
          std::vector<P> out(size_t(ts.size()));
          for (size_t i = 0; i < out.size(); ++i)
            out[i] = how == 0   ? evaluate_de_casteljau(c, ts.data()[i])
                     : how == 1 ? evaluate_bernstein(c, ts.data()[i])
                                : evaluate_horner(c, ts.data()[i]);
          return points_array(out);
        });
      },
      py::arg("points"), py::arg("t"), py::arg("method") = "de-casteljau",
      R"(Points Q(t) of the Bezier curve with control points (n + 1, 2) or (n + 1, 3), for every t of an array: by de
Casteljau's construction (default), the Bernstein sum, or Horner's rule on the power form. Returns (len(t), d).)");
  m.def(
      "bezier_levels",
      [](py::handle points, double t) {
        return on_curve(points, [&](const auto& c) -> py::object {
          py::list levels;
          for (const auto& level : de_casteljau_levels(c, t)) levels.append(points_array(level));
          return levels;
        });
      },
      py::arg("points"), py::arg("t"), "De Casteljau's construction at t: every level's points, the last Q(t).");
  m.def(
      "bezier_split",
      [](py::handle points, double t) {
        return on_curve(points, [&](const auto& c) -> py::object {
          const auto [left, right] = split(c, t);
          return py::make_tuple(points_array(left.points), points_array(right.points));
        });
      },
      py::arg("points"), py::arg("t") = 0.5, "The control points of the curve's two halves at t (de Casteljau).");
  m.def(
      "bezier_elevate",
      [](py::handle points) {
        return on_curve(points, [](const auto& c) -> py::object { return points_array(elevate_degree(c).points); });
      },
      py::arg("points"), "The same curve with one degree more (n + 2 control points).");
  m.def(
      "bezier_derivative",
      [](py::handle points) {
        return on_curve(points, [](const auto& c) -> py::object { return points_array(derivative(c).points); });
      },
      py::arg("points"), "The hodograph: the control points n (P_{i+1} - P_i) of Q'(t).");
  m.def(
      "bezier_flatten",
      [](py::handle points, double tolerance) {
        return on_curve(points, [&](const auto& c) -> py::object {
          std::vector<std::decay_t<decltype(c.points[0])>> out{c.front()};
          flatten(c, tolerance, out);
          return points_array(out);
        });
      },
      py::arg("points"), py::arg("tolerance") = 0.25,
      "A polyline within `tolerance` of the curve (recursive subdivision until flat), from Q(0) to Q(1).");

  m.def(
      "read_patches", [](const std::filesystem::path& path) { return patches_array(read_bpt(path)); }, py::arg("path"),
      "Reads bicubic Bezier patches from a .bpt file (the Utah teapot's format) as an array (P, 4, 4, 3).");
  m.def(
      "write_patches", [](const std::filesystem::path& path, py::handle value) { write_bpt(path, patches(value)); },
      py::arg("path"), py::arg("patches"), "Writes patches (P, 4, 4, 3) as a .bpt file.");
  m.def(
      "patch_points",
      [](py::handle value, double u, double v) {
        std::vector<Vec3> out;
        for (const BezierPatch& p : patches(value)) out.push_back(evaluate_bernstein(p, u, v));
        return points_array(out);
      },
      py::arg("patches"), py::arg("u"), py::arg("v"),
      "S(u, v) of every patch (P, 3) (the tensor-product Bernstein sum).");
  m.def(
      "tessellate_patches",
      [](py::handle value, int steps, double tolerance, const std::string& orientation) {
        const std::vector<BezierPatch> ps = patches(value);
        PatchTessellation o;
        o.steps = steps;
        o.tolerance = tolerance;
        o.orientation = choice<PatchOrientation>(orientation,
                                                 {{"outward", PatchOrientation::outward},
                                                  {"given", PatchOrientation::as_given},
                                                  {"flip", PatchOrientation::flipped}},
                                                 "orientation");
        PolyMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = to_poly_mesh(tessellate(ps, o));
        }
        return to_python(std::move(mesh));
      },
      py::arg("patches"), py::arg("steps") = 8, py::kw_only(), py::arg("tolerance") = 0.0,
      py::arg("orientation") = "outward",
      R"(Triangles of the patches: each on an (steps + 1)^2 grid of (u, v), or with tolerance > 0 as many steps as the
flatness bound needs (at most `steps`); normals and uvs per vertex. orientation (as `tessera patch --orient`):
'outward' (out of the model: a positive signed volume), 'given' (du x dv) or 'flip'.)");
  m.def(
      "patch_control_net", [](py::handle value) { return to_python(control_net(patches(value))); }, py::arg("patches"),
      "The control nets as a Mesh: per patch its 16 points and 9 quads.");
}

}  // namespace tessera::python
