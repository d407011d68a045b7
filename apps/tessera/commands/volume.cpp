// tessera volume info|slice|contour|isosurface|render: volume data from raw/NRRD/MetaImage files or procedural names.
#include <fmt/format.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "camera_options.hpp"
#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/farm/mpi.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/soup.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/marching_squares.hpp"
#include "tessera/volume/volume_io.hpp"
#include "tessera/volume/volume_render.hpp"

namespace tessera::cli {
namespace {

/// The volume argument and the raw layout options every subcommand takes.
struct VolumeInput {
  std::string path, dims, spacing;
  VoxelType dtype = VoxelType::uint8;
  Endian endian = Endian::little;
  long long header_skip = 0;
  std::vector<const CLI::Option*> raw_options;  ///< the raw layout options, to refuse them where they mean nothing

  void add(CLI::App& app) {
    app.add_option("volume", path,
                   "Volume: FILE.nrrd|.nhdr|.mhd, a raw file with --dims, or sphere:N, torus:N, gyroid:N, "
                   "metaballs:N, noise:N[:SEED]")
        ->required();
    raw_options = {
        app.add_option("--dims", dims, "Raw voxels along x,y,z")->check(numbers_format(3)),
        add_choice(app, "--dtype", dtype,
                   {{"uint8", VoxelType::uint8},
                    {"uint16", VoxelType::uint16},
                    {"int16", VoxelType::int16},
                    {"float32", VoxelType::float32}},
                   "Raw voxel type"),
        add_choice(app, "--endian", endian, {{"little", Endian::little}, {"big", Endian::big}}, "Raw byte order"),
        app.add_option("--spacing", spacing, "Raw voxel spacing sx,sy,sz")->check(numbers_format(3)),
        app.add_option("--header-skip", header_skip, "Raw bytes before the first voxel")->check(non_negative())};
  }

