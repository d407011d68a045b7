#include "convert.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "tessera/core/error.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera::python {
namespace {

/// "(2, 3)": an array's shape as numpy prints it.
std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += fmt::format("{}{}", i ? ", " : "", a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// `value` as a contiguous array of T, converting; InvalidInput naming `what` when numpy cannot.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> as_array(py::handle value, const std::string& what) {
  auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a) {
    PyErr_Clear();
    throw InvalidInput(fmt::format("{}: expected an array of numbers, got {}", what,
                                   std::string(py::str(py::type::of(value).attr("__name__")))));
  }
  return a;
}

/// The tessera package's class `name` (Image, Mesh, Volume): the Python side of the types.
py::object package_class(const char* name) { return py::module_::import("tessera").attr(name); }

/// A vector of N glm vectors (N x cols values) viewed as an (N, cols) array, or None when empty.
template <class V>
py::object rows_or_none(const std::shared_ptr<const PolyMesh>& owner, const std::vector<V>& v) {
  if (v.empty()) return py::none();
  return owned_array<typename V::value_type>(owner, &v[0][0], {py::ssize_t(v.size()), V::length()});
}

/// Copies an (N, cols) array into glm vectors, checking N.
template <class V>
std::vector<V> vectors(py::handle value, size_t count, const std::string& what, const std::string& per) {
  const auto a = rows(value, V::length(), what);
  if (size_t(a.shape(0)) != count)
    throw InvalidInput(fmt::format("{}: expected one row per {} ({}), got {}", what, per, count, a.shape(0)));
  std::vector<V> out(count);
  const double* p = a.data();
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < V::length(); ++c) out[i][c] = typename V::value_type(p[i * V::length() + c]);
  return out;
}

}  // namespace

py::array_t<double, py::array::c_style | py::array::forcecast> rows(py::handle value, int cols,
                                                                    const std::string& what) {
  auto a = as_array<double>(value, what);
  if (a.ndim() != 2 || a.shape(1) != cols)
    throw InvalidInput(fmt::format("{}: expected an (N, {}) array, got shape {}", what, cols, shape_text(a)));
  const double* p = a.data();
  const auto n = size_t(a.size());
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(p[i]))
      throw InvalidInput(fmt::format("{}: row {} has a value that is not finite ({})", what, i / size_t(cols), p[i]));
  return a;
}

Vec3 vec3(py::handle value, const std::string& what) {
  const auto a = as_array<double>(value, what);
  if (a.size() != 3)
    throw InvalidInput(fmt::format("{}: expected 3 numbers (x, y, z), got shape {}", what, shape_text(a)));
  const Vec3 v(a.data()[0], a.data()[1], a.data()[2]);
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw InvalidInput(fmt::format("{}: expected finite numbers, got ({}, {}, {})", what, v.x, v.y, v.z));
  return v;
}

Vec3f color(py::handle value, const std::string& what) {
  if (py::isinstance<py::str>(value)) {
    const std::string text = py::str(value);
    try {
      const Vec4f c = parse_svg_color(text);
      return {c.x, c.y, c.z};
    } catch (const InvalidInput&) {
      throw InvalidInput(fmt::format(
          "{}: expected a color name (as SVG's: white, cornflowerblue), #rrggbb or (r, g, b) in [0, 1], got '{}'", what,
          text));
    }
  }
  const Vec3 c = vec3(value, what);
  if (c.x < 0 || c.y < 0 || c.z < 0 || c.x > 1 || c.y > 1 || c.z > 1)
    throw InvalidInput(fmt::format("{}: color components must be in [0, 1], got ({}, {}, {})", what, c.x, c.y, c.z));
  return Vec3f(c);
}

py::object to_python(ImageRGB image) {
  auto owner = std::make_shared<const ImageRGB>(std::move(image));
  const float* data = owner->empty() ? nullptr : &owner->pixels()[0][0];
  return owned_array<float>(owner, data, {owner->height(), owner->width(), 3}).attr("view")(package_class("Image"));
}

py::object to_python(ImageRGBA image) {
  auto owner = std::make_shared<const ImageRGBA>(std::move(image));
  const float* data = owner->empty() ? nullptr : &owner->pixels()[0][0];
  return owned_array<float>(owner, data, {owner->height(), owner->width(), 4}).attr("view")(package_class("Image"));
}

py::object to_python(DepthImage image) {
  auto owner = std::make_shared<const DepthImage>(std::move(image));
  const float* data = owner->empty() ? nullptr : owner->pixels().data();
  return owned_array<float>(owner, data, {owner->height(), owner->width()});
}

