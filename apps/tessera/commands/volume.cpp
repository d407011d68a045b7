// tessera volume info|slice|contour|isosurface|render: volume data from raw/NRRD/MetaImage files or procedural names.
#include <chrono>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "camera_options.hpp"
#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/marching_squares.hpp"
#include "tessera/volume/volume_io.hpp"
#include "tessera/volume/volume_render.hpp"

namespace tessera::cli {
namespace {

/// The volume argument and the raw layout options every subcommand takes.
struct VolumeInput {
  std::string path, dims, dtype = "uint8", endian = "little", spacing;
  long long header_skip = 0;

  void add(CLI::App& app) {
    app.add_option("volume", path, "Volume: FILE.nrrd|.nhdr|.mhd, a raw file with --dims, or sphere:N, torus:N, gyroid:N, "
                                   "metaballs:N, noise:N[:SEED]")
        ->required();
    app.add_option("--dims", dims, "Raw voxels along x,y,z");
    app.add_option("--dtype", dtype, "Raw voxel type: uint8|uint16|int16|float32");
    app.add_option("--endian", endian, "Raw byte order: little|big");
    app.add_option("--spacing", spacing, "Raw voxel spacing sx,sy,sz");
    app.add_option("--header-skip", header_skip, "Raw bytes before the first voxel")->check(non_negative());
  }

