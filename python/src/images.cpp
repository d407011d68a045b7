// Images, colors and textures: image files in and out, 8-bit and float conversions, color models over arrays.
#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cstring>
#include <variant>

#include "bindings.hpp"
#include "convert.hpp"
#include "tessera/color/model.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/image/texture.hpp"

namespace tessera::python {
namespace {

/// An 8-bit image as a uint8 array (H, W, 4) viewing it.
py::array to_python_bytes(ImageRGBA8 image) {
  auto owner = std::make_shared<const ImageRGBA8>(std::move(image));
  const uint8_t* data = owner->empty() ? nullptr : &owner->pixels()[0][0];
  return owned_array<uint8_t>(owner, data, {owner->height(), owner->width(), 4});
}

/// A uint8 array (H, W, 4) as an 8-bit image (copied).
ImageRGBA8 bytes_image(const py::array_t<uint8_t, py::array::c_style>& a) {
  ImageRGBA8 out(int(a.shape(1)), int(a.shape(0)));
  std::memcpy(out.pixels().data(), a.data(), size_t(a.size()));
  return out;
}

/// Whether `value` is a uint8 array (H, W, 4): written as its bytes, without a float round trip.
bool is_rgba_bytes(py::handle value) {
  if (!py::isinstance<py::array>(value)) return false;
  const auto a = py::reinterpret_borrow<py::array>(value);
  return a.dtype().is(py::dtype::of<uint8_t>()) && a.ndim() == 3 && a.shape(2) == 4;
}

py::object read(const std::filesystem::path& path, const std::string& dtype) {
  if (dtype != "float32" && dtype != "uint8")
    throw InvalidInput(fmt::format("dtype: expected 'float32' or 'uint8', got '{}'", dtype));
  if (dtype == "float32") {
    ImageRGBA image;
    {
      py::gil_scoped_release release;
      image = read_image(path);
    }
    return to_python(std::move(image));
  }
  ImageRGBA8 bytes;
  {
    py::gil_scoped_release release;
    FileImage file = read_image_native(path);
    bytes = std::holds_alternative<ImageRGBA8>(file) ? std::move(std::get<ImageRGBA8>(file))
                                                     : to_rgba8(std::get<ImageRGBA>(file));
  }
  return to_python_bytes(std::move(bytes));
}

void write(const std::filesystem::path& path, py::handle image, bool srgb, int jpeg_quality) {
  const WriteOptions options{.srgb = srgb, .jpeg_quality = jpeg_quality};
  if (is_rgba_bytes(image)) {
    const ImageRGBA8 bytes =
        bytes_image(py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(image));
    py::gil_scoped_release release;
    write_image(path, bytes, options);
    return;
  }
  ImageRGBA rgba = image_rgba(image, "image");
  // Without alpha the file gets none (an RGB PNG, as the CLI writes renders).
  const bool opaque = py::array::ensure(image).ndim() == 2 || py::array::ensure(image).shape(2) == 3;
  py::gil_scoped_release release;
  if (opaque)
    write_image(path, to_rgb(rgba), options);
  else
    write_image(path, rgba, options);
}

/// Scales the hue component of every color in place (turns <-> the caller's unit).
void scale_hue(std::span<double> values, int components, int hue, double factor) {
  if (hue < 0 || factor == 1) return;
  for (size_t i = size_t(hue); i < values.size(); i += size_t(components)) values[i] *= factor;
}

py::array convert(py::handle values, const std::string& from_name, const std::string& to_name,
                  const std::string& hue_unit) {
  const ColorModel from = parse_color_model(from_name), to = parse_color_model(to_name);
  const double turn = full_turn(parse_hue_unit(hue_unit));
  const int nf = component_count(from), nt = component_count(to);
  auto in = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!in || in.ndim() < 1 || in.shape(in.ndim() - 1) != nf) {
    PyErr_Clear();
    throw InvalidInput(fmt::format("colors: expected an array (..., {}) of {} colors", nf, from_name));
  }
  std::vector<py::ssize_t> shape(in.shape(), in.shape() + in.ndim());
  shape.back() = nt;
  py::array_t<double> out(shape);
  std::span<const double> source(in.data(), size_t(in.size()));
  std::vector<double> scaled;  // a copy only when the hue's unit is not the library's turns
  if (turn != 1 && hue_index(from) >= 0) {
    scaled.assign(source.begin(), source.end());
    scale_hue(scaled, nf, hue_index(from), 1 / turn);
    source = scaled;
  }
  std::span<double> target(out.mutable_data(), size_t(out.size()));
  {
    py::gil_scoped_release release;
    convert_many(from, to, source, target);
  }
  scale_hue(target, nt, hue_index(to), turn);
  return out;
}

}  // namespace

