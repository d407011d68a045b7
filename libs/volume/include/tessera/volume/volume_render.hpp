#pragma once
// Direct volume rendering by ray casting (the notes' "render directly from volume data"): eye rays through the
// volume's box, trilinear samples at a fixed step, a transfer function, front-to-back compositing with early ray
// termination, empty-space skipping over a min/max block grid, maximum-intensity projection, gradient shading.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/volume/volume.hpp"

namespace tessera {

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

  /// Presets for CT (Hounsfield-like values of headsq: "ct-bone", "ct-skin") and 8-bit MRI ("mri"). Throws
  /// InvalidInput for another name.
  static TransferFunction preset(const std::string& name);
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
  Camera camera;                 ///< camera.aspect is set from width / height
  int width = 256, height = 256;
  float step = 0;                ///< world distance between samples; 0 = half the smallest spacing
  TransferFunction transfer;     ///< used unless mip
  bool mip = false;              ///< maximum-intensity projection: gray = (max - lo) / (hi - lo) of the volume range
  bool shading = true;           ///< gradient shading: ambient + diffuse + Blinn specular, headlight
  float ambient = 0.3f, diffuse = 0.7f, specular = 0.3f, shininess = 32.0f;
  float termination = 0.99f;     ///< early ray termination when accumulated opacity reaches this
  bool skip_empty = true;        ///< skip blocks whose values all map to zero opacity (same image, faster)
  int block = 8;                 ///< voxels per empty-space block side
  bool simd = true;              ///< 8 rays at a time with AVX2 where the CPU has it (same image up to rounding)
  Vec3f background{0.0f};
};

/// Ray-casts `volume` into an image (parallel tiles; identical for any thread count). Throws InvalidInput for an
/// empty volume or a non-positive size. The same as VolumeRenderer(volume).render(options).
ImageRGB render_volume(const Volume<float>& volume, const VolumeRenderOptions& options);

/// A volume prepared for ray casting (its values and central-difference gradients quantized to 16 bits and
/// interleaved), for rendering it several times, e.g. from several views, without preparing it again; VTK's
/// ray-cast mappers keep their gradient tables between renders the same way. `volume` must outlive the renderer.
class VolumeRenderer {
 public:
  /// Prepares `volume`. Throws InvalidInput for an empty volume.
  explicit VolumeRenderer(const Volume<float>& volume);
  ~VolumeRenderer();
  VolumeRenderer(VolumeRenderer&&) noexcept;
  VolumeRenderer& operator=(VolumeRenderer&&) noexcept;
  /// Ray-casts the volume (see render_volume). Throws InvalidInput for a non-positive size.
  ImageRGB render(const VolumeRenderOptions& options) const;

 private:
  struct Prepared;
  const Volume<float>* volume_;
  std::unique_ptr<Prepared> prepared_;
};

}  // namespace tessera