  AnyVolume read() const {
    RawLayout layout;
    if (!dims.empty()) {
      const auto d = parse_doubles(dims, 3, "--dims");
      for (int i = 0; i < 3; ++i) {
        if (d[size_t(i)] < 1 || d[size_t(i)] > double(1 << 30) || d[size_t(i)] != std::floor(d[size_t(i)]))
          throw InvalidInput(fmt::format("--dims: expected three positive integers, got '{}'", dims));
        layout.dims[i] = int(d[size_t(i)]);
      }
    }
    layout.type = parse_voxel_type(dtype);
    if (endian != "little" && endian != "big") throw InvalidInput(fmt::format("--endian: expected little or big, got '{}'", endian));
    layout.endian = endian == "big" ? Endian::Big : Endian::Little;
    if (!spacing.empty()) {
      const auto s = parse_doubles(spacing, 3, "--spacing");
      layout.spacing = {s[0], s[1], s[2]};
      if (!(s[0] > 0 && s[1] > 0 && s[2] > 0)) throw InvalidInput("--spacing: values must be positive");
    }
    layout.header_skip = uint64_t(header_skip);
    return read_volume(path, layout);
  }
};

void setup_info(CLI::App& volume, CommonOptions&) {
  auto* cmd = volume.add_subcommand("info", "Dimensions, voxel type, spacing, origin and value range");
  auto in = std::make_shared<VolumeInput>();
  in->add(*cmd);
  cmd->callback([in] {
    const AnyVolume v = in->read();
    const auto d = dims_of(v);
    const auto s = spacing_of(v), o = origin_of(v);
    const auto [lo, hi] = std::visit([](const auto& x) { return value_range(x); }, v);
    fmt::print("dims={},{},{}\ntype={}\nspacing={},{},{}\norigin={},{},{}\nmin={}\nmax={}\n", d.x, d.y, d.z,
               voxel_type_name(voxel_type(v)), s.x, s.y, s.z, o.x, o.y, o.z, stat_value(lo), stat_value(hi));
  });
}

/// Grayscale image of a slice, values mapped from [lo, hi] to [0, 1].
ImageRGB gray_image(const DepthImage& s, double lo, double hi) {
  ImageRGB img(s.width(), s.height());
  for (int y = 0; y < s.height(); ++y)
    for (int x = 0; x < s.width(); ++x) img(x, y) = Vec3f(float(std::clamp((s(x, y) - lo) / std::max(hi - lo, 1e-12), 0.0, 1.0)));
  return img;
}

struct SliceArgs {
  std::string axis = "z";
  int index = 0;
  std::string output;
  void add(CLI::App& cmd) {
    cmd.add_option("--axis", axis, "Slice axis: x|y|z");
    cmd.add_option("--slice", index, "Slice index along the axis")->required();
    cmd.add_option("-o,--output", output, "Output file")->required();
  }
};

void setup_slice(CLI::App& volume, CommonOptions&) {
  auto* cmd = volume.add_subcommand("slice", "A plane of voxels as a grayscale image (min..max mapped to black..white)");
  auto in = std::make_shared<VolumeInput>();
  auto args = std::make_shared<SliceArgs>();
  in->add(*cmd);
  args->add(*cmd);
  cmd->callback([in, args] {
    const Volume<float> v = to_float(in->read());
    const auto [lo, hi] = value_range(v);
    write_image(args->output, gray_image(slice(v, parse_axis(args->axis), args->index), lo, hi));
  });
}

void setup_contour(CLI::App& volume, CommonOptions&) {
  auto* cmd = volume.add_subcommand("contour", "Marching-squares iso-lines of a slice, as SVG or PNG");
  auto in = std::make_shared<VolumeInput>();
  auto args = std::make_shared<SliceArgs>();
  auto iso = std::make_shared<float>(0.0f);
  in->add(*cmd);
  args->add(*cmd);
  cmd->add_option("--iso", *iso, "Iso value")->required();
  cmd->callback([in, args, iso] {
    const Volume<float> v = to_float(in->read());
    const DepthImage s = slice(v, parse_axis(args->axis), args->index);
    const auto lines = marching_squares(s, *iso);
    const std::string ext = std::filesystem::path(args->output).extension().string();
    if (ext == ".svg") {
      write_contours_svg(args->output, lines, s.width(), s.height());
      return;
    }
    const double scale = 4;
    Canvas canvas(int(s.width() * scale), int(s.height() * scale));
    canvas.background(Vec4f(1.0f));
    canvas.smooth();
    canvas.stroke(Vec4f(0.12f, 0.3f, 0.6f, 1.0f));
    canvas.stroke_weight(1.5);
    for (const auto& l : lines)
      for (size_t i = 0; i + 1 < l.points.size() + (l.closed ? 1 : 0); ++i) {
        const Vec2 a = (l.points[i] + 0.5) * scale, b = (l.points[(i + 1) % l.points.size()] + 0.5) * scale;
        canvas.line(a.x, a.y, b.x, b.y);
      }
    canvas.save(args->output);
  });
}

void setup_isosurface(CLI::App& volume, CommonOptions& common) {
  auto* cmd = volume.add_subcommand("isosurface", "Marching-cubes iso-surface as a mesh file");
  auto in = std::make_shared<VolumeInput>();
  auto options = std::make_shared<MarchingCubesOptions>();
  auto output = std::make_shared<std::string>();
  in->add(*cmd);
  cmd->add_option("--iso", options->iso, "Iso value (inside is value >= iso)")->required();
  cmd->add_option("-o,--output", *output, "Output mesh (.obj, .ply, .off, .stl)")->required();
  cmd->add_flag("--topological", options->topological, "Resolve ambiguous faces with the asymptotic decider");
  add_common_options(*cmd, common);
  cmd->callback([in, options, output, &common] {
    const ThreadLimit limit(common.threads);
    const Volume<float> v = to_float(in->read());
    const auto start = std::chrono::steady_clock::now();
    const PolyMesh mesh = marching_cubes(v, *options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_mesh(*output, mesh);
    if (common.stats)
      print_stats({{"tris", stat_value(double(mesh.face_count()))},
                   {"verts", stat_value(double(mesh.vertex_count()))},
                   {"area", stat_value(surface_area(mesh))},
                   {"volume", stat_value(signed_volume(mesh))},
                   {"seconds", stat_value(seconds)}});
  });
}

void setup_render(CLI::App& volume, CommonOptions& common) {
  auto* cmd = volume.add_subcommand("render", "Direct volume rendering (ray casting) or maximum-intensity projection");
  auto in = std::make_shared<VolumeInput>();
  struct Args {
    std::string output, tf, preset;
    CameraOptions camera;
    bool mip = false;
    float step = 0;
  };
  auto a = std::make_shared<Args>();
  in->add(*cmd);
  cmd->add_option("-o,--output", a->output, "Output image")->required();
  a->camera.fovy = 30;  // a volume's box fills a narrower view better
  a->camera.add(*cmd, "256x256");
  cmd->add_option("--tf", a->tf, "Transfer function file (.json or .csv)");
  cmd->add_option("--preset", a->preset, "Transfer-function preset: ct-bone|ct-skin|mri");
  cmd->add_flag("--mip", a->mip, "Maximum-intensity projection");
  cmd->add_option("--step", a->step, "Sample distance in world units (default: half the smallest spacing)");
  add_common_options(*cmd, common);
  cmd->callback([in, a, &common] {
    const ThreadLimit limit(common.threads);
    const Volume<float> v = to_float(in->read());
    VolumeRenderOptions o;
    const auto size = a->camera.image_size();
    o.width = size.width;
    o.height = size.height;
    o.step = a->step;
    o.mip = a->mip;
    // Framed as every 3D command frames its scene: the volume's bounding sphere fills the view from the +z side.
    const Vec3 lo = v.origin(), hi = v.to_world(Vec3(v.dims() - 1));
    o.camera = a->camera.camera(lo, hi);
    if (!a->tf.empty()) {
      o.transfer = TransferFunction::load(a->tf);
    } else if (!a->preset.empty()) {
      o.transfer = TransferFunction::preset(a->preset);
    } else {  // a ramp over the volume's upper half
      const auto [vlo, vhi] = value_range(v);
      const float m = float(0.5 * (vlo + vhi)), top = float(vhi);
      o.transfer = TransferFunction({{m, {0.9f, 0.6f, 0.4f}, 0.0f}, {top, {1.0f, 0.95f, 0.9f}, 0.8f}});
    }
    write_image(a->output, render_volume(v, o));
  });
}

}  // namespace

void setup_volume(CLI::App& volume, CommonOptions& common) {
  volume.require_subcommand(1);
  setup_info(volume, common);
  setup_slice(volume, common);
  setup_contour(volume, common);
  setup_isosurface(volume, common);
  setup_render(volume, common);
}

}  // namespace tessera::cli
