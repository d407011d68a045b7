#pragma once
// Direct volume rendering by ray casting (the notes' "render directly from volume data"): eye rays through the
// volume's box, trilinear samples at a fixed step, a transfer function, front-to-back compositing with early ray
// termination, empty-space skipping over a min/max block grid, maximum-intensity projection, gradient shading.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/volume/volume.hpp"

namespace tessera {

/// What a volume's value histogram says about it, for transfer functions that adapt to the data (medical volumes
/// come as 8-bit, 12-bit or Hounsfield values, procedural ones in any range).
struct ValueProfile {
  double lo = 0, hi = 0;  ///< the value range
  double threshold = 0;   ///< Otsu's threshold (1024 bins over [lo, 99th percentile]): object above, background below
  double median = 0;      ///< the median of the values above the threshold
  double top = 0;         ///< the 99.5th percentile of the values above the threshold (robust to a few outliers)
  double diagonal = 0;    ///< the length of the volume's box diagonal, world units
  /// Whether the values above the threshold spread over a range (false for a constant volume).
  bool separable() const { return top > threshold; }
  /// The value at position s of the object's scale: s = 0 is the threshold, s = 1 the top.
  double value_at(double s) const { return threshold + s * (top - threshold); }
};

/// Profiles `volume`. Throws InvalidInput for an empty volume.
ValueProfile profile_values(const Volume<float>& volume);

/// A piecewise-linear map from value to color and opacity. Opacity is per unit world length: a sample standing for a
/// segment of length s gets alpha = 1 - (1 - opacity)^s.
class TransferFunction {
 public:
  struct Point {
    float value;
    Vec3f color;
    float opacity;
  };
  /// The largest color component a point may have (colors may exceed 1, for emission brighter than white).
  static constexpr float kMaxColor = 1e6f;
  TransferFunction() = default;
  /// Control points; they are sorted by value. Throws InvalidInput when empty, or for a value that is not finite, a
  /// color component outside [0, kMaxColor] or an opacity outside [0, 1].
  explicit TransferFunction(std::vector<Point> points);
  /// Color and opacity at v (clamped to the first and last points).
  Vec4f operator()(float v) const;
  /// The largest opacity over [lo, hi].
  float max_opacity(float lo, float hi) const;
  const std::vector<Point>& points() const { return points_; }

  /// The opacities of automatic() and preset() are per this fraction of the volume's diagonal (one world unit of the
  /// volumes the presets were made for, whose diagonals are 317 and 298), so that they look alike at any size.
  static constexpr double kReferenceDiagonal = 300;
  /// The names preset() knows, for help texts and messages.
  static const std::vector<std::string>& preset_names();
  /// A preset adapted to a volume: "ct-bone", "ct-skin" (CT) or "mri" (MRI). Values are placed on the object's scale
  /// of `profile` (ValueProfile::value_at), so one preset serves 8-bit, 12-bit and Hounsfield data alike; opacities
  /// are per kReferenceDiagonal-th of the diagonal. Throws InvalidInput for another name, and, saying why, for a
  /// volume without an object to tell from its background (a constant volume).
  static TransferFunction preset(const std::string& name, const ValueProfile& profile);
  /// The default transfer function, for any volume: the background (below Otsu's threshold) clear, then color and
  /// opacity ramping up to the profile's top, translucent enough to see inside. A constant volume is a uniform haze.
  static TransferFunction automatic(const ValueProfile& profile);
  /// Parses JSON {"points": [[value, r, g, b, opacity], ...]} or CSV lines "value,r,g,b,opacity" (by extension).
  static TransferFunction load(const std::filesystem::path& path);
  /// Parses the JSON text above. Throws InvalidInput naming `name`.
  static TransferFunction from_json(const std::string& text, const std::string& name);
  /// Parses the CSV text above ('#' comments). Throws InvalidInput naming "name:line".
  static TransferFunction from_csv(const std::string& text, const std::string& name);

