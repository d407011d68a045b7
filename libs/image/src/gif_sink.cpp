// Animated GIF output through giflib's streaming encoder: the screen descriptor and the NETSCAPE2.0 loop extension
// at the first frame, then per frame a graphic control extension (the delay), an image descriptor of the rectangle
// that changed since the previous frame, with a local color table when that rectangle does not use the global one,
// and the LZW-coded indices. Bytes go straight to an AtomicFile.
#include <gif_lib.h>

#include <algorithm>

#include "animation_sinks.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/parse.hpp"

namespace tessera::detail {
namespace {

namespace fs = std::filesystem;

/// giflib's output callback: appends to the AtomicFile's stream; a short count makes giflib report a write error.
int write_to_stream(GifFileType* gif, const GifByteType* data, int size) {
  auto& out = *static_cast<std::ostream*>(gif->UserData);
  out.write(reinterpret_cast<const char*>(data), size);
  return out ? size : 0;
}

struct ColorMapDeleter {
  void operator()(ColorMapObject* map) const { GifFreeMapObject(map); }
};
using ColorMap = std::unique_ptr<ColorMapObject, ColorMapDeleter>;

/// A GIF color table of `palette`, padded with black to the power of two (at least 2) that GIF tables must have.
ColorMap color_map(const std::vector<Rgb8>& palette) {
  int size = 2;
  while (size < int(palette.size())) size *= 2;
  std::vector<GifColorType> colors(size_t(size), GifColorType{0, 0, 0});
  for (size_t i = 0; i < palette.size(); ++i) colors[i] = {palette[i].x, palette[i].y, palette[i].z};
  ColorMap map(GifMakeMapObject(size, colors.data()));
  if (!map) throw std::bad_alloc();
  return map;
}

class GifSink final : public Rgb8Sink {
 public:
  GifSink(const fs::path& path, const AnimationOptions& options)
      : Rgb8Sink(options.srgb), path_(path), options_(options), file_(path) {
    int error = 0;
    gif_ = EGifOpen(&file_.stream(), write_to_stream, &error);
    if (!gif_) fail(error);
    EGifSetGifVersion(gif_, true);  // GIF89a: the extensions need it (giflib cannot tell while streaming)
  }
  ~GifSink() override {
    if (gif_) EGifCloseFile(gif_, nullptr);  // frees giflib's state; the AtomicFile then removes the temporary
  }
  GifSink(const GifSink&) = delete;
  GifSink& operator=(const GifSink&) = delete;

  // + the palette indices, the previous frame and the changed rectangle
  int bytes_per_pixel() const override { return Rgb8Sink::bytes_per_pixel() + 1 + 3 + 3; }

  void finish() override {
    int error = 0;
    const int status = EGifCloseFile(gif_, &error);  // writes the trailer and frees, even on error
    gif_ = nullptr;
    if (status == GIF_ERROR) fail(error);
    file_.commit();
  }

 protected:
  void write_rgb8(const std::vector<Rgb8>& frame, int width, int height, long long index) override {
    if (width > 65535 || height > 65535)
      throw InvalidInput(fmt::format("'{}': a GIF is at most 65535x65535 pixels, the frames are {}x{}",
                                     printable(path_.string()), width, height));
    // Only the rectangle that changed since the previous frame is stored; the rest stays on screen (disposal 1).
    const Rect rect = index == 0 ? Rect{0, 0, width, height} : changed(frame, width, height);
    const std::vector<Rgb8>& pixels = crop(frame, width, rect);
    previous_ = frame;
    indices_.resize(pixels.size());
    // A frame of at most 256 colors is exact with its own palette or a global one holding them all, and then
    // dithering has no error to spread: the frame is mapped directly.
    const auto colors = distinct_colors(pixels);
    bool exact = colors.has_value();
    ColorMap local;
    if (index == 0) {
      start(colors ? *colors : median_cut_palette(pixels), width, height);
    } else if (const bool fits_global = colors && in_global(*colors); uses_global(fits_global)) {
      exact = fits_global;
    } else {
      local_.emplace(colors ? *colors : median_cut_palette(pixels));
      local = color_map(local_->palette());
    }
    PaletteMapper& mapper = local ? *local_ : *global_;
    map_to_palette(pixels, rect.width, rect.height, mapper, options_.dither && !exact, indices_);

    const int delay = AnimationWriter::gif_delay_cs(options_.fps, index);
    // Graphic control: disposal 1 (leave the frame in place), no transparency; the delay little-endian.
    GifByteType control[4] = {0x04, GifByteType(delay & 0xFF), GifByteType(delay >> 8), 0};
    check(EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, 4, control));
    check(EGifPutImageDesc(gif_, rect.x, rect.y, rect.width, rect.height, false, local.get()));
    check(EGifPutLine(gif_, indices_.data(), rect.width * rect.height));
  }

