// The volume renderer: the ray caster (MIP from the float volume, compositing from the packed one, 8 rays at a time
// with AVX2 where the CPU has it), render_volume and VolumeRenderer. Transfer functions: transfer_function.cpp.
#include "tessera/volume/volume_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "tessera/core/cpu.hpp"
#include "tessera/image/image_io.hpp"
#include "volume_render_internal.hpp"

namespace tessera {

using namespace volume_render_detail;

namespace {

/// The sample distance of `options` on `volume` (options.step, or half the smallest spacing when 0). Throws
/// InvalidInput for a negative or non-finite step, or one giving more than kMaxSamplesPerRay samples across the box.
float sample_step(const Volume<float>& volume, const VolumeRenderOptions& options) {
  if (!(options.step >= 0) || !std::isfinite(options.step))
    throw InvalidInput(
        fmt::format("step {} must be a finite distance >= 0 (0: half the smallest spacing)", options.step));
  const Vec3 sp = volume.spacing();
  const double step = options.step > 0 ? double(options.step) : 0.5 * std::min({sp.x, sp.y, sp.z});
  const double diagonal = glm::length(volume.to_world(Vec3(volume.dims() - 1)) - volume.origin());
  const double samples = std::ceil(diagonal / step);
  if (!(samples <= double(VolumeRenderOptions::kMaxSamplesPerRay)))
    throw InvalidInput(
        fmt::format("step {} gives {:.3g} samples per ray across the volume's box (diagonal {:.6g}); at "
                    "most {} are allowed: use a step of at least {:.3g}",
                    float(step), samples, diagonal, VolumeRenderOptions::kMaxSamplesPerRay,
                    diagonal / double(VolumeRenderOptions::kMaxSamplesPerRay)));
  return float(step);
}

/// The samples of a ray that fall in `brick`, [begin, end): sample k's z (in the whole volume's voxels) is the one
/// march() computes; it is monotonic in k, so the brick's samples are consecutive and found by bisection.
std::pair<int, int> brick_samples(const RaySamples& r, const VolumeRenderOptions::Brick& brick) {
  const auto z = [&](int k) {
    return k == r.n - 1 && r.short_last() ? r.last_point.z : r.first.z + float(k) * r.delta.z;
  };
  const bool rising = r.n < 2 || z(r.n - 1) >= z(0);
  // The first sample at or past `plane` in the ray's direction (n if none).
  const auto crossing = [&](float plane) {
    int lo = 0, hi = r.n;
    while (lo < hi) {
      const int mid = lo + (hi - lo) / 2;
      if (rising ? z(mid) >= plane : z(mid) < plane)
        hi = mid;
      else
        lo = mid + 1;
    }
    return lo;
  };
  const int below_begin = brick.first ? (rising ? 0 : r.n) : crossing(float(brick.z_begin));
  const int below_end = brick.last ? (rising ? r.n : 0) : crossing(float(brick.z_end));
  return rising ? std::pair{below_begin, below_end} : std::pair{below_end, below_begin};
}

/// The ray caster: MIP from the float volume, compositing from the prepared one (`packed`, unused for MIP). The
/// result is the layer (premultiplied color, opacity) when `layer`, else the image over the background.
ImageRGBA cast_rays(const Volume<float>& volume, const VolumeRenderOptions& options, double vlo, double vhi,
                    const PackedVolume* packed_volume, bool layer) {
  Camera camera = options.camera;
  camera.aspect = double(options.width) / double(options.height);
  const EyeRays rays(camera, options.width, options.height);
  const Vec3 sp = volume.spacing();
  const float step = sample_step(volume, options);
  // A brick samples where the whole volume does: its box and voxel coordinates are the whole volume's.
  const auto& brick = options.brick;
  if (brick && options.mip) throw InvalidInput("maximum-intensity projection is not rendered in bricks");
  const Vec3 whole_origin = brick ? volume.origin() - Vec3(0, 0, brick->offset * sp.z) : volume.origin();
  const glm::ivec3 whole_dims = brick ? brick->whole_dims : volume.dims();
  AABB box;
  box.expand(Vec3f(whole_origin));
  box.expand(Vec3f(whole_origin + sp * Vec3(whole_dims - 1)));
  const Vec3f inv_spacing = Vec3f(1.0 / sp);
  const Vec3f origin = Vec3f(whole_origin);
  ImageRGBA image(options.width, options.height, layer ? Vec4f(0.0f) : Vec4f(options.background, 1.0f));
  const auto report = [&](const Tile& tile) {
    if (options.progress) options.progress(int64_t(tile.x1 - tile.x0) * (tile.y1 - tile.y0));
  };
  if (options.mip) {
    parallel_tiles(options.width, options.height, 16, [&](const Tile& tile) {
      for (int j = tile.y0; j < tile.y1; ++j)
        for (int i = tile.x0; i < tile.x1; ++i) {
          const Ray ray = rays.ray(i, j);
          float t0 = 0, t1 = 0;
          if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) continue;
          float best = -INFINITY;
          // Sample k at t0 + (k + 1/2) step: an integer count always ends, where t += step stalls once step is
          // below half an ulp of t.
          const int n = int(std::ceil((t1 - t0) / step));
          for (int k = 0; k < n; ++k) {
            const float t = t0 + (float(k) + 0.5f) * step;
            if (t >= t1) break;
            best = std::max(best, volume.sample((ray.at(t) - origin) * inv_spacing));
          }
          // A range of any width, however tiny, spans black to white (the values are floats: vhi - vlo > 0 is
          // at least their smallest difference, and the quotient is in [0, 1]).
          if (best > -INFINITY) image(i, j) = Vec4f(Vec3f(vhi > vlo ? float((best - vlo) / (vhi - vlo)) : 0.0f), 1.0f);
        }
      report(tile);
    });
    return image;
  }
  const PackedVolume& packed = *packed_volume;
  const TransferTable table(options.transfer, vlo, vhi, step);
  // Without skipping one block covers the volume: it is "empty" only when every sample would be clear anyway.
  const BlockGrid blocks(packed, options.skip_empty ? std::max(1, options.block) : 1 << 20, table);
  const SpecularPower power(options.shininess);
  // A gradient shorter than 1e-6 world units, or than 1e-6 of the value range per smallest spacing where that is
  // shorter (a tiny value range, whose gradient_scale is huge), is left unshaded: a tiny range shades as the unit
  // range does, and the threshold stays finite.
  const float min_gradient = float(1e-6 * std::min(packed.gradient_scale, 32767.0));
  const Caster cast{packed, table, blocks, power, options, step, min_gradient * min_gradient};
  const auto setup = [&](int i, int j) {
    RaySamples r;
    const Ray ray = rays.ray(i, j);
    float t0 = 0, t1 = 0;
    if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) return r;
    // Sample k is at the middle of [t0 + k step, min(t1, t0 + (k + 1) step)].
    r.n = int(std::ceil((t1 - t0) / step));
    const float last_length = t1 - (t0 + float(r.n - 1) * step);
    // In [0, 1]: where t0 + (n - 1) step rounds to t1 (or past it) the last segment is empty, and an opaque entry's
    // correction would be 0 * log(0), NaN (a fuzzer finding: a box 0.25 thick, 4 default steps, seen along x).
    r.last_fraction = std::clamp(last_length / step, 0.0f, 1.0f);
    r.first = (ray.at(t0 + 0.5f * step) - origin) * inv_spacing;
    r.delta = ray.dir * step * inv_spacing;
    r.last_point = (ray.at(t1 - 0.5f * last_length) - origin) * inv_spacing;
    r.light = -ray.dir;  // headlight: light and viewer at the eye
    return r;
  };
#if TESSERA_VOLUME_AVX2
  // The gathers index the packed voxels with int32, and march8 divides cells by the block size in float.
  const bool simd = options.simd && cpu_features().avx2 && cpu_features().fma &&
                    packed.voxels.size() < (size_t(1) << 31) &&
                    glm::all(glm::lessThan(packed.dims, glm::ivec3(1 << 23)));
#else
  const bool simd = false;
#endif
  parallel_tiles(options.width, options.height, 16, [&](const Tile& tile) {
    // Packets of 4 x 2 pixels: their rays stay closer together than a row of 8, so they share more cache lines.
    for (int j0 = tile.y0; j0 < tile.y1; j0 += 2)
      for (int i0 = tile.x0; i0 < tile.x1; i0 += 4) {
        glm::ivec2 pixel[8];
        int count = 0;
        for (int j = j0; j < std::min(j0 + 2, tile.y1); ++j)
          for (int i = i0; i < std::min(i0 + 4, tile.x1); ++i) pixel[count++] = {i, j};
        RaySamples r[8];
        Vec3f color[8];
        float alpha[8];
        int k[8] = {};
        for (int lane = 0; lane < count; ++lane) {
          r[lane] = setup(pixel[lane].x, pixel[lane].y);
          color[lane] = Vec3f(0.0f);
          alpha[lane] = 0;
          if (brick) {
            // Only the brick's samples, in the brick's own voxels (z less the offset: exact, as the offset is a
            // whole number no larger than z); a brick that ends before the ray does has no shorter last segment.
            const auto [begin, end] = brick_samples(r[lane], *brick);
            if (end < r[lane].n) r[lane].last_fraction = 1;
            r[lane].n = std::max(end, begin);
            k[lane] = begin;
            r[lane].first.z -= float(brick->offset);
            r[lane].last_point.z -= float(brick->offset);
          }
        }
#if TESSERA_VOLUME_AVX2
        if (simd) march8(cast, r, count, color, alpha, k);
#endif
        for (int lane = 0; lane < count; ++lane) {
          cast.march(r[lane], k[lane], color[lane], alpha[lane]);
          image(pixel[lane].x, pixel[lane].y) = layer
                                                    ? Vec4f(color[lane], alpha[lane])
                                                    : Vec4f(color[lane] + (1 - alpha[lane]) * options.background, 1.0f);
        }
      }
    report(tile);
  });
  return image;
}

}  // namespace

