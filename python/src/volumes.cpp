// Volumes: volume files, procedural fields, isosurfaces (marching cubes), contours (marching squares), ray casting.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/marching_squares.hpp"
#include "tessera/volume/procedural.hpp"
#include "tessera/volume/volume_io.hpp"
#include "tessera/volume/volume_render.hpp"

namespace tessera::python {
namespace {

/// The transfer function of render_volume: None (automatic, from the values' profile), a preset name, a file
/// (.json or .csv, as --tf reads) or rows (value, r, g, b, opacity in [0, 1] per unit length).
TransferFunction transfer_function(const py::object& value, const Volume<float>& v) {
  if (value.is_none()) return TransferFunction::automatic(profile_values(v));
  if (py::isinstance<py::str>(value)) {
    const std::string name = py::str(value);
    for (const std::string& preset : TransferFunction::preset_names())
      if (name == preset) return TransferFunction::preset(name, profile_values(v));
    return TransferFunction::load(name);
  }
  const auto r = rows(value, 5, "transfer");
  std::vector<TransferFunction::Point> points;
  for (py::ssize_t i = 0; i < r.shape(0); ++i) {
    const double* p = r.data() + 5 * i;
    points.push_back({float(p[0]), Vec3f(float(p[1]), float(p[2]), float(p[3])), float(p[4])});
  }
  return TransferFunction(std::move(points));
}

py::object render(py::handle value, int width, int height, py::dict kwargs) {
  Options options(std::move(kwargs));
  const Volume<float> v = volume(value, "volume");
  VolumeRenderOptions o;
  o.width = width;
  o.height = height;
  o.mip = options.get("mip", false);
  o.step = options.get("step", 0.0f);
  o.shading = options.get("shading", true);
  o.background = color(options.get<py::object>("background", py::make_tuple(0, 0, 0)), "background");
  const py::object transfer = options.take("transfer");
  // A volume's box fills a narrower view better (the CLI's default too).
  const Framing f = framing(options, 30);
  options.finish("render_volume");
  o.camera = frame_camera(f, v.origin(), v.to_world(Vec3(v.dims() - 1)), double(width) / double(height));
  if (!o.mip) o.transfer = transfer_function(transfer, v);
  ImageRGB image;
  {
    py::gil_scoped_release release;
    image = render_volume(v, o);
  }
  return to_python(std::move(image));
}

}  // namespace

void bind_volumes(py::module_& m) {
  m.def(
      "read_volume",
      [](const std::filesystem::path& name, std::optional<std::array<int, 3>> dims, const std::string& dtype,
         const std::string& byte_order, std::optional<std::array<double, 3>> spacing, uint64_t header_skip) {
        RawLayout layout;
        if (dims) layout.dims = {(*dims)[0], (*dims)[1], (*dims)[2]};
        layout.type = parse_voxel_type(dtype);
        layout.endian = choice<Endian>(byte_order, {{"little", Endian::little}, {"big", Endian::big}}, "byte_order");
        if (spacing) layout.spacing = {(*spacing)[0], (*spacing)[1], (*spacing)[2]};
        layout.header_skip = header_skip;
        Volume<float> v;
        {
          py::gil_scoped_release release;
          v = to_float(read_volume(name.string(), layout));
        }
        return to_python(std::move(v));
      },
      py::arg("path"), py::kw_only(), py::arg("dims") = py::none(), py::arg("dtype") = "uint8",
      py::arg("byte_order") = "little", py::arg("spacing") = py::none(), py::arg("header_skip") = 0,
      R"(Reads a volume as a Volume of float32 values: NRRD (.nrrd, .nhdr), MetaImage (.mhd) or raw voxels (.raw, with
dims=(x, y, z), dtype 'uint8' 'uint16' 'int16' 'float32', byte_order and spacing), or a procedural field 'sphere:N',
'torus:N', 'gyroid:N', 'metaballs:N', 'noise:N' (as the CLI's volume inputs). Raises IoError or InvalidInput naming
the file and what was expected.)");
  m.def(
      "write_volume",
      [](const std::filesystem::path& path, py::handle value, bool gzip) {
        const Volume<float> v = volume(value, "volume");
        py::gil_scoped_release release;
        write_nrrd(path, AnyVolume(v), gzip);
      },
      py::arg("path"), py::arg("volume"), py::kw_only(), py::arg("gzip") = false,
      "Writes a volume (float32 voxels, spacing and origin) as NRRD, optionally gzip-compressed. Atomic.");
  m.def(
      "marching_cubes",
      [](py::handle value, float iso, bool topological, bool normals) {
        const BorrowedVoxels v = voxels(value, "volume");  // read in place: no copy of a float32 array
        PolyMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = marching_cubes(v.grid, {.iso = iso, .topological = topological, .normals = normals});
        }
        return to_python(std::move(mesh));
      },
      py::arg("volume"), py::arg("iso") = 0.0f, py::kw_only(), py::arg("topological") = false,
      py::arg("normals") = true,
      R"(The isosurface value = iso of a volume (a Volume or an array (Z, Y, X)) as a triangle Mesh in world
coordinates (x, y, z) = origin + spacing * (i, j, k): Lorensen and Cline's marching cubes with shared vertices, inside
where value >= iso. topological=True resolves ambiguous faces with the asymptotic decider (a watertight surface).
normals: per-vertex normals from the field's gradient.)");
  m.def(
      "marching_squares",
      [](py::handle value, float iso) {
        const DepthImage f = field(value, "field");
        std::vector<Polyline> lines;
        {
          py::gil_scoped_release release;
          lines = marching_squares(f, iso);
        }
        py::list out;
        for (Polyline& line : lines) {
          auto owner = std::make_shared<const Polyline>(std::move(line));
          out.append(py::make_tuple(owned_array<double>(owner, owner->points.empty() ? nullptr : &owner->points[0][0],
                                                        {py::ssize_t(owner->points.size()), 2}),
                                    owner->closed));
        }
        return out;
      },
      py::arg("field"), py::arg("iso") = 0.0f,
      "The contour lines value = iso of a 2D field (H, W) as a list of (points (K, 2) as (x, y), closed) polylines.");
  m.def(
      "procedural_volume",
      [](const std::string& spec) {
        Volume<float> v;
        {
          py::gil_scoped_release release;
          if (!make_procedural(spec, v))
            throw InvalidInput(fmt::format("'{}': expected sphere:N, torus:N, gyroid:N, metaballs:N or noise:N", spec));
        }
        return to_python(std::move(v));
      },
      py::arg("spec"),
      "A procedural field: 'sphere:N', 'torus:N', 'gyroid:N', 'metaballs:N' or 'noise:N' (N^3 voxels).");
  m.def("_render_volume", &render, py::arg("volume"), py::arg("width"), py::arg("height"), py::arg("options"));
}

}  // namespace tessera::python
