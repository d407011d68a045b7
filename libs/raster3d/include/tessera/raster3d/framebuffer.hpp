#pragma once
// Framebuffer: the color, depth and stencil buffers the 3D pipeline draws into, double buffered (the notes' "Memory 1
// used for display, Memory 2 for creating the next image").
//
// Color is 8-bit RGBA, as an OpenGL RGBA8 framebuffer: a fragment's color is clamped to [0, 1] and rounded to
// nearest when written, so results compare with Mesa pixel for pixel. Depth is a 24-bit unsigned normalized integer
// per pixel (0 = near plane, 2^24 - 1 = far plane), gl-raster-conventions.md item 7. Stencil is 8 bits per pixel
// (GL's usual depth 24 / stencil 8). The images keep row 0 at the top (DESIGN.md section 3); the pipeline maps
// OpenGL's window row j (y up) to image row height - 1 - j.
#include <cstdint>
#include <memory>

#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"

namespace tessera::raster3d {

/// The largest 24-bit depth value: the cleared depth, 1.0 in window z.
inline constexpr uint32_t kDepthMax = (1u << 24) - 1;

/// Window z in [0, 1] to the stored 24-bit value, round(z (2^24 - 1)) with z clamped to [0, 1].
inline uint32_t depth_to_unorm24(double z) {
  z = z < 0 ? 0 : (z > 1 ? 1 : z);
  return uint32_t(z * double(kDepthMax) + 0.5);
}

/// A float in [0, 1] to an 8-bit unorm (clamped, NaN to 0), rounded to nearest with ties to even as Mesa does
/// (0.3 * 255 = 76.5 gives 76): adding and subtracting 1.5 * 2^23 leaves the float rounded to an integer in the
/// default rounding mode, branch-free and vectorizable.
inline uint8_t to_unorm8(float v) {
  v = v > 0.0f ? v : 0.0f;  // NaN -> 0
  v = v < 1.0f ? v : 1.0f;
  constexpr float kRound = 12582912.0f;  // 1.5 * 2^23
  return uint8_t((v * 255.0f + kRound) - kRound);
}

/// A linear float color in [0, 1] to 8-bit RGBA (to_unorm8 per channel, alpha 255).
inline glm::u8vec4 to_color8(const Vec3f& c) { return {to_unorm8(c.x), to_unorm8(c.y), to_unorm8(c.z), 255}; }
/// The same with alpha.
inline glm::u8vec4 to_color8(const Vec4f& c) {
  return {to_unorm8(c.x), to_unorm8(c.y), to_unorm8(c.z), to_unorm8(c.w)};
}

namespace detail {
struct RasterScratch;  // binning memory reused from draw to draw (detail/pipeline_setup.hpp)
}  // namespace detail

/// Color, depth and stencil buffers of width x height pixels, with a back buffer (drawn into) and a front buffer
/// (shown). The pipeline's raster thread may still be writing the buffers after a Context call returns: read them
/// through Context::framebuffer(), which waits; clear_*, swap, moves and the destructor wait too.
class Framebuffer {
 public:
  /// A width x height framebuffer, color black, depth cleared to the far plane, stencil 0. Throws InvalidInput for
  /// sizes < 1.
  Framebuffer(int width, int height);
  /// A width x height framebuffer with a depth buffer alone: no color or stencil buffers (their images are empty).
  /// Draws into it write depth only, as with the color mask off; a draw with the stencil test on throws InvalidInput.
  /// A fifth of the memory: what a shadow map's pass 1 needs. Throws InvalidInput for sizes < 1.
  static Framebuffer depth_only(int width, int height);
  ~Framebuffer();
  Framebuffer(Framebuffer&&) noexcept;
  Framebuffer& operator=(Framebuffer&&) noexcept;

  /// Size in pixels.
  int width() const { return depth_.width(); }
  int height() const { return depth_.height(); }
  /// Whether it has color (and stencil) buffers: false for depth_only.
  bool has_color() const { return !color_.empty(); }

  /// The back color buffer (what drawing writes).
  ImageRGBA8& color() { return color_; }
  const ImageRGBA8& color() const { return color_; }
  /// The depth buffer: 24-bit unorm values in uint32, row 0 at the top.
  Image<uint32_t>& depth() { return depth_; }
  const Image<uint32_t>& depth() const { return depth_; }
  /// The stencil buffer: 8 bits per pixel, row 0 at the top.
  Image<uint8_t>& stencil() { return stencil_; }
  const Image<uint8_t>& stencil() const { return stencil_; }
  /// The front color buffer: what the last swap() presented.
  const ImageRGBA8& front() const { return front_; }

  /// Clears the back color buffer to `color` and `alpha` (glClearColor + glClear(GL_COLOR_BUFFER_BIT)).
  void clear_color(const Vec3f& color, float alpha = 1.0f);
  /// Clears the depth buffer to window z `depth` (default the far plane, 1.0).
  void clear_depth(double depth = 1.0);
  /// Clears the stencil buffer to `value` (glClearStencil + glClear(GL_STENCIL_BUFFER_BIT)).
  void clear_stencil(uint8_t value = 0);
  /// Clears color and depth.
  void clear(const Vec3f& color, double depth = 1.0) {
    clear_color(color);
    clear_depth(depth);
  }
  /// Exchanges back and front color buffers (double buffering); the new back buffer keeps the old front's pixels.
  void swap();

  /// The back color buffer as linear float RGB (for image files and comparisons); empty for depth_only.
  ImageRGB color_rgb() const;
  /// The depth buffer as window z in [0, 1] (value / (2^24 - 1)), for --depth-out PFM files.
  DepthImage depth_image() const;

  /// Internal: the pipeline's reusable binning memory and raster thread.
  detail::RasterScratch& scratch() { return *scratch_; }

 private:
  Framebuffer(int width, int height, bool color);
  void wait_for_raster() noexcept;

  ImageRGBA8 color_, front_;
  Image<uint32_t> depth_;
  Image<uint8_t> stencil_;
  std::unique_ptr<detail::RasterScratch> scratch_;
};

}  // namespace tessera::raster3d
