// tessera render SCENE.json|BUILTIN -o IMG: render a scene file (or a built-in scene by name) with the ray tracer or
// the rasterizer; one frame, a range of frames of an animated scene (files, a GIF or a video), or a tile of a frame
// (docs/farm.md).
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "command.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/farm/frames.hpp"
#include "tessera/farm/manifest.hpp"
#include "tessera/farm/mpi.hpp"
#include "tessera/image/animation.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/scene/raster.hpp"
#include "tessera/scene/trace.hpp"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

enum class Backend { raytrace, raster };

struct RenderArgs {
  std::string scene, output, size, frames, tile, crop;
  std::optional<int> frame, tiles;
  Backend backend = Backend::raytrace;
  RasterShadows shadow_method = RasterShadows::map;
  bool shadow_method_given = false, skip_existing = false, mpi = false;
  std::optional<int> spp, depth;
  uint64_t seed = 0;
};

std::string builtin_list() {
  std::string list;
  for (const auto& name : builtin_scene_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

// Refuses an image over the memory budget. Per pixel: the float image, the depth image and the 8-bit copy (25 bytes
// measured with either backend).
void check_render_memory(Size2 size) {
  MemoryBudget::check(saturating_product({uint64_t(size.width), uint64_t(size.height), 28}),
                      fmt::format("rendering {}x{} pixels", size.width, size.height));
}

// `tessera render --list`: each built-in scene, its frames when it moves, and its description.
void print_builtin_list() {
  for (const auto& name : builtin_scene_names()) {
    const AnimatedScene scene = load_animated_scene(name);
    const SceneAnimation& a = scene.animation();
    std::string frames =
        scene.keyed() || a.last > a.first ? fmt::format("frames {}:{} at {} fps", a.first, a.last, a.fps) : "still";
    std::fputs(fmt::format("{:<16} {}\n", name, frames).c_str(), stdout);
  }
}

// The part of a frame to render: the whole frame, a tile (K/N bands of rows) or a crop window.
struct Part {
  std::optional<TileSpec> tile;
  std::optional<PixelRect> crop;
  // The pixels of a width x height frame the part covers.
  std::optional<PixelRect> rect(int width, int height) const {
    if (tile) return tile_rect(*tile, width, height);
    if (crop && !(crop->x0 < crop->x1 && crop->x1 <= width && crop->y0 < crop->y1 && crop->y1 <= height))
      throw InvalidInput(fmt::format("--crop {},{},{},{}: expected 0 <= x0 < x1 <= {} and 0 <= y0 < y1 <= {}", crop->x0,
                                     crop->y0, crop->x1, crop->y1, width, height));
    return crop;
  }
};

PixelRect parse_crop(const std::string& text) {
  const std::vector<double> v = parse_doubles(text, 4, "--crop");
  for (double x : v)
    if (x != std::floor(x) || x < 0 || x > 65536)
      throw InvalidInput(fmt::format("--crop: expected x0,y0,x1,y1 in whole pixels, got '{}'", printable(text)));
  return {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
}

// What a run adds up for --stats.
struct Totals {
  StatRows first_frame;  // the per-frame figures of the first frame rendered (size, samples, objects, ...)
  double seconds = 0, eye_rays = 0, rays = 0, ray_seconds = 0;
  int rendered = 0, skipped = 0;
};

// Renders `part` of one frame of the scene.
// Renders `part` of one frame of the scene; `prepared` is the scene's RayScene when the caller keeps one (the tiles of
// a frame share it), else the ray tracer makes its own.
ImageRGB render_frame(const Scene& scene, const RenderArgs& a, const CommonOptions& common, const Size2& size,
                      const Part& part, PhaseTimer& timer, Totals& totals, const RayScene* prepared = nullptr) {
  RenderSettings settings = render_settings(scene);
  if (size.width > 0) settings.width = size.width, settings.height = size.height;
  check_render_memory({settings.width, settings.height});  // a scene file's own size
  if (a.spp) settings.samples = *a.spp;
  if (a.depth) settings.max_depth = *a.depth;
  settings.seed = a.seed;
  settings.progress = !common.quiet;
  const std::optional<PixelRect> rect = part.rect(settings.width, settings.height);
  // The raster backend shades one sample per pixel, locally: the scene's samples and depth do not apply.
  const int samples = a.backend == Backend::raster ? 1 : settings.samples;
  const int width = rect ? rect->x1 - rect->x0 : settings.width, height = rect ? rect->y1 - rect->y0 : settings.height;
  if (totals.first_frame.empty())
    totals.first_frame = {{"width", stat_value(width)},
                          {"height", stat_value(height)},
                          {"pixels", stat_value(double(width) * height)},
                          {"samples", stat_value(samples)},
                          {"objects", stat_value(double(scene.objects.size()))},
                          {"lights", stat_value(double(scene.lights.size()))}};
  ImageRGB image;
  if (a.backend == Backend::raster) {
    // The rasterizer draws the whole frame (its pixels are then those of an unsplit render) and the part is cut out.
    image = timer.time("compute_s",
                       [&] { return rasterize_scene(scene, settings.width, settings.height, a.shadow_method); });
    totals.seconds = timer.seconds("compute_s");
    if (rect) {
      ImageRGB cut(width, height);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) cut(x, y) = image(x + rect->x0, y + rect->y0);
      image = std::move(cut);
    }
  } else {
    if (rect) settings.window = RenderSettings::Window{rect->x0, rect->y0, rect->x1, rect->y1};
    RenderStats stats;
    image = timer.time("compute_s", [&] {
      return prepared ? render(*prepared, settings, &stats) : render(to_ray_scene(scene), settings, &stats);
    });
    totals.seconds += stats.seconds;
    totals.eye_rays += double(stats.eye_rays);
    totals.rays += double(stats.rays);
    totals.ray_seconds += stats.seconds;
  }
  ++totals.rendered;
  return image;
}

// What decides a rendered picture's pixels, for the manifest: the scene's bytes (a file's or a built-in's) and every
// option that changes pixels. A rerun with --skip-existing renders again what other settings made.
std::string render_fingerprint(const RenderArgs& a, const CommonOptions& common) {
  std::error_code ec;
  // A path that exists is the scene, as load_animated_scene decides (a folder is refused there, and here alike).
  const uint32_t scene = fs::exists(a.scene, ec) ? file_crc32(a.scene) : crc32_of(builtin_scene_text(a.scene));
  return fmt::format("scene {:08x} size {} spp {} depth {} seed {} backend {} shadows {} srgb {}", scene,
                     a.size.empty() ? "scene" : a.size, a.spp ? std::to_string(*a.spp) : "scene",
                     a.depth ? std::to_string(*a.depth) : "scene", a.seed,
                     a.backend == Backend::raster ? "raster" : "raytrace",
                     a.shadow_method == RasterShadows::map ? "map" : "volumes", common.srgb ? 1 : 0);
}

// Where frames (or a tile of each) go and how: image files, recorded in the folder's manifest (frames.json) for a
// farm so that a resubmitted task can skip what is already there and whole, or a movie.
struct Output {
  fs::path pattern;
  bool farm = false;
  std::optional<TileSpec> tile;
  std::string settings;  // what makes the pictures (render_fingerprint), recorded with each file

  fs::path folder() const { return pattern.parent_path().empty() ? fs::path(".") : pattern.parent_path(); }
  fs::path file(int frame) const {
    const fs::path frame_file = numbered_frame_path(pattern, frame);
    return tile ? tile_file(frame_file, *tile) : frame_file;
  }
  // Written whole by an earlier run with these settings: it matches its manifest entry (bytes, CRC-32 and settings)
  // or, without one, exists (writes are atomic; such a file's settings are unknown).
  bool done(const Manifest& manifest, int frame) const {
    const std::string name = file(frame).filename().string();
    std::error_code ec;
    if (const ManifestEntry* entry = manifest.find(name))
      return (entry->settings.empty() || entry->settings == settings) && manifest.verified(folder(), name);
    return fs::is_regular_file(file(frame), ec);
  }
  // Writes a rendered frame (or tile) that took `seconds`: into the movie when there is one, else to its file.
  void write(const ImageRGB& image, int frame, double seconds, const CommonOptions& common,
             std::optional<AnimationWriter>& movie, PhaseTimer& timer) const {
    if (movie) return timer.time("write_s", [&] { movie->add(image); });
    const fs::path path = file(frame);
    timer.time("write_s", [&] {
      write_image(path, image, common.write_options());
      if (farm)
        Manifest::record(folder(), path.filename().string(),
                         ManifestEntry{.frame = frame,
                                       .tile = tile ? tile->index : -1,
                                       .tiles = tile ? tile->count : 1,
                                       .crc32 = file_crc32(path),
                                       .bytes = uint64_t(fs::file_size(path)),
                                       .seconds = seconds,
                                       .host = host_name(),
                                       .settings = settings});
    });
    if (farm && !common.quiet && common.progress != "none")
      std::fputs(fmt::format("tessera render: frame {} -> {} ({:.3f} s)\n", frame, path.string(), seconds).c_str(),
                 stderr);
  }
};

// `mpirun -n R tessera render ... --mpi`: every rank renders tiles of the frames, handed out one at a time by rank 0
// (mpi::farm_units), which stitches them and writes each frame as it completes (a movie in frame order). Rank 0
// decides which frames to render (--skip-existing) and tells the others. Only rank 0 writes or prints: true on it.
bool run_render_mpi(const RenderArgs& a, const CommonOptions& common, const AnimatedScene& animated, FrameRange range,
                    Size2 size, const Output& out, const std::function<void()>& open_movie,
                    std::optional<AnimationWriter>& writer, PhaseTimer& timer, Totals& totals) {
  const mpi::Session session;
  const bool root = session.rank() == 0;
  CommonOptions quiet = common;
  quiet.quiet = !root || common.quiet;
  std::vector<int> frames;
  if (root) {
    const Manifest manifest = out.farm && a.skip_existing ? Manifest::read(out.folder()) : Manifest();
    for (int f = range.first; f <= range.last; ++f) {
      if (out.farm && a.skip_existing && out.done(manifest, f))
        ++totals.skipped;
      else
        frames.push_back(f);
    }
    open_movie();
  }
  mpi::broadcast(session, frames);
  if (frames.empty()) return root;
  // The frame's size, and the tiles each frame is cut into: as asked, else four per frame for an animation (the last
  // unit, which one rank finishes while the others wait, is then a quarter frame) or sixteen per rank for a single
  // frame (slow tiles balance; a tile costs about 0.1 ms more, bench/farm/scaling.sh); the rasterizer draws whole
  // frames.
  const Scene first = animated.at(frames.front());
  RenderSettings probe = render_settings(first);
  if (size.width > 0) probe.width = size.width, probe.height = size.height;
  const int width = probe.width, height = probe.height;
  int tiles = a.tiles.value_or(std::min(height, frames.size() > 1 ? 4 : 16 * session.size()));
  if (a.backend == Backend::raster) tiles = 1;
  if (tiles < 1 || tiles > height)
    throw InvalidInput(fmt::format("--tiles: expected 1 to {} (the frame's rows), got {}", height, tiles));
  // The frame this rank rendered last, kept for its next tile of that frame: the scene and, for the ray tracer, its
  // RayScene (the BVH).
  struct Cached {
    int frame;
    Scene scene;
    std::optional<RayScene> prepared;
  };
  std::optional<Cached> cached;
  const auto render_unit = [&](int unit) {
    const int frame = frames[size_t(unit / tiles)];
    if (!cached || cached->frame != frame) {
      cached.emplace(Cached{frame, animated.at(frame), std::nullopt});
      if (a.backend == Backend::raytrace) cached->prepared.emplace(to_ray_scene(cached->scene));
    }
    Part part;
    if (tiles > 1) part.tile = TileSpec{unit % tiles, tiles};
    PhaseTimer unit_timer;
    Totals unit_totals;
    CommonOptions silent = common;
    silent.quiet = true;
    return render_frame(cached->scene, a, silent, size, part, unit_timer, unit_totals,
                        cached->prepared ? &*cached->prepared : nullptr);
  };
  struct Pending {
    ImageRGB image;
    int tiles_left = 0;
    double seconds = 0;
  };
  std::map<int, Pending> pending;    // frames with tiles still to come
  std::map<int, ImageRGB> finished;  // whole frames waiting for an earlier one (a movie is written in order)
  size_t next_in_order = 0;
  const auto deliver = [&](mpi::UnitResult&& r) {
    const int frame = frames[size_t(r.unit / tiles)];
    Pending& p = pending[frame];
    if (p.tiles_left == 0) p = Pending{ImageRGB(width, height), tiles, 0.0};
    const PixelRect rect = tile_rect({r.unit % tiles, tiles}, width, height);
    if (r.image.width() != width || r.image.height() != rect.y1 - rect.y0)
      throw InvalidInput(
          fmt::format("frame {}: the scene's size changes between frames, which --mpi does not split", frame));
    for (int y = rect.y0; y < rect.y1; ++y) std::copy_n(r.image.row(y - rect.y0), width, p.image.row(y));
    p.seconds += r.seconds;
    if (--p.tiles_left > 0) return;
    ++totals.rendered;
    if (!writer) {
      out.write(p.image, frame, p.seconds, quiet, writer, timer);
    } else {
      finished.emplace(frame, std::move(p.image));
      for (auto it = finished.begin(); it != finished.end() && it->first == frames[next_in_order];
           it = finished.erase(it), ++next_in_order)
        out.write(it->second, it->first, 0, quiet, writer, timer);
    }
    pending.erase(frame);
  };
  if (root)
    totals.first_frame = {{"width", stat_value(width)},
                          {"height", stat_value(height)},
                          {"pixels", stat_value(double(width) * height)},
                          {"samples", stat_value(a.backend == Backend::raster ? 1 : a.spp.value_or(probe.samples))},
                          {"objects", stat_value(double(first.objects.size()))},
                          {"lights", stat_value(double(first.lights.size()))},
                          {"ranks", stat_value(session.size())},
                          {"tiles", stat_value(tiles)}};
  const auto start = std::chrono::steady_clock::now();
  timer.time("compute_s", [&] { mpi::farm_units(session, int(frames.size()) * tiles, render_unit, deliver); });
  totals.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (writer) timer.time("write_s", [&] { writer->finish(); });
  return root;
}

void run_render(const RenderArgs& a, const CommonOptions& common) {
  // Every option and the output are checked before the scene is built or anything is written.
  Size2 size{0, 0};
  if (!a.size.empty()) size = parse_size(a.size, "--size");
  check_render_memory(size);
  if (a.spp && (*a.spp < 1 || *a.spp > SceneImage::kMaxSamples))
    throw InvalidInput(
        fmt::format("--spp: expected a number of samples in [1, {}], got {}", SceneImage::kMaxSamples, *a.spp));
  if (a.depth && (*a.depth < 1 || *a.depth > RenderSettings::kMaxDepth))
    throw InvalidInput(
        fmt::format("--depth: expected a recursion depth in [1, {}], got {}", RenderSettings::kMaxDepth, *a.depth));
  if (a.shadow_method_given && a.backend != Backend::raster)
    throw InvalidInput("--shadow-method: only the raster backend has shadow methods; add --backend raster");
  if (a.frame && !a.frames.empty()) throw InvalidInput("--frame and --frames: give one of them");
  if (!a.tile.empty() && !a.crop.empty()) throw InvalidInput("--tile and --crop: give one of them");
  std::optional<FrameRange> frames;
  if (!a.frames.empty()) frames = parse_frame_range(a.frames, "--frames");
  if (a.frame) frames = parse_frame_range(std::to_string(*a.frame), "--frame");
  Part part;
  if (!a.tile.empty()) part.tile = parse_tile(a.tile, "--tile");
  if (!a.crop.empty()) part.crop = parse_crop(a.crop);

  const fs::path output(a.output);
  const std::string lower = [&] {
    std::string ext = output.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
  }();
  static const std::set<std::string> kImages = {".png", ".ppm", ".pfm", ".hdr", ".jpg", ".jpeg", ".bmp", ".tga"};
  static const std::set<std::string> kMovies = {".gif", ".mp4", ".mov", ".mkv", ".webm"};
  const bool movie = kMovies.count(lower) > 0;
  if (!movie && !kImages.count(lower))
    throw InvalidInput(
        fmt::format("-o {}: expected an image file (.png, .hdr, .pfm, .ppm, .jpg, .bmp, .tga), or with "
                    "--frames a numbered one (frame_%04d.png) or a movie (.gif, .mp4, .mov, .mkv, .webm)",
                    a.output));
  if (movie && (part.tile || part.crop)) throw InvalidInput("--tile/--crop: a movie is made of whole frames");
  if (movie && !frames) throw InvalidInput(fmt::format("-o {}: a movie needs --frames A:B", a.output));
  if (movie && numbered_frame_path(output, 0) != output)
    throw InvalidInput(fmt::format("-o {}: a movie is one file; its name has no frame number", a.output));
  if (part.tile) check_lossless_image_path(output);
  const bool numbered = numbered_frame_path(output, 0) != output;
  if (frames && frames->count() > 1 && !movie && !numbered)
    throw InvalidInput(
        fmt::format("-o {}: several frames need a numbered file name (frame_%04d.png or "
                    "frame-####.png) or a movie",
                    a.output));

  // A crop is not part of a farm's frames: it is neither recorded in frames.json nor skipped.
  const bool farm_output = (frames && !movie && !part.crop) || part.tile;
  const Output out{output, farm_output, part.tile, render_fingerprint(a, common)};
  PhaseTimer timer;
  const AnimatedScene animated = timer.time("read_s", [&] { return load_animated_scene(a.scene); });
  const FrameRange range = frames.value_or(FrameRange{animated.animation().first, animated.animation().first});
  if (range.first < animated.animation().first || range.last > animated.animation().last)
    throw InvalidInput(fmt::format("--frames {}:{}: the scene '{}' has frames {}:{}", range.first, range.last, a.scene,
                                   animated.animation().first, animated.animation().last));
  if (a.tiles && !a.mpi)
    throw InvalidInput("--tiles: splits frames among MPI ranks; with --mpi only (else --tile K/N)");
  if (a.mpi && (part.tile || part.crop))
    throw InvalidInput("--mpi: ranks share whole frames; --tile/--crop do not apply");
  if (farm_output) fs::create_directories(out.folder());
  std::optional<AnimationWriter> writer;
  const auto open_movie = [&] {
    if (movie) writer.emplace(output, AnimationOptions{.fps = animated.animation().fps, .srgb = common.srgb});
  };
  Totals totals;
  if (a.mpi) {
    if (!run_render_mpi(a, common, animated, range, size, out, open_movie, writer, timer, totals)) return;
  } else {
    open_movie();
    const Manifest manifest = farm_output && a.skip_existing ? Manifest::read(out.folder()) : Manifest();
    for (int f = range.first; f <= range.last; ++f) {
      if (farm_output && a.skip_existing && out.done(manifest, f)) {
        ++totals.skipped;
        continue;
      }
      const Scene scene = timer.time("read_s", [&] { return animated.at(f); });
      const double before = timer.seconds("compute_s");
      const ImageRGB image = render_frame(scene, a, common, size, part, timer, totals);
      out.write(image, f, timer.seconds("compute_s") - before, common, writer, timer);
    }
    if (writer) timer.time("write_s", [&] { writer->finish(); });
  }
  if (!common.stats) return;
  StatRows figures = totals.first_frame;
  if (a.backend == Backend::raytrace && totals.rendered > 0 && !a.mpi)
    figures.insert(figures.end(), {{"eye_rays", stat_value(totals.eye_rays)},
                                   {"rays", stat_value(totals.rays)},
                                   {"rays_per_s", stat_value(totals.rays / std::max(totals.ray_seconds, 1e-9))}});
  if (frames)
    figures.insert(figures.end(), {{"frames", stat_value(totals.rendered)}, {"skipped", stat_value(totals.skipped)}});
  figures.emplace_back("seconds", stat_value(totals.seconds));
  const StatRows phases = timer.rows();
  figures.insert(figures.end(), phases.begin(), phases.end());
  print_stats(figures);
}

}  // namespace

void setup_render(CLI::App& cmd, CommonOptions& common) {
  auto a = std::make_shared<RenderArgs>();
  cmd.add_option("scene", a->scene, "Scene file (.json, docs/scene-format.md) or a built-in scene: " + builtin_list())
      ->required();
  cmd.add_option("-o,--output", a->output,
                 "Output image (.png, .hdr, .pfm, .ppm, .jpg, .bmp, .tga); with --frames a numbered file name "
                 "(frames/frame_%04d.png or frame-####.png) or a movie (.gif, .mp4, .mov, .mkv, .webm)")
      ->required();
  // Like --help, --list runs while the command line is parsed, before the required arguments are asked for.
  cmd.add_flag_callback(
      "--list",
      [] {
        print_builtin_list();
        throw CLI::Success();
      },
      "List the built-in scenes and the frames of those that move, then exit");
  cmd.add_option("--frames", a->frames, "Render frames A:B of an animated scene (default: its first frame)");
  cmd.add_option("--frame", a->frame, "Render frame N of an animated scene");
  cmd.add_option("--tile", a->tile,
                 "Render tile K of N (bands of rows, K from 0) into <output stem>.tile-K-of-N<ext>; `tessera "
                 "assemble` stitches the tiles (docs/farm.md)");
  cmd.add_option("--crop", a->crop, "Render only the pixels x0,y0,x1,y1 ([x0, x1) x [y0, y1)) of the frame");
  cmd.add_flag("--skip-existing", a->skip_existing,
               "With --frames or --tile: skip frames and tiles already written whole (checked against the folder's "
               "frames.json)");
  cmd.add_flag("--mpi", a->mpi,
               "Render across the ranks of `mpirun -n R tessera render ... --mpi`: tiles of each frame handed out "
               "as ranks become free, written by rank 0 (docs/farm.md)");
  cmd.add_option("--tiles", a->tiles,
                 "With --mpi: tiles per frame (default: 4 for several frames, 16 per rank for one frame)");
  cmd.add_option("--spp", a->spp, "Samples per pixel (default: the scene's)");
  cmd.add_option("--size", a->size, "Image size WxH (default: the scene's)")->check(size_format());
  cmd.add_option("--depth", a->depth, "Recursion depth, 1 = eye rays only (default: the scene's)");
  cmd.add_option("--seed", a->seed, "Seed of the sampling patterns (same seed, same picture)");
  add_choice(
      cmd, "--backend", a->backend, {{"raytrace", Backend::raytrace}, {"raster", Backend::raster}},
      "Renderer: raytrace (everything) or raster (z-buffer, local shading, one bounce of reflection by cube maps, "
      "glass blended without refraction; docs/raytrace.md)");
  CLI::Option* shadows = add_choice(cmd, "--shadow-method", a->shadow_method,
                                    {{"map", RasterShadows::map}, {"volumes", RasterShadows::volumes}},
                                    "Raster shadows of every light: map (a shadow map per light) or volumes (stencil "
                                    "shadow volumes)");
  add_srgb_option(cmd, common);
  cmd.callback([a, shadows, &common] {
    a->shadow_method_given = shadows->count() > 0;
    run_render(*a, common);
  });
}

}  // namespace tessera::cli
