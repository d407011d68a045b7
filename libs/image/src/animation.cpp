#include "tessera/image/animation.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "animation_sinks.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/image/image_io.hpp"

namespace tessera {

namespace fs = std::filesystem;

namespace detail {

void Rgb8Sink::write(const ImageRGB& frame, long long index) { write(to_rgba8(frame, srgb_), index); }
void Rgb8Sink::write(const ImageRGBA& frame, long long index) { write(to_rgba8(frame, srgb_), index); }

void Rgb8Sink::write(const ImageRGBA8& frame, long long index) {
  pixels_.resize(frame.pixels().size());
  std::transform(frame.pixels().begin(), frame.pixels().end(), pixels_.begin(),
                 [](const glm::u8vec4& p) { return Rgb8(p); });
  write_rgb8(pixels_, frame.width(), frame.height(), index);
}

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

namespace {

/// Numbered image files: write_image per frame, each file atomic on its own.
class SequenceSink final : public AnimationSink {
 public:
  SequenceSink(fs::path pattern, bool srgb) : pattern_(std::move(pattern)), srgb_(srgb) {
    std::error_code ec;
    const fs::path folder = pattern_.parent_path();
    if (!folder.empty()) fs::create_directories(folder, ec);
    if (ec) throw IoError(fmt::format("cannot create the folder '{}': {}", printable(folder.string()), ec.message()));
  }
  int bytes_per_pixel() const override { return 4; }  // write_image's 8-bit copy
  void write(const ImageRGB& frame, long long index) override {
    write_image(numbered_frame_path(pattern_, index), frame, WriteOptions{.srgb = srgb_});
  }
  void write(const ImageRGBA& frame, long long index) override {
    write_image(numbered_frame_path(pattern_, index), frame, WriteOptions{.srgb = srgb_});
  }
  void write(const ImageRGBA8& frame, long long index) override {
    write_image(numbered_frame_path(pattern_, index), frame, WriteOptions{.srgb = srgb_});
  }
  void finish() override {}

 private:
  fs::path pattern_;
  bool srgb_;
};

/// Where a frame number goes in a file name: the first run of '#' (Processing's saveFrame) or printf's "%d" or
/// "%0Nd" (render farms' "frame_%04d.png"), as [begin, end) and the zero-padded width; and whether a second follows.
struct NumberField {
  size_t begin = std::string::npos, end = std::string::npos;
  int width = 1;
  bool more = false;
};
NumberField find_number_field(const std::string& name) {
  const auto field_at = [&](size_t from) {
    NumberField f;
    for (size_t i = from; i < name.size(); ++i) {
      if (name[i] == '#') {
        f.begin = i;
        f.end = std::min(name.find_first_not_of('#', i), name.size());
        f.width = int(f.end - f.begin);
        return f;
      }
      if (name[i] != '%') continue;
      size_t j = i + 1;
      const bool zero = j < name.size() && name[j] == '0';
      while (j < name.size() && j - i < 4 && std::isdigit(static_cast<unsigned char>(name[j]))) ++j;
      if (j < name.size() && name[j] == 'd' && (j == i + 1 || zero)) {
        f.begin = i;
        f.end = j + 1;
        f.width = j == i + 1 ? 1 : std::stoi(name.substr(i + 1, j - i - 1));
        return f;
      }
    }
    return f;
  };
  NumberField field = field_at(0);
  if (field.begin != std::string::npos) field.more = field_at(field.end).begin != std::string::npos;
  return field;
}

/// The sequence pattern for a path: itself when its file name has '#', else "<folder>/frame-####.png".
fs::path sequence_pattern(const fs::path& path) {
  if (find_number_field(path.filename().string()).begin != std::string::npos) return path;
  return path / "frame-####.png";
}

}  // namespace
}  // namespace detail

AnimationFormat animation_format(const fs::path& path) {
  const std::string name = path.filename().string();
  if (detail::find_number_field(name).begin != std::string::npos) return AnimationFormat::sequence;
  const std::string ext = detail::lower_extension(path);
  if (ext == ".gif") return AnimationFormat::gif;
  if (ext == ".mp4" || ext == ".mov" || ext == ".mkv" || ext == ".webm") return AnimationFormat::video;
  std::error_code ec;
  if (name.empty() || fs::is_directory(path, ec)) return AnimationFormat::sequence;
  throw InvalidInput(
      fmt::format("'{}': unknown animation format: expected .gif, .mp4, .mov, .mkv, .webm, a file name "
                  "with a run of '#' or %0Nd (frame-####.png, frame_%04d.png) or a folder",
                  printable(path.string())));
}

fs::path numbered_frame_path(const fs::path& pattern, long long frame) {
  if (frame < 0) throw InvalidInput(fmt::format("frame number {} is negative", frame));
  const std::string name = pattern.filename().string();
  const detail::NumberField run = detail::find_number_field(name);
  if (run.begin == std::string::npos) return pattern;
  if (run.more)
    throw InvalidInput(
        fmt::format("'{}': the file name has more than one frame number field ('#' run or %d; expected one, as "
                    "frame-####.png or frame_%04d.png)",
                    printable(pattern.string())));
  const std::string number = fmt::format("{:0{}}", frame, run.width);
  return pattern.parent_path() / (name.substr(0, run.begin) + number + name.substr(run.end));
}

int AnimationWriter::gif_delay_cs(double fps, long long i) {
  // Centiseconds elapsed at the start of frame i, floored; the small slack keeps 100 * 3 / 30 at 10, not 9.99...
  const auto elapsed = [fps](long long n) { return std::floor(double(n) * 100.0 / fps + 1e-7); };
  return int(elapsed(i + 1) - elapsed(i));
}

class AnimationWriter::Impl {
 public:
  Impl(const fs::path& path, const AnimationOptions& options) : path_(path), format_(animation_format(path)) {
    if (!std::isfinite(options.fps) || options.fps <= 0)
      throw InvalidInput(fmt::format("animation frame rate {} must be a positive number", options.fps));
    if (format_ == AnimationFormat::gif && options.fps < 100.0 / 65535)
      throw InvalidInput(
          fmt::format("'{}': a GIF frame lasts at most 655.35 seconds (a 16-bit count of centiseconds), "
                      "so at least {:.6f} frames per second, not {}",
                      printable(path.string()), 100.0 / 65535, options.fps));
    if (format_ == AnimationFormat::gif && options.fps > 50)
      throw InvalidInput(
          fmt::format("'{}': a GIF plays at most 50 frames per second (its delays are whole "
                      "centiseconds, and viewers slow delays under 2 to 10), not {}",
                      printable(path.string()), options.fps));
    if (options.loop < -1 || options.loop > 65535)
      throw InvalidInput(
          fmt::format("GIF loop count {} must be -1 (play once), 0 (forever) or up to 65535", options.loop));
    if (options.crf < -1 || options.crf > 63)
      throw InvalidInput(fmt::format("video crf {} must be -1 (the encoder's default) or 0 to 63", options.crf));
    switch (format_) {
      case AnimationFormat::gif:
        sink_ = detail::make_gif_sink(path, options);
        break;
      case AnimationFormat::video:
        sink_ = detail::make_video_sink(path, options);
        break;
      case AnimationFormat::sequence:
        pattern_ = detail::sequence_pattern(path);
        sink_ = std::make_unique<detail::SequenceSink>(pattern_, options.srgb);
        break;
    }
  }

