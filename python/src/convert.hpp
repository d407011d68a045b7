#pragma once
// Between numpy and Tessera's types: what the bindings of every module share.
//
// Out (C++ -> Python) is zero-copy: the C++ object moves into a shared holder and the arrays view its storage, each
// keeping the holder alive through its base, so that an array stays valid after everything else is dropped. In
// (Python -> C++) copies once into the library's std::vector storage, checking shape and values first: a wrong
// shape or an index out of range is an InvalidInput naming the argument, never undefined behaviour.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/scene/framing.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/volume.hpp"

namespace tessera::python {

namespace py = pybind11;

/// A C-contiguous numpy array of `shape` over `data`, which `owner` keeps alive for as long as the array lives.
template <class T>
py::array_t<T> owned_array(std::shared_ptr<const void> owner, const T* data, std::vector<py::ssize_t> shape) {
  auto* keep = new std::shared_ptr<const void>(std::move(owner));
  const py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<const void>*>(p); });
  return py::array_t<T>(std::move(shape), data, base);
}

/// The value named `name` among `names` (pairs of a name and a value): the keyword arguments' string choices, spelled
/// as the CLI spells them. Throws InvalidInput naming `what` and listing the names.
template <class T, class Names>
T choose(const std::string& name, const Names& names, const std::string& what) {
  std::string list;
  for (const auto& [n, value] : names) {
    if (name == n) return value;
    list += (list.empty() ? "" : ", ") + std::string(n);
  }
  throw InvalidInput(fmt::format("{}: expected one of {}, got '{}'", what, list, name));
}
/// choose() over names written in place, {{"name", value}, ...}.
template <class T>
T choice(const std::string& name, std::initializer_list<std::pair<const char*, T>> names, const std::string& what) {
  return choose<T>(name, names, what);
}
/// choose() over a library table of names (framing.hpp's).
template <class T, size_t N>
T choice(const std::string& name, const std::array<std::pair<std::string_view, T>, N>& names, const std::string& what) {
  return choose<T>(name, names, what);
}

/// A contiguous float64 array from any array-like `value` of shape (N, cols). Throws InvalidInput naming `what` for
/// another shape or a value that is not finite.
py::array_t<double, py::array::c_style | py::array::forcecast> rows(py::handle value, int cols,
                                                                    const std::string& what);
/// Three numbers from a sequence or array of 3 (a point, a direction). Throws InvalidInput naming `what`.
Vec3 vec3(py::handle value, const std::string& what);
/// A color: three numbers in [0, 1], or a name / #rrggbb as SVG and CSS spell them. Throws InvalidInput naming `what`.
Vec3f color(py::handle value, const std::string& what);

/// The keyword options of a call (the Python wrapper's, as a dict), read by name once each: finish() refuses the
/// names no one read, so that a misspelt option is an error, not silently ignored.
class Options {
 public:
  explicit Options(py::dict options) : options_(std::move(options)) {}
  /// The option `name` converted to T, or `fallback` when absent or None.
  template <class T>
  T get(const char* name, T fallback) {
    const py::object o = take(name);
    return o.is_none() ? fallback : o.cast<T>();
  }
  /// The option `name` (None when absent), marked read.
  py::object take(const char* name);
  /// Throws InvalidInput naming `what` and the first option not read.
  void finish(const std::string& what) const;

 private:
  py::dict options_;
  std::vector<std::string> read_;
};

/// The framing options (view, azimuth, elevation, up_axis, front_axis, fovy, eye, center, up, ortho, ortho_size,
/// near, far) as the CLI's camera options spell them; `fovy` is the default field of view.
Framing framing(Options& options, double fovy);

/// The image as tessera.Image, a float32 numpy array (H, W, 3) or (H, W, 4) viewing the moved image.
py::object to_python(ImageRGB image);
py::object to_python(ImageRGBA image);
/// A one-channel float image (a depth buffer, a field) as a float32 array (H, W).
py::object to_python(DepthImage image);
/// An image argument: an array (H, W), (H, W, 3) or (H, W, 4) of floats (linear, as Tessera's images) or uint8
/// (v / 255). Gray gives equal channels; alpha is 1 where missing. Throws InvalidInput naming `what`.
ImageRGBA image_rgba(py::handle value, const std::string& what);
/// A scalar field argument: an array (H, W) of numbers as float32.
DepthImage field(py::handle value, const std::string& what);

/// The mesh as tessera.Mesh, its arrays viewing the moved PolyMesh.
py::object to_python(PolyMesh mesh);
/// A mesh argument: a tessera.Mesh, or any object with `vertices` and `faces` (a trimesh.Trimesh, ...). Checks the
/// face indices and every per-vertex and per-corner array's length. Throws InvalidInput naming `what`.
PolyMesh mesh(py::handle value, const std::string& what);

/// A volume argument's voxels where they are: a float32 C-contiguous array is read in place (numpy converts another
/// dtype or layout once); `array` keeps them alive for as long as the grid is used.
struct BorrowedVoxels {
  py::array_t<float, py::array::c_style | py::array::forcecast> array;
  VoxelGrid grid;
};
BorrowedVoxels voxels(py::handle value, const std::string& what);
/// A volume argument: a tessera.Volume, or an array (Z, Y, X) of numbers with spacing and origin 1 and 0. Throws
/// InvalidInput naming `what`.
Volume<float> volume(py::handle value, const std::string& what);
/// The volume as tessera.Volume (its data a float32 array (Z, Y, X) viewing the moved volume).
py::object to_python(Volume<float> volume);

}  // namespace tessera::python