ImageRGB render_volume(const Volume<float>& volume, const VolumeRenderOptions& options) {
  if (volume.empty()) throw InvalidInput("cannot render an empty volume");
  if (options.width < 1 || options.height < 1) throw InvalidInput("image size must be positive");
  if (options.mip) {
    const auto [lo, hi] = value_range(volume);
    return to_rgb(cast_rays(volume, options, lo, hi, nullptr, false));
  }
  return VolumeRenderer(volume).render(options);
}

struct VolumeRenderer::Prepared {
  double lo, hi;  ///< the value range
  PackedVolume packed;
  Prepared(const Volume<float>& v, std::pair<double, double> range)
      : lo(range.first), hi(range.second), packed(v, range.first, range.second) {}
};

VolumeRenderer::VolumeRenderer(const Volume<float>& volume) : volume_(&volume) {
  if (volume.empty()) throw InvalidInput("cannot render an empty volume");
  prepared_ = std::make_unique<Prepared>(volume, value_range(volume));
}
VolumeRenderer::VolumeRenderer(const Volume<float>& volume, double lo, double hi) : volume_(&volume) {
  if (volume.empty()) throw InvalidInput("cannot render an empty volume");
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi))
    throw InvalidInput(fmt::format("value range [{}, {}] must be finite with lo <= hi", lo, hi));
  prepared_ = std::make_unique<Prepared>(volume, std::pair{lo, hi});
}
VolumeRenderer::~VolumeRenderer() = default;
VolumeRenderer::VolumeRenderer(VolumeRenderer&&) noexcept = default;
VolumeRenderer& VolumeRenderer::operator=(VolumeRenderer&&) noexcept = default;

ImageRGB VolumeRenderer::render(const VolumeRenderOptions& options) const {
  if (options.width < 1 || options.height < 1) throw InvalidInput("image size must be positive");
  return to_rgb(cast_rays(*volume_, options, prepared_->lo, prepared_->hi, &prepared_->packed, false));
}

ImageRGBA VolumeRenderer::render_layer(const VolumeRenderOptions& options) const {
  if (options.width < 1 || options.height < 1) throw InvalidInput("image size must be positive");
  if (options.mip) throw InvalidInput("maximum-intensity projection has no layer to composite");
  return cast_rays(*volume_, options, prepared_->lo, prepared_->hi, &prepared_->packed, true);
}

}  // namespace tessera