namespace {

Sampler sampler(const std::string& filter, const std::string& wrap_u, const std::string& wrap_v) {
  const auto wrap = [](const std::string& name, const char* what) {
    return choice<Wrap>(name, {{"repeat", Wrap::repeat}, {"clamp", Wrap::clamp}, {"mirror", Wrap::mirror}}, what);
  };
  return {.wrap_u = wrap(wrap_u, "wrap"),
          .wrap_v = wrap(wrap_v.empty() ? wrap_u : wrap_v, "wrap_v"),
          .filter = choice<Filter>(
              filter, {{"nearest", Filter::nearest}, {"bilinear", Filter::bilinear}, {"trilinear", Filter::trilinear}},
              "filter")};
}

void bind_texture(py::module_& m) {
  py::class_<Texture2D, std::shared_ptr<Texture2D>>(m, "Texture", R"(A 2D texture with MIPmaps (the notes' texture
mapping): sample(uv) reads it at (u, v) in [0, 1]^2 (v upward, as OpenGL: v = 0 is the image's bottom row) with the
filter 'nearest', 'bilinear' or 'trilinear' (MIPmaps; lod picks the level) and the wrap 'repeat', 'clamp' or 'mirror'.
An 8-bit image (uint8, or a file read as 8-bit) stays 8-bit, as GL_RGBA8.)")
      .def(
          py::init([](py::handle image, const std::string& filter, const std::string& wrap, const std::string& wrap_v) {
            const Sampler s = sampler(filter, wrap, wrap_v);
            if (py::isinstance<py::str>(image) || py::hasattr(image, "__fspath__"))
              return std::make_shared<Texture2D>(load_texture(py::str(image).cast<std::string>(), s));
            if (is_rgba_bytes(image))
              return std::make_shared<Texture2D>(
                  bytes_image(py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(image)), s);
            return std::make_shared<Texture2D>(image_rgba(image, "image"), s);
          }),
          py::arg("image"), py::arg("filter") = "bilinear", py::arg("wrap") = "repeat", py::arg("wrap_v") = "",
          "A texture of an image array or file with its sampler (wrap_v: as wrap unless given).")
      .def_property_readonly("width", &Texture2D::width, "Width of level 0 in texels.")
      .def_property_readonly("height", &Texture2D::height, "Height of level 0 in texels.")
      .def_property_readonly("levels", &Texture2D::levels, "The number of MIPmap levels.")
      .def(
          "level", [](const Texture2D& t, int i) { return to_python(t.level(i)); }, py::arg("i"),
          "MIPmap level i (0 = the image) as a float Image.")
      .def(
          "sample",
          [](const Texture2D& t, py::handle uv, py::handle lod) {
            const auto a = rows(uv, 2, "uv");
            const auto n = size_t(a.shape(0));
            std::vector<float> lods(n, 0.0f);
            if (!lod.is_none()) {
              const auto l = py::array_t<float, py::array::forcecast>::ensure(lod);
              if (!l || (l.size() != 1 && size_t(l.size()) != n)) {
                PyErr_Clear();
                throw InvalidInput("lod: expected a number or one per uv row");
              }
              for (size_t i = 0; i < n; ++i) lods[i] = l.data()[l.size() == 1 ? 0 : i];
            }
            py::array_t<float> out(std::vector<py::ssize_t>{py::ssize_t(n), 4});
            float* o = out.mutable_data();
            const double* p = a.data();
            {
              py::gil_scoped_release release;
              parallel_for(0, int64_t(n), 16384, [&](int64_t begin, int64_t end) {
                for (auto i = size_t(begin); i < size_t(end); ++i) {
                  const glm::vec4 c = t.sample(glm::vec2(float(p[2 * i]), float(p[2 * i + 1])), lods[i]);
                  for (int k = 0; k < 4; ++k) o[4 * i + size_t(k)] = c[k];
                }
              });
            }
            return out;
          },
          py::arg("uv"), py::arg("lod") = py::none(),
          "Samples at uv (N, 2), lod a number or (N,) (trilinear only); returns RGBA (N, 4) float32.");
}

}  // namespace