ImageRGBA image_rgba(py::handle value, const std::string& what) {
  const py::array raw = py::array::ensure(value);
  if (!raw) {
    PyErr_Clear();
    throw InvalidInput(fmt::format("{}: expected an image array (H, W), (H, W, 3) or (H, W, 4)", what));
  }
  const int channels = raw.ndim() == 2 ? 1 : raw.ndim() == 3 ? int(raw.shape(2)) : 0;
  if (channels != 1 && channels != 3 && channels != 4)
    throw InvalidInput(
        fmt::format("{}: expected an image array (H, W), (H, W, 3) or (H, W, 4), got shape {}", what, shape_text(raw)));
  const bool bytes = raw.dtype().is(py::dtype::of<uint8_t>());
  const auto a = as_array<float>(raw, what);
  ImageRGBA out(int(a.shape(1)), int(a.shape(0)), Vec4f(0, 0, 0, 1));
  const float* p = a.data();
  const float scale = bytes ? 1.0f / 255.0f : 1.0f;
  std::span<Vec4f> px = out.pixels();
  for (size_t i = 0; i < px.size(); ++i) {
    const float* s = p + i * size_t(channels);
    px[i] = channels == 1   ? Vec4f(Vec3f(s[0] * scale), 1.0f)
            : channels == 3 ? Vec4f(s[0] * scale, s[1] * scale, s[2] * scale, 1.0f)
                            : Vec4f(s[0], s[1], s[2], s[3]) * scale;
  }
  return out;
}

DepthImage field(py::handle value, const std::string& what) {
  const auto a = as_array<float>(value, what);
  if (a.ndim() != 2) throw InvalidInput(fmt::format("{}: expected an array (H, W), got shape {}", what, shape_text(a)));
  DepthImage out(int(a.shape(1)), int(a.shape(0)));
  std::copy_n(a.data(), a.size(), out.pixels().data());
  return out;
}

py::object to_python(PolyMesh mesh) {
  auto owner = std::make_shared<const PolyMesh>(std::move(mesh));
  const PolyMesh& m = *owner;
  const auto flat = [&](const std::vector<uint32_t>& v) {
    return owned_array<uint32_t>(owner, v.data(), {py::ssize_t(v.size())});
  };
  std::vector<uint32_t> edges, corner_vertices;
  std::vector<float> crease_sharpness, corner_sharpness;
  for (const EdgeCrease& c : m.creases)
    edges.insert(edges.end(), {c.v0, c.v1}), crease_sharpness.push_back(c.sharpness);
  for (const VertexCorner& c : m.corners) corner_vertices.push_back(c.v), corner_sharpness.push_back(c.sharpness);
  py::object creases = py::none(), corners = py::none();
  if (!m.creases.empty())
    creases = py::make_tuple(py::array_t<uint32_t>({py::ssize_t(m.creases.size()), py::ssize_t(2)}, edges.data()),
                             py::array_t<float>(py::ssize_t(crease_sharpness.size()), crease_sharpness.data()));
  if (!m.corners.empty())
    corners = py::make_tuple(py::array_t<uint32_t>(py::ssize_t(corner_vertices.size()), corner_vertices.data()),
                             py::array_t<float>(py::ssize_t(corner_sharpness.size()), corner_sharpness.data()));
  return package_class("Mesh").attr("_from_arrays")(
      rows_or_none(owner, m.positions).is_none() ? py::object(py::array_t<double>(std::vector<py::ssize_t>{0, 3}))
                                                 : rows_or_none(owner, m.positions),
      flat(m.face_vertices), flat(m.face_offsets), rows_or_none(owner, m.normals), rows_or_none(owner, m.uvs),
      rows_or_none(owner, m.colors), rows_or_none(owner, m.corner_uvs), rows_or_none(owner, m.corner_normals), creases,
      corners);
}