  AnyVolume read() const {
    // A header file or a procedural name brings its own layout: raw options given with it would be ignored.
    const std::string ext = CLI::detail::to_lower(std::filesystem::path(path).extension().string());
    if (ext == ".nrrd" || ext == ".nhdr" || ext == ".mhd" ||
        (!std::filesystem::exists(path) && path.find(':') != std::string::npos))
      for (const CLI::Option* o : raw_options)
        if (o->count() > 0)
          throw InvalidInput(
              fmt::format("{}: {} describes raw files only; this volume brings its own layout", path, o->get_name()));
    RawLayout layout;
    if (!dims.empty()) {
      const auto d = parse_doubles(dims, 3, "--dims");
      for (int i = 0; i < 3; ++i) {
        if (d[size_t(i)] < 1 || d[size_t(i)] > double(1 << 30) || d[size_t(i)] != std::floor(d[size_t(i)]))
          throw InvalidInput(fmt::format("--dims: expected three positive integers, got '{}'", dims));
        layout.dims[i] = int(d[size_t(i)]);
      }
    }
    layout.type = dtype;
    layout.endian = endian;
    if (!spacing.empty()) {
      const auto s = parse_doubles(spacing, 3, "--spacing");
      layout.spacing = {s[0], s[1], s[2]};
      if (!(s[0] > 0 && s[1] > 0 && s[2] > 0)) throw InvalidInput("--spacing: values must be positive");
    }
    layout.header_skip = uint64_t(header_skip);
    return read_volume(path, layout);
  }
};

/// The rows every --stats report of a volume command ends with: what `extra` holds, then the timed phases.
void print_volume_stats(StatRows rows, const PhaseTimer& timer) {
  const StatRows phases = timer.rows();
  rows.insert(rows.end(), phases.begin(), phases.end());
  print_stats(rows);
}

/// --stats rows for an image written: width, height.
StatRows image_rows(int width, int height) { return {{"width", stat_value(width)}, {"height", stat_value(height)}}; }

void setup_info(CLI::App& volume, CommonOptions& common) {
  auto* cmd = volume.add_subcommand(
      "info",
      "Dimensions, voxel type, spacing, origin, value range, and Otsu's threshold between background and object");
  auto in = std::make_shared<VolumeInput>();
  in->add(*cmd);
  add_common_options(*cmd, common);
  cmd->callback([in, &common] {
    PhaseTimer timer;
    AnyVolume v = timer.time("read_s", [&] { return in->read(); });
    const auto d = dims_of(v);
    const auto s = spacing_of(v), o = origin_of(v);
    const VoxelType type = voxel_type(v);
    // Moved into its float copy: a float volume is not copied (the read estimate counts 8 bytes a voxel).
    const ValueProfile p = timer.time("compute_s", [&] { return profile_values(to_float(std::move(v))); });
    fmt::print("dims={},{},{}\ntype={}\nspacing={},{},{}\norigin={},{},{}\nmin={}\nmax={}\nthreshold={}\n", d.x, d.y,
               d.z, voxel_type_name(type), s.x, s.y, s.z, o.x, o.y, o.z, stat_value(p.lo), stat_value(p.hi),
               stat_value(p.threshold));
    if (common.stats) print_volume_stats({{"voxels", stat_value(double(d.x) * d.y * d.z)}}, timer);
  });
}

/// Says on stderr that every voxel has the same value, and what that makes of the output.
void warn_constant(double value, const char* consequence) {
  fmt::print(stderr, "tessera: warning: every voxel has the value {}: {}\n", stat_value(value), consequence);
}

/// Grayscale image of a slice, values mapped from [lo, hi] to [0, 1].
ImageRGB gray_image(const DepthImage& s, double lo, double hi) {
  ImageRGB img(s.width(), s.height());
  for (int y = 0; y < s.height(); ++y)
    for (int x = 0; x < s.width(); ++x)
      img(x, y) = Vec3f(float(std::clamp((s(x, y) - lo) / std::max(hi - lo, 1e-12), 0.0, 1.0)));
  return img;
}

struct SliceArgs {
  Axis axis = Axis::z;
  std::optional<int> index;
  std::string output;
  void add(CLI::App& cmd) {
    add_choice(cmd, "--axis", axis, {{"x", Axis::x}, {"y", Axis::y}, {"z", Axis::z}}, "Slice axis");
    cmd.add_option("--slice", index, "Slice index along the axis (default: the middle one)");
    cmd.add_option("-o,--output", output, "Output file")->required();
  }
  /// The slice asked for, or the middle one. Refused over the memory budget first (a flat volume's slice has as many
  /// pixels as it has voxels): per pixel the float slice (4 bytes), the float RGB picture made of it (12), the 8-bit
  /// copy a writer makes (4) and 4 to spare.
  DepthImage take(const Volume<float>& v) const {
    const glm::ivec3 d = v.dims();
    const int w = axis == Axis::x ? d.y : d.x, h = axis == Axis::z ? d.y : d.z;
    MemoryBudget::check(saturating_product({uint64_t(w), uint64_t(h), 24}), fmt::format("a {}x{} slice", w, h));
    return slice(v, axis, index ? *index : d[int(axis)] / 2);
  }
};

void setup_slice(CLI::App& volume, CommonOptions& common) {
  auto* cmd =
      volume.add_subcommand("slice", "A plane of voxels as a grayscale image (min..max mapped to black..white)");
  auto in = std::make_shared<VolumeInput>();
  auto args = std::make_shared<SliceArgs>();
  in->add(*cmd);
  args->add(*cmd);
  add_common_options(*cmd, common);
  add_srgb_option(*cmd, common);
  cmd->callback([in, args, &common] {
    PhaseTimer timer;
    const Volume<float> v = timer.time("read_s", [&] { return to_float(in->read()); });
    const ImageRGB image = timer.time("compute_s", [&] {
      const auto [lo, hi] = value_range(v);
      if (!(hi > lo)) warn_constant(lo, "the slice is black (min..max maps to black..white)");
      return gray_image(args->take(v), lo, hi);
    });
    timer.time("write_s", [&] { write_image(args->output, image, common.write_options()); });
    if (common.stats) print_volume_stats(image_rows(image.width(), image.height()), timer);
  });
}

/// Says on stderr when an iso value lies outside the values it is drawn from (the output is then empty).
void warn_outside(float iso, double lo, double hi, const char* where) {
  if (iso < lo || iso > hi)
    fmt::print(stderr, "tessera: warning: --iso {} is outside the {}'s values [{}, {}]: the output is empty\n", iso,
               where, stat_value(lo), stat_value(hi));
}

/// --iso: given, or Otsu's threshold of the volume (said on stderr unless quiet).
float iso_or_threshold(const std::optional<float>& iso, const Volume<float>& v, bool quiet) {
  if (iso) return *iso;
  const float t = float(profile_values(v).threshold);
  if (!quiet) fmt::print(stderr, "tessera: note: --iso {:.4g} (Otsu's threshold between background and object)\n", t);
  return t;
}

void setup_contour(CLI::App& volume, CommonOptions& common) {
  auto* cmd = volume.add_subcommand("contour", "Marching-squares iso-lines of a slice, as SVG or PNG");
  auto in = std::make_shared<VolumeInput>();
  auto args = std::make_shared<SliceArgs>();
  auto iso = std::make_shared<std::optional<float>>();
  in->add(*cmd);
  args->add(*cmd);
  cmd->add_option("--iso", *iso, "Iso value (default: Otsu's threshold of the volume)");
  add_common_options(*cmd, common);
  add_srgb_option(*cmd, common);
  cmd->callback([in, args, iso, &common] {
    const std::string ext = std::filesystem::path(args->output).extension().string();
    if (ext == ".svg" && common.srgb)
      throw InvalidInput(fmt::format("{}: --srgb encodes 8-bit images; an SVG's colors are not encoded", args->output));
    PhaseTimer timer;
    const Volume<float> v = timer.time("read_s", [&] { return to_float(in->read()); });
    std::vector<Polyline> lines;
    const DepthImage s = timer.time("compute_s", [&] {
      const float value = iso_or_threshold(*iso, v, common.quiet);
      DepthImage plane = args->take(v);
      const auto [lo, hi] = std::minmax_element(plane.pixels().begin(), plane.pixels().end());
      warn_outside(value, *lo, *hi, "slice");
      lines = marching_squares(plane, value);
      return plane;
    });
    const auto stats = [&](int width, int height) {
      if (!common.stats) return;
      size_t points = 0, segments = 0;
      for (const auto& l : lines) {
        points += l.points.size();
        segments += l.points.size() - (l.closed || l.points.empty() ? 0 : 1);
      }
      StatRows rows{{"vertices", stat_value(double(points))}, {"edges", stat_value(double(segments))}};
      if (width > 0) {
        const StatRows size = image_rows(width, height);
        rows.insert(rows.end(), size.begin(), size.end());
      }
      print_volume_stats(rows, timer);
    };
    if (ext == ".svg") {
      timer.time("write_s", [&] { write_contours_svg(args->output, lines, s.width(), s.height()); });
      stats(0, 0);
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
    timer.time("write_s", [&] { write_image(args->output, canvas.image(), common.write_options()); });
    stats(canvas.width(), canvas.height());
  });
}

// `mpirun -n R tessera volume isosurface ... --mpi`: rank r extracts the cell layers of slab r (with the slices beyond
// them that its normals read), in the whole volume's coordinates, and rank 0 joins the pieces, welding the vertices
// that neighbouring slabs both put on their shared plane (bit-identical: the same voxels and arithmetic). The mesh on
// rank 0, empty elsewhere.
PolyMesh isosurface_bricks(const mpi::Session& session, const Volume<float>& v, const MarchingCubesOptions& options) {
  const int ranks = session.size(), rank = session.rank();
  const glm::ivec3 dims = v.dims();
  const int cells = dims.z - 1;
  if (cells < ranks)
    throw InvalidInput(fmt::format("--mpi: {} ranks cannot share the {} cell layers of z", ranks, std::max(cells, 0)));
  const auto bound = [&](int r) { return int(int64_t(r) * cells / ranks); };
  const int z0 = std::max(0, bound(rank) - 1), z1 = std::min(dims.z - 1, bound(rank + 1) + 1);
  VoxelGrid brick{&v(0, 0, z0), glm::ivec3(dims.x, dims.y, z1 - z0 + 1), v.spacing(), v.origin(), z0};
  MarchingCubesOptions o = options;
  o.first_layer = bound(rank) - z0;
  o.end_layer = bound(rank + 1) - z0;
  const PolyMesh piece = marching_cubes(brick, o);
  // On the wire: vertex and face counts, positions, normals (as many as positions, or none), then the faces'
  // vertex indices (marching cubes gives triangles only).
  std::string bytes;
  const auto put = [&](const void* data, size_t size) { bytes.append(static_cast<const char*>(data), size); };
  const uint64_t counts[3] = {piece.positions.size(), piece.normals.size(), piece.face_vertices.size()};
  put(counts, sizeof counts);
  put(piece.positions.data(), piece.positions.size() * sizeof(Vec3));
  put(piece.normals.data(), piece.normals.size() * sizeof(Vec3));
  put(piece.face_vertices.data(), piece.face_vertices.size() * sizeof(uint32_t));
  const std::vector<std::string> parts = mpi::gather(session, bytes);
  if (rank != 0) return {};
  std::vector<Vec3> positions, normals;
  std::vector<uint32_t> corners;
  for (const std::string& part : parts) {
    uint64_t n[3];
    std::memcpy(n, part.data(), sizeof n);
    const char* at = part.data() + sizeof n;
    const auto base = uint32_t(positions.size());
    const auto take = [&](auto& out, uint64_t count) {
      const size_t first = out.size();
      out.resize(first + count);
      std::memcpy(out.data() + first, at, count * sizeof(out[0]));
      at += count * sizeof(out[0]);
    };
    take(positions, n[0]);
    take(normals, n[1]);
    const size_t first = corners.size();
    take(corners, n[2]);
    for (size_t i = first; i < corners.size(); ++i) corners[i] += base;
  }
  const WeldedPoints welded = weld_points(positions);
  PolyMesh mesh;
  mesh.positions = welded.points;
  if (!normals.empty()) {
    mesh.normals.resize(mesh.positions.size());
    for (size_t i = 0; i < normals.size(); ++i) mesh.normals[welded.remap[i]] = normals[i];
  }
  mesh.face_vertices.reserve(corners.size());
  for (const uint32_t c : corners) mesh.face_vertices.push_back(welded.remap[c]);
  mesh.face_offsets.resize(corners.size() / 3 + 1);
  for (size_t f = 0; f < mesh.face_offsets.size(); ++f) mesh.face_offsets[f] = uint32_t(3 * f);
  return mesh;
}

void setup_isosurface(CLI::App& volume, CommonOptions& common) {
  auto* cmd = volume.add_subcommand("isosurface", "Marching-cubes iso-surface as a mesh file");
  auto in = std::make_shared<VolumeInput>();
  auto options = std::make_shared<MarchingCubesOptions>();
  auto output = std::make_shared<std::string>();
  in->add(*cmd);
  auto iso = std::make_shared<std::optional<float>>();
  cmd->add_option("--iso", *iso, "Iso value (inside is value >= iso; default: Otsu's threshold of the volume)");
  cmd->add_option("-o,--output", *output, "Output mesh (.obj, .ply, .off, .stl)")->required();
  cmd->add_flag("--topological", options->topological, "Resolve ambiguous faces with the asymptotic decider");
  auto mpi = std::make_shared<bool>(false);
  cmd->add_flag("--mpi", *mpi,
                "Extract across the ranks of `mpirun -n R tessera volume isosurface ... --mpi`: each takes a slab of "
                "z, rank 0 joins and welds the pieces (docs/farm.md)");
  add_common_options(*cmd, common);
  cmd->callback([in, options, output, iso, mpi, &common] {
    PhaseTimer timer;
    std::optional<mpi::Session> session;
    if (*mpi) session.emplace();
    const bool root = !session || session->rank() == 0;
    const Volume<float> v = timer.time("read_s", [&] { return to_float(in->read()); });
    MarchingCubesOptions o = *options;
    o.iso = iso_or_threshold(*iso, v, common.quiet || !root);
    const auto [lo, hi] = value_range(v);
    if (root) warn_outside(o.iso, lo, hi, "volume");
    const PolyMesh mesh =
        timer.time("compute_s", [&] { return session ? isosurface_bricks(*session, v, o) : marching_cubes(v, o); });
    if (!root) return;
    timer.time("write_s", [&] { write_mesh(*output, mesh); });
    if (common.stats) {
      const std::string triangles = stat_value(double(mesh.face_count())),
                        vertices = stat_value(double(mesh.vertex_count()));
      // tris, verts and seconds (the extraction's time, = compute_s) are the deprecated spellings scripts rely on.
      print_volume_stats({{"triangles", triangles},
                          {"vertices", vertices},
                          {"area", stat_value(surface_area(mesh))},
                          {"volume", stat_value(signed_volume(mesh))},
                          {"tris", triangles},
                          {"verts", vertices},
                          {"seconds", stat_value(timer.seconds("compute_s"))}},
                         timer);
    }
  });
}

/// Says on stderr why a rendered picture shows nothing but the background, when it does.
void warn_if_empty(const ImageRGB& image, const VolumeRenderOptions& o, std::pair<double, double> range) {
  const auto [lo, hi] = range;
  if (o.mip && !(hi > lo)) {
    warn_constant(lo, "the projection is black");
    return;
  }
  if (!o.mip) {
    if (o.transfer.max_opacity(float(lo), float(hi)) == 0) {
      fmt::print(stderr,
                 "tessera: warning: the transfer function is transparent over the volume's values [{}, {}]: the "
                 "picture is empty\n",
                 stat_value(lo), stat_value(hi));
      return;
    }
  }
  for (const auto& p : image.pixels())
    if (p != o.background) return;
  fmt::print(stderr,
             "tessera: warning: the picture shows only the background: no ray meets a voxel that the transfer function "
             "makes visible (is the volume in view? are the transfer function's values those of the volume?)\n");
}

// `mpirun -n R tessera volume render ... --mpi`: rank r keeps slab r of the volume's cells along z (with the slices
// its samples and gradients reach), renders what that slab adds to each pixel, and the layers are composited
// sort-last, nearest the eye first, by binary swap (mpi::composite_layers). The picture on rank 0, empty elsewhere.
// --stats: composite_s is the compositing's share of compute_s.
ImageRGB render_bricks(const mpi::Session& session, Volume<float> whole, const VolumeRenderOptions& options,
                       PhaseTimer& timer) {
  const int ranks = session.size(), rank = session.rank();
  const glm::ivec3 dims = whole.dims();
  const int cells = dims.z - 1;
  if (cells < ranks)
    throw InvalidInput(
        fmt::format("--mpi: {} ranks cannot share the {} cells of z between {} slices", ranks, cells, dims.z));
  const auto bound = [&](int r) { return int(int64_t(r) * cells / ranks); };
  VolumeRenderOptions o = options;
  o.brick = VolumeRenderOptions::Brick{dims, 0, bound(rank), bound(rank + 1), rank == 0, rank == ranks - 1};
  const int z0 = std::max(0, o.brick->z_begin - 1), z1 = std::min(dims.z - 1, o.brick->z_end + 1);
  o.brick->offset = z0;
  const auto [lo, hi] = value_range(whole);
  const Vec3 origin = whole.origin(), spacing = whole.spacing();
  Volume<float> brick(glm::ivec3(dims.x, dims.y, z1 - z0 + 1), 0.0f, spacing, whole.to_world(Vec3(0, 0, z0)));
  std::copy_n(&whole(0, 0, z0), brick.voxel_count(), &brick(0, 0, 0));
  whole = Volume<float>();  // only the brick stays
  const ImageRGBA layer = VolumeRenderer(brick, lo, hi).render_layer(o);
  // Visibility order: the slab the eye is in (or nearest to) first, then those beyond it on either side; a ray
  // crosses only the slabs on one side, so the order holds along every ray.
  std::vector<int> order;
  const Camera& camera = o.camera;
  const double eye_z = camera.orthographic ? ((camera.center - camera.eye).z >= 0 ? -1.0 : double(cells))
                                           : (camera.eye.z - origin.z) / spacing.z;
  int nearest = 0;
  while (nearest + 1 < ranks && eye_z >= bound(nearest + 1)) ++nearest;
  for (int r = nearest; r < ranks; ++r) order.push_back(r);
  for (int r = nearest - 1; r >= 0; --r) order.push_back(r);
  const ImageRGBA composite = timer.time("composite_s", [&] { return mpi::composite_layers(session, layer, order); });
  if (rank != 0) return {};
  ImageRGB image(composite.width(), composite.height());
  for (size_t i = 0; i < image.pixels().size(); ++i) {
    const Vec4f& c = composite.pixels()[i];
    image.pixels()[i] = Vec3f(c) + (1 - c.w) * options.background;
  }
  return image;
}

void setup_render(CLI::App& volume, CommonOptions& common) {
  auto* cmd = volume.add_subcommand("render", "Direct volume rendering (ray casting) or maximum-intensity projection");
  auto in = std::make_shared<VolumeInput>();
  struct Args {
    std::string output, tf, preset;
    CameraOptions camera;
    bool mip = false, mpi = false;
    float step = 0, termination = 0.99f;
  };
  auto a = std::make_shared<Args>();
  in->add(*cmd);
  cmd->add_option("-o,--output", a->output, "Output image")->required();
  a->camera.fovy = 30;            // a volume's box fills a narrower view better
  a->camera.clip_planes = false;  // rays run through the whole box: --near/--far would change nothing
  a->camera.add(*cmd, "256x256");
  auto* tf = cmd->add_option("--tf", a->tf, "Transfer function file (.json or .csv)");
  auto* preset = cmd->add_option("--preset", a->preset,
                                 "Transfer-function preset, fitted to the volume's values (Otsu's threshold and the "
                                 "top of the object's values)")
                     ->check(CLI::IsMember(TransferFunction::preset_names()));
  auto* mip = cmd->add_flag("--mip", a->mip, "Maximum-intensity projection (no transfer function)");
  tf->excludes(preset);
  mip->excludes(tf)->excludes(preset);
  cmd->add_option("--step", a->step, "Sample distance in world units (default: half the smallest spacing)")
      ->check(non_negative());
  cmd->add_option("--termination", a->termination,
                  "Early ray termination: a ray stops once its opacity reaches this (1: never; with --mpi each "
                  "brick applies it to its own opacity)")
      ->check(CLI::Range(0.5f, 1.0f));
  cmd->add_flag("--mpi", a->mpi,
                "Render across the ranks of `mpirun -n R tessera volume render ... --mpi`: each renders a slab of z, "
                "composited sort-last by binary swap (docs/farm.md)");
  add_common_options(*cmd, common);
  add_srgb_option(*cmd, common);
  cmd->callback([in, a, &common] {
    // The picture's size is refused before the volume is read (an absurd --size answers at once). Per pixel: the
    // float RGBA picture (16 bytes), the 8-bit copy a writer makes (4) and a float to spare.
    const auto size = a->camera.image_size();
    MemoryBudget::check(saturating_product({uint64_t(size.width), uint64_t(size.height), 24}),
                        fmt::format("rendering {}x{} pixels", size.width, size.height));
    PhaseTimer timer;
    std::optional<mpi::Session> session;
    if (a->mpi) {
      if (a->mip) throw InvalidInput("--mpi: maximum-intensity projection is not split into bricks");
      session.emplace();
    }
    const bool root = !session || session->rank() == 0;
    CommonOptions shown = common;
    shown.quiet = common.quiet || !root;
    std::optional<Volume<float>> whole = timer.time("read_s", [&] { return to_float(in->read()); });
    const Volume<float>& v = *whole;
    VolumeRenderOptions o;
    o.width = size.width;
    o.height = size.height;
    o.step = a->step;
    o.mip = a->mip;
    o.termination = a->termination;
    // Framed as every 3D command frames its scene (CameraOptions: a three-quarter view of the bounding sphere).
    const Vec3 lo = v.origin(), hi = v.to_world(Vec3(v.dims() - 1));
    o.camera = a->camera.camera(lo, hi);
    if (!a->tf.empty()) {
      o.transfer = TransferFunction::load(a->tf);
    } else if (!a->mip) {
      const ValueProfile p = timer.time("compute_s", [&] { return profile_values(v); });
      o.transfer = a->preset.empty() ? TransferFunction::automatic(p) : TransferFunction::preset(a->preset, p);
      if (!shown.quiet)
        fmt::print(stderr,
                   "tessera: note: {} over values {:.4g}..{:.4g} (Otsu's threshold {:.4g}, top of the object {:.4g})\n",
                   a->preset.empty() ? std::string("default transfer function") : "preset " + a->preset,
                   o.transfer.points().front().value, o.transfer.points().back().value, p.threshold, p.top);
    }
    const std::pair<double, double> range = value_range(v);
    ImageRGB image;
    if (session) {
      image = timer.time("compute_s", [&] { return render_bricks(*session, std::move(*whole), o, timer); });
      whole.reset();
      if (!root) return;
    } else {
      image = timer.time("compute_s", [&] {
        Progress progress("render", int64_t(o.width) * o.height);
        o.progress = [&](int64_t pixels) { progress.advance(pixels); };
        ImageRGB picture = render_volume(v, o);
        progress.done();
        o.progress = nullptr;
        return picture;
      });
    }
    warn_if_empty(image, o, range);
    timer.time("write_s", [&] { write_image(a->output, image, common.write_options()); });
    if (common.stats) {
      // pixels: those the volume covers (docs/cli.md), i.e. not left at the background.
      StatRows rows = image_rows(image.width(), image.height());
      const auto covered = std::count_if(image.pixels().begin(), image.pixels().end(),
                                         [&](const Vec3f& p) { return p != o.background; });
      rows.emplace_back("pixels", stat_value(double(covered)));
      print_volume_stats(rows, timer);
    }
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