 private:
  struct Rect {
    int x, y, width, height;
  };

  /// The smallest rectangle holding every pixel that differs from the previous frame (a 1x1 one when none does).
  Rect changed(const std::vector<Rgb8>& frame, int width, int height) const {
    int x0 = width, y0 = height, x1 = -1, y1 = -1;
    for (int y = 0; y < height; ++y) {
      const size_t row = size_t(y) * size_t(width);
      for (int x = 0; x < width; ++x)
        if (frame[row + size_t(x)] != previous_[row + size_t(x)]) {
          x0 = std::min(x0, x), x1 = std::max(x1, x);
          y0 = std::min(y0, y), y1 = y;
        }
    }
    return x1 < 0 ? Rect{0, 0, 1, 1} : Rect{x0, y0, x1 - x0 + 1, y1 - y0 + 1};
  }

  /// The pixels of `rect` (the frame itself when it covers it all).
  const std::vector<Rgb8>& crop(const std::vector<Rgb8>& frame, int width, const Rect& rect) {
    if (rect.width == width && size_t(rect.width) * size_t(rect.height) == frame.size()) return frame;
    cropped_.clear();
    for (int y = rect.y; y < rect.y + rect.height; ++y) {
      const auto row = frame.begin() + ptrdiff_t(y) * width + rect.x;
      cropped_.insert(cropped_.end(), row, row + rect.width);
    }
    return cropped_;
  }

  /// The first frame: its palette becomes the global table; the screen descriptor and loop extension go out.
  void start(std::vector<Rgb8> palette, int width, int height) {
    global_.emplace(std::move(palette));
    for (const Rgb8& c : global_->palette()) global_colors_.push_back(pack_rgb(c));
    std::sort(global_colors_.begin(), global_colors_.end());
    const ColorMap map = color_map(global_->palette());
    check(EGifPutScreenDesc(gif_, width, height, 8, 0, map.get()));
    if (options_.loop >= 0) {
      // NETSCAPE2.0 application extension: sub-block 1, then the loop count little-endian (0 = forever).
      const GifByteType loop[3] = {1, GifByteType(options_.loop & 0xFF), GifByteType(options_.loop >> 8)};
      check(EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE));
      check(EGifPutExtensionBlock(gif_, 11, "NETSCAPE2.0"));
      check(EGifPutExtensionBlock(gif_, 3, loop));
      check(EGifPutExtensionTrailer(gif_));
    }
  }

  /// Whether a later frame takes the global table: always (shared), never (per frame), or when the table holds
  /// every color of the frame (automatic: `fits_global`).
  bool uses_global(bool fits_global) const {
    switch (options_.palette) {
      case GifPalette::shared:
        return true;
      case GifPalette::per_frame:
        return false;
      case GifPalette::automatic:
        break;
    }
    return fits_global;
  }

  /// Whether the global table holds every one of `colors`.
  bool in_global(const std::vector<Rgb8>& colors) const {
    return std::all_of(colors.begin(), colors.end(), [&](Rgb8 c) {
      return std::binary_search(global_colors_.begin(), global_colors_.end(), pack_rgb(c));
    });
  }

  void check(int status) const {
    if (status == GIF_ERROR) fail(gif_->Error);
  }
  [[noreturn]] void fail(int error) const {
    throw IoError(fmt::format("cannot write '{}': giflib: {}", printable(path_.string()), GifErrorString(error)));
  }

  fs::path path_;
  AnimationOptions options_;
  AtomicFile file_;
  GifFileType* gif_ = nullptr;
  std::optional<PaletteMapper> global_, local_;
  std::vector<uint32_t> global_colors_;  // the global table as sorted 0xRRGGBB, for the automatic test
  std::vector<uint8_t> indices_;
  std::vector<Rgb8> previous_, cropped_;  // the previous frame, and the changed rectangle of this one
};

}  // namespace

std::unique_ptr<AnimationSink> make_gif_sink(const fs::path& path, const AnimationOptions& options) {
  return std::make_unique<GifSink>(path, options);
}

}  // namespace tessera::detail