PolyMesh mesh(py::handle value, const std::string& what) {
  // tessera.Mesh keeps faces flat (any valence); other meshes (trimesh's) give an (M, k) array.
  const bool flat = py::hasattr(value, "face_vertices") && py::hasattr(value, "face_offsets");
  if (!py::hasattr(value, "vertices") || !(flat || py::hasattr(value, "faces")))
    throw InvalidInput(fmt::format("{}: expected a tessera.Mesh (or an object with vertices and faces), got {}", what,
                                   std::string(py::str(py::type::of(value).attr("__name__")))));
  PolyMesh m;
  const auto v = rows(value.attr("vertices"), 3, what + ".vertices");
  m.positions.resize(size_t(v.shape(0)));
  std::memcpy(m.positions.data(), v.data(), m.positions.size() * sizeof(Vec3));
  const auto indices = [&](py::handle h, const std::string& name) { return as_array<int64_t>(h, what + "." + name); };
  if (flat) {
    const auto fv = indices(value.attr("face_vertices"), "face_vertices");
    const auto fo = indices(value.attr("face_offsets"), "face_offsets");
    if (fv.ndim() != 1 || fo.ndim() != 1 || fo.size() < 1 || fo.data()[0] != 0 || fo.data()[fo.size() - 1] != fv.size())
      throw InvalidInput(
          fmt::format("{}: face_offsets must start at 0 and end at len(face_vertices) ({})", what, fv.size()));
    for (py::ssize_t f = 0; f + 1 < fo.size(); ++f)
      if (fo.data()[f + 1] < fo.data()[f] + 3)
        throw InvalidInput(
            fmt::format("{}: face {} has {} vertices (at least 3)", what, f, fo.data()[f + 1] - fo.data()[f]));
    for (py::ssize_t i = 0; i < fv.size(); ++i)
      if (fv.data()[i] < 0 || size_t(fv.data()[i]) >= m.positions.size())
        throw InvalidInput(fmt::format("{}: face_vertices[{}] = {} is not a vertex index (0..{})", what, i,
                                       fv.data()[i], int64_t(m.positions.size()) - 1));
    m.face_offsets.assign(fo.data(), fo.data() + fo.size());
    m.face_vertices.assign(fv.data(), fv.data() + fv.size());
  } else {
    const auto faces = indices(value.attr("faces"), "faces");
    if (faces.ndim() != 2 || faces.shape(1) < 3)
      throw InvalidInput(fmt::format("{}.faces: expected an (M, k) array of vertex indices, k >= 3, got shape {}", what,
                                     shape_text(faces)));
    const auto k = size_t(faces.shape(1));
    for (py::ssize_t f = 0; f < faces.shape(0); ++f) {
      for (size_t c = 0; c < k; ++c) {
        const int64_t i = faces.data()[size_t(f) * k + c];
        if (i < 0 || size_t(i) >= m.positions.size())
          throw InvalidInput(fmt::format("{}.faces[{}, {}] = {} is not a vertex index (0..{})", what, f, c, i,
                                         int64_t(m.positions.size()) - 1));
        m.face_vertices.push_back(uint32_t(i));
      }
      m.face_offsets.push_back(uint32_t(m.face_vertices.size()));
    }
  }
  const auto optional = [&](const char* name) { return py::getattr(value, name, py::none()); };
  const size_t nv = m.positions.size(), nc = m.face_vertices.size();
  const std::string w = what + ".";
  if (py::object o = optional("normals"); !o.is_none()) m.normals = vectors<Vec3>(o, nv, w + "normals", "vertex");
  if (py::object o = optional("uvs"); !o.is_none()) m.uvs = vectors<Vec2>(o, nv, w + "uvs", "vertex");
  if (py::object o = optional("colors"); !o.is_none()) m.colors = vectors<Vec3>(o, nv, w + "colors", "vertex");
  if (py::object o = optional("corner_uvs"); !o.is_none())
    m.corner_uvs = vectors<Vec2>(o, nc, w + "corner_uvs", "face corner");
  if (py::object o = optional("corner_normals"); !o.is_none())
    m.corner_normals = vectors<Vec3>(o, nc, w + "corner_normals", "face corner");
  if (py::object o = optional("crease_edges"); !o.is_none()) {
    const auto e = as_array<int64_t>(o, w + "crease_edges");
    const auto s = as_array<float>(optional("crease_sharpness"), w + "crease_sharpness");
    if (e.ndim() != 2 || e.shape(1) != 2 || s.ndim() != 1 || s.shape(0) != e.shape(0))
      throw InvalidInput(fmt::format("{}: expected crease_edges (K, 2) and crease_sharpness (K,)", what));
    for (py::ssize_t i = 0; i < e.shape(0); ++i) {
      const int64_t a = e.data()[2 * i], b = e.data()[2 * i + 1];
      if (a < 0 || b < 0 || size_t(a) >= nv || size_t(b) >= nv)
        throw InvalidInput(fmt::format("{}: crease {} names vertex {} or {}, not a vertex index", what, i, a, b));
      m.creases.push_back({uint32_t(a), uint32_t(b), s.data()[i]});
    }
  }
  if (py::object o = optional("corner_vertices"); !o.is_none()) {
    const auto v2 = as_array<int64_t>(o, w + "corner_vertices");
    const auto s = as_array<float>(optional("corner_sharpness"), w + "corner_sharpness");
    if (v2.ndim() != 1 || s.ndim() != 1 || s.shape(0) != v2.shape(0))
      throw InvalidInput(fmt::format("{}: expected corner_vertices (C,) and corner_sharpness (C,)", what));
    for (py::ssize_t i = 0; i < v2.shape(0); ++i) {
      if (v2.data()[i] < 0 || size_t(v2.data()[i]) >= nv)
        throw InvalidInput(fmt::format("{}: corner {} names vertex {}, not a vertex index", what, i, v2.data()[i]));
      m.corners.push_back({uint32_t(v2.data()[i]), s.data()[i]});
    }
  }
  return m;
}