void bind_images(py::module_& m) {
  bind_texture(m);
  m.def("read_image", &read, py::arg("path"), py::arg("dtype") = "float32",
        R"(Reads an image file (PNG, JPG, BMP, TGA, HDR, PPM/PGM, PFM) as an Image.

dtype 'float32' (default): linear float RGBA (H, W, 4), 8-bit values v/255 without gamma decoding (as OpenGL and
Processing), 16-bit v/65535, HDR and PFM as stored. dtype 'uint8': the file's 8-bit values (H, W, 4) as a texture keeps
them; float files are clamped and rounded. Row 0 is the top row. Raises IoError or InvalidInput naming the file.)");
  m.def("write_image", &write, py::arg("path"), py::arg("image"), py::kw_only(), py::arg("srgb") = false,
        py::arg("jpeg_quality") = 95,
        R"(Writes an image array to PNG, PPM, PFM, HDR, JPG, BMP or TGA (the extension picks the format).

image: (H, W), (H, W, 3) or (H, W, 4); float (linear, clamped to [0, 1] for 8-bit files) or uint8 (written as is).
srgb: encode float values with the sRGB curve for 8-bit files. The write is atomic: a failure leaves no partial file.)");
  m.def(
      "to_uint8",
      [](py::handle image, bool srgb) {
        const ImageRGBA rgba = image_rgba(image, "image");
        ImageRGBA8 bytes;
        {
          py::gil_scoped_release release;
          bytes = to_rgba8(rgba, srgb);
        }
        return to_python_bytes(std::move(bytes));
      },
      py::arg("image"), py::arg("srgb") = false,
      "8-bit RGBA (H, W, 4) uint8 from a float image: clamped to [0, 1] (NaN -> 0), optionally sRGB-encoded, rounded.");
  m.def(
      "to_float",
      [](py::handle image, bool srgb) {
        auto a = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(image);
        if (!a || a.ndim() != 3 || a.shape(2) != 4) {
          PyErr_Clear();
          throw InvalidInput("image: expected a uint8 array (H, W, 4)");
        }
        const ImageRGBA8 bytes = bytes_image(a);
        ImageRGBA rgba;
        {
          py::gil_scoped_release release;
          rgba = to_float(bytes, srgb);
        }
        return to_python(std::move(rgba));
      },
      py::arg("image"), py::arg("srgb") = false,
      "Linear float RGBA Image from 8-bit RGBA: v/255, or sRGB-decoded color channels when srgb (alpha stays v/255).");
  m.def("convert_colors", &convert, py::arg("colors"), py::arg("source"), py::arg("target"), py::kw_only(),
        py::arg("hue") = "turns",
        R"(Converts colors between models: rgb cmy cmyk hsv hls yiq xyz xyy srgb.

colors: an array (..., n) with n = 4 for cmyk, else 3; returns (..., m) for the target model, float64. Conversions go
through linear RGB (the notes' formulas; hls as Python's colorsys). hue: the unit of HSV's and HLS's hue, 'turns'
(default, colorsys's [0, 1)), 'degrees' or 'radians'. Vectorized in C++: no Python loop per color.)");
  m.attr("color_models") = [] {
    py::list names;
    for (ColorModel model : kColorModels) names.append(std::string(model_name(model)));
    return names;
  }();
}

}  // namespace tessera::python
