#include "tessera/sketch/runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>

#include "sketch_access.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/image/animation.hpp"
#include "tessera/image/image_io.hpp"
#include "window.hpp"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
using detail::SketchAccess;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void check_options(const RunOptions& o) {
  if (o.frames && *o.frames < 1) throw InvalidInput(fmt::format("--frames {}: expected at least 1", *o.frames));
  if (o.seconds && !(*o.seconds > 0 && std::isfinite(*o.seconds)))
    throw InvalidInput(fmt::format("--seconds {}: expected a number > 0", *o.seconds));
  if (o.frames && o.seconds) throw InvalidInput("--frames and --seconds: give one of them");
  if (o.fps && !(*o.fps > 0 && *o.fps <= 1000))
    throw InvalidInput(fmt::format("--fps {}: expected 0 < F <= 1000", *o.fps));
}

/// The output: every frame to an AnimationWriter (GIF, video, numbered sequence), or the last frame to one picture.
class Output {
 public:
  Output(const std::filesystem::path& path, double fps) : path_(path) {
    if (path.empty() || !is_animation(path)) return;
    // A GIF's delays are whole centiseconds (at most 50 frames per second): above that every k-th frame is kept.
    if (animation_format(path) == AnimationFormat::gif && fps > 50) keep_every_ = int(std::ceil(fps / 50));
    writer_.emplace(path, AnimationOptions{.fps = fps / keep_every_});
  }
  void add(int frame, const ImageRGBA8& picture) {
    if (writer_ && (frame - 1) % keep_every_ == 0) writer_->add(picture);
  }
  /// Completes the animation, or writes `last` (the last frame presented; null when none was) as the one picture.
  void finish(const ImageRGBA8* last) {
    if (writer_)
      writer_->finish();
    else if (!path_.empty() && last)
      write_image(path_, *last);
  }

 private:
  // What AnimationWriter takes (a GIF or video, a name with a run of '#', a folder) gets every frame; anything else
  // is one picture.
  static bool is_animation(const std::filesystem::path& path) {
    try {
      animation_format(path);
      return true;
    } catch (const InvalidInput&) {
      return false;
    }
  }
  std::filesystem::path path_;
  std::optional<AnimationWriter> writer_;
  int keep_every_ = 1;
};

}  // namespace

RunMode run_mode(bool window, bool headless, const std::filesystem::path& output) {
  return window || (!headless && output.empty()) ? RunMode::window : RunMode::headless;
}

RunResult run_sketch(Sketch& sketch, const RunOptions& options, const FrameCallback& on_frame) {
  check_options(options);
  const ThreadLimit limit(options.threads);
  std::vector<InputEvent> script = options.events;
  if (!options.input.empty()) {
    std::vector<InputEvent> file = read_input_script(options.input);
    script.insert(script.end(), file.begin(), file.end());
  }
  std::stable_sort(script.begin(), script.end(),
                   [](const InputEvent& a, const InputEvent& b) { return a.frame < b.frame; });

  const bool windowed = options.mode == RunMode::window;
  RunResult result;
  const Clock::time_point setup_start = Clock::now();
  SketchAccess::begin(sketch, options.seed, options.size, windowed);
  SketchAccess::setup(sketch);
  if (options.fps) SketchAccess::fix_frame_rate(sketch, *options.fps);
  result.draw_seconds += seconds_since(setup_start);
  result.width = sketch.width;
  result.height = sketch.height;

  const double fps = sketch.frame_rate();
  // Headless: the frames asked for, or round(seconds fps), by default one second's. In a window: until closed, or
  // the frames asked for; --seconds there is wall time.
  std::optional<int> budget = options.frames;
  if (!budget && !windowed) budget = int(std::clamp(std::llround(options.seconds.value_or(1.0) * fps), 1LL, 1LL << 30));
  std::unique_ptr<detail::Window> window;
  if (windowed) {
    window = detail::open_window(options.title, sketch.width, sketch.height);
    SketchAccess::set_window_size(sketch, window->drawable_size());
  }
  Output output(options.output, fps);
  std::optional<Progress> progress;
  if (!windowed) progress.emplace("sketch frames", *budget);

  const Clock::time_point start = Clock::now();
  std::vector<InputEvent> window_events;
  ImageRGBA8 converted;               // the 8-bit frame when shown() must convert (2D, or 3D with --srgb)
  const ImageRGBA8* shown = nullptr;  // the last frame presented
  size_t next_event = 0;
  for (int frame = 1; !budget || frame <= *budget; ++frame) {
    const Clock::time_point frame_start = Clock::now();
    bool close = false;
    // Input between frames: the window's (in the order they happened), then the script's for this frame.
    if (window) {
      window_events.clear();
      close = !window->poll(window_events);
      for (const InputEvent& e : window_events) {
        SketchAccess::deliver(sketch, e);
        // Escape closes the sketch after its key_pressed(), as in Processing.
        if (e.kind == InputKind::key_press && e.key == Key::escape) close = true;
      }
    }
    if (close) break;
    for (; next_event < script.size() && script[next_event].frame <= frame; ++next_event)
      SketchAccess::deliver(sketch, script[next_event]);
    if (SketchAccess::wants_draw(sketch)) {
      SketchAccess::draw(sketch);
      ++result.draws;
    }
    shown = &SketchAccess::shown(sketch, options.srgb, converted);
    const ImageRGBA8& picture = *shown;
    result.draw_seconds += seconds_since(frame_start);

    const Clock::time_point write_start = Clock::now();
    if (window) window->present(picture);
    output.add(frame, picture);
    if (on_frame) on_frame(frame, picture);
    result.write_seconds += seconds_since(write_start);
    ++result.frames;
    if (progress) progress->advance();

    if (SketchAccess::exiting(sketch)) break;
    if (window) {
      if (options.seconds && seconds_since(start) >= *options.seconds) break;
      // Pace to the frame rate (the present above already waited for the vertical sync when there is one).
      std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(frame / sketch.frame_rate())));
    } else {
      // Nothing can change once the sketch stopped looping and no scripted event is left.
      if (!SketchAccess::wants_draw(sketch) && next_event == script.size()) break;
      SketchAccess::tick(sketch);
    }
  }
  if (progress) progress->done();
  const Clock::time_point write_start = Clock::now();
  output.finish(shown);
  result.write_seconds += seconds_since(write_start);
  return result;
}

}  // namespace tessera
