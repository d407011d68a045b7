#pragma once
// The outputs behind AnimationWriter (private to the image module): each format is a Sink that receives frames
// already checked for size; AnimationWriter (animation.cpp) does the checks shared by all formats.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "color_quantize.hpp"
#include "tessera/image/animation.hpp"

namespace tessera::detail {

/// One output format.
class AnimationSink {
 public:
  virtual ~AnimationSink() = default;
  /// Bytes of work buffers per pixel of a frame (checked against the memory budget before the first frame).
  virtual int bytes_per_pixel() const = 0;
  /// Receives frame `index` (0, 1, ...); every frame has the first frame's size.
  virtual void write(const ImageRGB& frame, long long index) = 0;
  virtual void write(const ImageRGBA& frame, long long index) = 0;
  virtual void write(const ImageRGBA8& frame, long long index) = 0;
  /// Completes the output (after at least one frame).
  virtual void finish() = 0;
};

/// A sink for formats that take 8-bit RGB: converts each float frame as write_image does (to_rgba8) and packs it to
/// RGB.
class Rgb8Sink : public AnimationSink {
 public:
  explicit Rgb8Sink(bool srgb) : srgb_(srgb) {}
  int bytes_per_pixel() const override { return 4 + 3; }
  void write(const ImageRGB& frame, long long index) override;
  void write(const ImageRGBA& frame, long long index) override;
  void write(const ImageRGBA8& frame, long long index) override;

 protected:
  /// Receives the frame as packed 8-bit RGB, rows from the top.
  virtual void write_rgb8(const std::vector<Rgb8>& pixels, int width, int height, long long index) = 0;

 private:
  bool srgb_;
  std::vector<Rgb8> pixels_;
};

/// The lowercase extension of a path, dot included ("" when none).
std::string lower_extension(const std::filesystem::path& path);

/// Animated GIF through giflib (gif_sink.cpp).
std::unique_ptr<AnimationSink> make_gif_sink(const std::filesystem::path& path, const AnimationOptions& options);
/// A video encoded by ffmpeg from raw frames on a pipe (video_sink.cpp). Throws IoError when ffmpeg is not on PATH.
std::unique_ptr<AnimationSink> make_video_sink(const std::filesystem::path& path, const AnimationOptions& options);

}  // namespace tessera::detail