  template <class Frame>
  void add(const Frame& frame) {
    check_usable("add()");
    if (frame.empty())
      throw InvalidInput(fmt::format("'{}': frame {} is empty ({}x{})", printable(path_.string()), frames_,
                                     frame.width(), frame.height()));
    if (frames_ == 0) {
      MemoryBudget::check(
          saturating_product({uint64_t(frame.width()), uint64_t(frame.height()), uint64_t(sink_->bytes_per_pixel())}),
          fmt::format("the {}x{} frame buffers of '{}'", frame.width(), frame.height(), printable(path_.string())));
      width_ = frame.width(), height_ = frame.height();
    } else if (frame.width() != width_ || frame.height() != height_) {
      throw InvalidInput(fmt::format("'{}': frame {} is {}x{}, the animation is {}x{} (the first frame's size)",
                                     printable(path_.string()), frames_, frame.width(), frame.height(), width_,
                                     height_));
    }
    // A failed frame may leave the output half-written: later calls refuse instead of writing a broken file.
    failed_ = true;
    sink_->write(frame, frames_);
    failed_ = false;
    ++frames_;
  }

  void finish() {
    check_usable("finish()");
    if (frames_ == 0) throw InvalidInput(fmt::format("'{}': no frames to write", printable(path_.string())));
    finished_ = true;
    sink_->finish();
  }

  void check_usable(std::string_view call) const {
    if (finished_ || failed_)
      throw InvalidInput(
          fmt::format("'{}': {} after {}", printable(path_.string()), call, finished_ ? "finish()" : "a failed frame"));
  }

  fs::path frame_path(long long i) const {
    return format_ == AnimationFormat::sequence ? numbered_frame_path(pattern_, i) : path_;
  }

  fs::path path_, pattern_;
  AnimationFormat format_;
  std::unique_ptr<detail::AnimationSink> sink_;
  int width_ = 0, height_ = 0;
  long long frames_ = 0;
  bool finished_ = false, failed_ = false;
};

AnimationWriter::AnimationWriter(const fs::path& path, const AnimationOptions& options)
    : impl_(std::make_unique<Impl>(path, options)) {}
AnimationWriter::~AnimationWriter() = default;
AnimationWriter::AnimationWriter(AnimationWriter&&) noexcept = default;
AnimationWriter& AnimationWriter::operator=(AnimationWriter&&) noexcept = default;

void AnimationWriter::add(const ImageRGB& frame) { impl_->add(frame); }
void AnimationWriter::add(const ImageRGBA& frame) { impl_->add(frame); }
void AnimationWriter::add(const ImageRGBA8& frame) { impl_->add(frame); }
void AnimationWriter::finish() { impl_->finish(); }
long long AnimationWriter::frames() const { return impl_->frames_; }
AnimationFormat AnimationWriter::format() const { return impl_->format_; }
fs::path AnimationWriter::frame_path(long long i) const { return impl_->frame_path(i); }

}  // namespace tessera