 private:
  std::vector<Point> points_;
};

/// Settings of render_volume().
struct VolumeRenderOptions {
  /// The most samples a ray may take across the volume's box (its diagonal / step): a step so small that it asks
  /// for more is refused (it would take hours, and float sample positions stop advancing below half an ulp).
  static constexpr int64_t kMaxSamplesPerRay = int64_t(1) << 20;
  Camera camera;  ///< camera.aspect is set from width / height
  int width = 256, height = 256;
  float step = 0;             ///< world distance between samples; 0 = half the smallest spacing (see kMaxSamplesPerRay)
  TransferFunction transfer;  ///< used unless mip
  bool mip = false;           ///< maximum-intensity projection: gray = (max - lo) / (hi - lo) of the volume range
  bool shading = true;        ///< gradient shading: ambient + diffuse + Blinn specular, headlight
  float ambient = 0.3f, diffuse = 0.7f, specular = 0.3f, shininess = 32.0f;
  float termination = 0.99f;  ///< early ray termination when accumulated opacity reaches this
  bool skip_empty = true;     ///< skip blocks whose values all map to zero opacity (same image, faster)
  int block = 8;              ///< voxels per empty-space block side
  bool simd = true;           ///< 8 rays at a time with AVX2 where the CPU has it (same image up to rounding)
  Vec3f background{0.0f};
  /// Called (from worker threads, concurrently) with the number of pixels of each finished tile, for progress reports.
  std::function<void(int64_t pixels)> progress;

  /// A brick of a volume split into slabs of z (sort-last rendering across MPI ranks, docs/farm.md): the volume
  /// rendered holds slices [offset, offset + its dims.z) of a volume of `whole_dims`, and only the samples whose z, in
  /// the whole volume's voxels, lies in [z_begin, z_end) are taken (all below z_end when `first`, all from z_begin
  /// when `last`), at the positions a render of the whole volume samples. The slices z_begin - 1 and z_end + 1 must
  /// be there where the whole volume has them (gradients). With the whole volume's value range, the bricks' layers
  /// (VolumeRenderer::render_layer) composited front to back give the whole render, up to rounding and early ray
  /// termination, which each brick applies to its own opacity.
  struct Brick {
    glm::ivec3 whole_dims{0};
    int offset = 0;
    int z_begin = 0, z_end = 0;
    bool first = false, last = false;
  };
  std::optional<Brick> brick;
};

/// Ray-casts `volume` into an image (parallel tiles; identical for any thread count). Throws InvalidInput for an
/// empty volume, a non-positive size, a negative or non-finite step, or a step that gives more than
/// VolumeRenderOptions::kMaxSamplesPerRay samples across the volume's box. The same as
/// VolumeRenderer(volume).render(options).
ImageRGB render_volume(const Volume<float>& volume, const VolumeRenderOptions& options);

/// A volume prepared for ray casting (its values and central-difference gradients quantized to 16 bits and
/// interleaved), for rendering it several times, e.g. from several views, without preparing it again; VTK's
/// ray-cast mappers keep their gradient tables between renders the same way. `volume` must outlive the renderer.
class VolumeRenderer {
 public:
  /// Prepares `volume`. Throws InvalidInput for an empty volume.
  explicit VolumeRenderer(const Volume<float>& volume);
  /// Prepares `volume` with the value range [lo, hi] rather than its own (a brick's, which must quantize and map
  /// values as the whole volume does).
  VolumeRenderer(const Volume<float>& volume, double lo, double hi);
  ~VolumeRenderer();
  VolumeRenderer(VolumeRenderer&&) noexcept;
  VolumeRenderer& operator=(VolumeRenderer&&) noexcept;
  /// Ray-casts the volume (see render_volume). Throws InvalidInput for a non-positive size or a step that
  /// render_volume refuses.
  ImageRGB render(const VolumeRenderOptions& options) const;
  /// What the volume (or options.brick of it) adds to each pixel, without the background: color premultiplied by
  /// opacity, and the opacity. render() is this layer over the background. Not for MIP (throws InvalidInput).
  ImageRGBA render_layer(const VolumeRenderOptions& options) const;

 private:
  struct Prepared;
  const Volume<float>* volume_;
  std::unique_ptr<Prepared> prepared_;
};

}  // namespace tessera