BorrowedVoxels voxels(py::handle value, const std::string& what) {
  const bool wrapped = py::hasattr(value, "data") && py::hasattr(value, "spacing") && !py::isinstance<py::array>(value);
  auto a = as_array<float>(wrapped ? value.attr("data") : py::object(py::reinterpret_borrow<py::object>(value)), what);
  if (a.ndim() != 3)
    throw InvalidInput(fmt::format("{}: expected a volume array (Z, Y, X), got shape {}", what, shape_text(a)));
  const Vec3 spacing = wrapped ? vec3(value.attr("spacing"), what + ".spacing") : Vec3(1.0);
  const Vec3 origin = wrapped ? vec3(value.attr("origin"), what + ".origin") : Vec3(0.0);
  const VoxelGrid grid{a.data(), glm::ivec3(int(a.shape(2)), int(a.shape(1)), int(a.shape(0))), spacing, origin};
  return {std::move(a), grid};
}

Volume<float> volume(py::handle value, const std::string& what) {
  const BorrowedVoxels b = voxels(value, what);
  Volume<float> v(b.grid.dims, 0.0f, b.grid.spacing, b.grid.origin);
  std::copy_n(b.grid.voxels, v.voxel_count(), v.voxels().data());
  return v;
}

py::object to_python(Volume<float> volume) {
  auto owner = std::make_shared<const Volume<float>>(std::move(volume));
  const glm::ivec3 d = owner->dims();
  const py::array data = owned_array<float>(owner, owner->voxels().data(), {d.z, d.y, d.x});
  const Vec3 s = owner->spacing(), o = owner->origin();
  return package_class("Volume")(data, py::make_tuple(s.x, s.y, s.z), py::make_tuple(o.x, o.y, o.z));
}

}  // namespace tessera::python

namespace tessera::python {

py::object Options::take(const char* name) {
  read_.emplace_back(name);
  return options_.contains(name) ? py::reinterpret_borrow<py::object>(options_[name]) : py::object(py::none());
}

void Options::finish(const std::string& what) const {
  for (const auto& [key, value] : options_) {
    const std::string name = py::str(key);
    if (std::find(read_.begin(), read_.end(), name) == read_.end())
      throw InvalidInput(fmt::format("{}: unknown option '{}'", what, name));
  }
}

Framing framing(Options& options, double fovy) {
  Framing f;
  f.fovy = options.get("fovy", fovy);
  const py::object view_name = options.take("view"), azimuth = options.take("azimuth"),
                   elevation = options.take("elevation"), eye = options.take("eye");
  if (!eye.is_none() && !(view_name.is_none() && azimuth.is_none() && elevation.is_none()))
    throw InvalidInput("eye: it places the camera; give eye, or view/azimuth/elevation, not both");
  const auto view =
      choice(view_name.is_none() ? "three-quarter" : view_name.cast<std::string>(), kFramedViewNames, "view");
  f.angles = view_angles(view);
  if (!azimuth.is_none()) f.angles.azimuth = azimuth.cast<double>();
  if (!elevation.is_none()) f.angles.elevation = elevation.cast<double>();
  if (!eye.is_none()) f.eye = vec3(eye, "eye");
  f.up_axis = choice(options.get<std::string>("up_axis", "y"), kUpAxisNames, "up_axis");
  f.front_axis = choice(options.get<std::string>("front_axis", "auto"), kFrontAxisNames, "front_axis");
  for (auto [name, slot] : {std::pair{"center", &f.center}, {"up", &f.up}})
    if (const py::object o = options.take(name); !o.is_none()) *slot = vec3(o, name);
  f.ortho = options.get("ortho", false);
  f.ortho_size = options.get("ortho_size", 0.0);
  f.near = options.get("near", 0.0);
  f.far = options.get("far", 0.0);
  return f;
}

}  // namespace tessera::python
