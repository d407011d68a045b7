// Fractals: escape-time sets (Mandelbrot, Julia), the self-similar constructions, fractal terrain, box counting.
#include <pybind11/complex.h>
#include <pybind11/stl.h>

#include <cstring>

#include "bindings.hpp"
#include "convert.hpp"
#include "tessera/fractal/coloring.hpp"
#include "tessera/fractal/dimension.hpp"
#include "tessera/fractal/escape_time.hpp"
#include "tessera/fractal/self_similar.hpp"
#include "tessera/fractal/terrain.hpp"

namespace tessera::python {
namespace {

/// An escape-time picture: colored by the palette, or with raw=True its (iterations, norm2) arrays.
py::object escape_picture(const std::function<EscapeImage()>& compute, bool raw, const std::string& palette,
                          double period, double phase) {
  ColorOptions colors{.palette = parse_palette(palette), .period = period, .phase = phase};
  EscapeImage escape;
  ImageRGB picture;
  {
    py::gil_scoped_release release;
    escape = compute();
    if (!raw) picture = colorize(escape, colors);
  }
  if (!raw) return to_python(std::move(picture));
  const int w = escape.iterations.width(), h = escape.iterations.height();
  py::array_t<uint32_t> iterations(std::vector<py::ssize_t>{h, w}, escape.iterations.pixels().data());
  return py::make_tuple(iterations, to_python(std::move(escape.norm2)));
}

ComplexView view(std::pair<int, int> size, std::complex<double> center, double scale) {
  return {.center = center, .scale = scale, .width = size.first, .height = size.second};
}

TerrainOptions terrain(int depth, double initial_range, double roughness, uint64_t seed) {
  return {.depth = depth, .initial_range = initial_range, .roughness = roughness, .seed = seed};
}

template <class T>
py::array_t<double> records(const std::vector<T>& items, const std::vector<py::ssize_t>& shape) {
  py::array_t<double> out(shape);
  static_assert(sizeof(T) % sizeof(double) == 0);
  if (!items.empty()) std::memcpy(out.mutable_data(), items.data(), items.size() * sizeof(T));
  return out;
}

py::array_t<double> polyline(const std::vector<Vec2>& points) {
  return records(points, {py::ssize_t(points.size()), 2});
}

}  // namespace

void bind_fractals(py::module_& m) {
  m.def(
      "mandelbrot",
      [](std::pair<int, int> size, std::complex<double> center, double scale, int iterations, double escape_radius,
         const std::string& palette, double period, double phase, bool raw) {
        const ComplexView v = view(size, center, scale);
        const EscapeOptions o{.max_iterations = iterations, .escape_radius = escape_radius};
        return escape_picture([&] { return mandelbrot(v, o); }, raw, palette, period, phase);
      },
      py::arg("size") = std::pair{800, 600}, py::arg("center") = std::complex<double>(-0.5, 0), py::arg("scale") = 3.0,
      py::arg("iterations") = 1000, py::arg("escape_radius") = 256.0, py::arg("palette") = "classic",
      py::arg("period") = 12.0, py::arg("phase") = 0.0, py::arg("raw") = false,
      R"(The Mandelbrot set over a view (center, scale = the view's width in the complex plane), SIMD escape-time
iterations colored smoothly by a palette ('classic', 'fire', 'ocean', 'gray'); raw=True returns the escape counts
(H, W) uint32 and |z_n|^2 (H, W) instead.)");
  m.def(
      "julia",
      [](std::complex<double> c, std::pair<int, int> size, std::complex<double> center, double scale, int iterations,
         double escape_radius, const std::string& palette, double period, double phase, bool raw) {
        const ComplexView v = view(size, center, scale);
        const EscapeOptions o{.max_iterations = iterations, .escape_radius = escape_radius, .interior_checks = false};
        return escape_picture([&] { return julia(c, v, o); }, raw, palette, period, phase);
      },
      py::arg("c"), py::arg("size") = std::pair{800, 600}, py::arg("center") = std::complex<double>(0, 0),
      py::arg("scale") = 3.2, py::arg("iterations") = 1000, py::arg("escape_radius") = 256.0,
      py::arg("palette") = "classic", py::arg("period") = 12.0, py::arg("phase") = 0.0, py::arg("raw") = false,
      "The Julia set of c (z0 = pixel), as mandelbrot().");
  m.def("julia_is_connected", &julia_is_connected, py::arg("c"), py::arg("max_iterations") = 10000,
        "The notes' test: the Julia set of c is connected iff the orbit of 0 stays bounded.");
  m.def(
      "cantor_set",
      [](int depth) {
        const auto v = cantor_set(depth);
        return records(v, {py::ssize_t(v.size()), 2});
      },
      py::arg("depth"), "The intervals (K, 2) [a, b] of the Cantor set's construction at depth.");
  m.def(
      "cantor_dust",
      [](int depth) {
        const auto v = cantor_dust(depth);
        return records(v, {py::ssize_t(v.size()), 4});
      },
      py::arg("depth"), "The squares (K, 4) (x, y, w, h) of Cantor dust.");
  m.def(
      "sierpinski_carpet",
      [](int depth) {
        const auto v = sierpinski_carpet(depth);
        return records(v, {py::ssize_t(v.size()), 4});
      },
      py::arg("depth"), "The squares (K, 4) (x, y, w, h) that remain of the unit square.");
  m.def(
      "sierpinski_triangle",
      [](int depth) {
        const auto v = sierpinski_triangle(depth);
        return records(v, {py::ssize_t(v.size()), 3, 2});
      },
      py::arg("depth"), "The triangles (K, 3, 2) that remain, counterclockwise.");
  m.def(
      "koch_curve", [](int depth) { return polyline(koch_curve(depth)); }, py::arg("depth"),
      "The Koch curve from (0, 0) to (1, 0) as a polyline (4^depth + 1, 2).");
  m.def(
      "koch_snowflake", [](int depth) { return polyline(koch_snowflake(depth)); }, py::arg("depth"),
      "The Koch snowflake as a closed polygon (K, 2).");
  m.def(
      "hilbert_curve", [](int depth) { return polyline(hilbert_curve(depth)); }, py::arg("depth"),
      "Hilbert's space-filling curve in the unit square (4^depth points).");
  m.def(
      "peano_curve", [](int depth) { return polyline(peano_curve(depth)); }, py::arg("depth"),
      "Peano's space-filling curve in the unit square (9^depth points).");
  m.def(
      "midpoint_displacement",
      [](int depth, double initial_range, double roughness, uint64_t seed) {
        const std::vector<double> h = midpoint_displacement_1d(terrain(depth, initial_range, roughness, seed));
        return py::array_t<double>(py::ssize_t(h.size()), h.data());
      },
      py::arg("depth") = 6, py::arg("initial_range") = 0.5, py::arg("roughness") = 0.5, py::arg("seed") = 1,
      "The notes' 1D mountain: 2^depth + 1 heights by midpoint displacement.");
  m.def(
      "triangle_mountain",
      [](int depth, double initial_range, double roughness, uint64_t seed) {
        return to_python(triangle_mountain(terrain(depth, initial_range, roughness, seed)));
      },
      py::arg("depth") = 6, py::arg("initial_range") = 0.5, py::arg("roughness") = 0.5, py::arg("seed") = 1,
      "The notes' fractal mountain: a triangle subdivided depth times, midpoints displaced (a Mesh).");
  m.def(
      "diamond_square",
      [](int depth, double initial_range, double roughness, uint64_t seed) {
        return to_python(diamond_square(terrain(depth, initial_range, roughness, seed)));
      },
      py::arg("depth") = 6, py::arg("initial_range") = 0.5, py::arg("roughness") = 0.5, py::arg("seed") = 1,
      "A height field (2^depth + 1)^2 by the diamond-square algorithm (float32 (H, W)).");
  m.def(
      "height_map_mesh",
      [](py::handle heights, double height_scale) {
        return to_python(height_map_mesh(field(heights, "heights"), height_scale));
      },
      py::arg("heights"), py::arg("height_scale") = 1.0, "A grid Mesh over a height field (H, W).");
  m.def(
      "box_counting_dimension",
      [](py::handle mask, double min_box, double max_box, double factor) {
        const auto a = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(mask);
        if (!a || a.ndim() != 2) {
          PyErr_Clear();
          throw InvalidInput("mask: expected an array (H, W); nonzero pixels are the set");
        }
        Image<uint8_t> m2(int(a.shape(1)), int(a.shape(0)));
        std::memcpy(m2.pixels().data(), a.data(), size_t(a.size()));
        const BoxCountResult r = box_counting_dimension(m2, {.min_box = min_box, .max_box = max_box, .factor = factor});
        py::dict d;
        d["dimension"] = r.dimension;
        d["sizes"] = r.sizes;
        d["counts"] = r.counts;
        d["fitted"] = r.fitted;
        d["extent"] = r.extent;
        return d;
      },
      py::arg("mask"), py::arg("min_box") = 1.0, py::arg("max_box") = 0.0, py::arg("factor") = 2.0,
      "The box-counting dimension of the nonzero pixels of a mask (H, W): dimension, sizes, counts, fitted, extent.");
}

}  // namespace tessera::python
