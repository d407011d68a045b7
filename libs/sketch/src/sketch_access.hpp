#pragma once
// The runner's side of a Sketch: what happens around the user's callbacks (private to the sketch module).
#include <tuple>
#include <utility>

#include "tessera/sketch/sketch.hpp"

namespace tessera::detail {

struct SketchAccess {
  /// Prepares a fresh run: the seed of random(), the clock, --size (replacing size()'s), and a 100 x 100 2D canvas
  /// in case setup() calls no size().
  static void begin(Sketch& s, uint64_t seed, std::optional<std::pair<int, int>> size_override, bool wall_clock);
  /// Runs setup() (with the 3D context current, when there is one).
  static void setup(Sketch& s);
  /// Whether the next frame calls draw(): looping, or a redraw() asked for.
  static bool wants_draw(const Sketch& s) { return s.looping_ || s.redraw_; }
  /// Draws one frame: frame_count + 1, Processing's per-frame pmouse, draw(), then (3D) the buffer swap.
  static void draw(Sketch& s);
  /// Advances the headless clock by one frame at the current frame rate.
  static void tick(Sketch& s) { s.frame_time_ms_ += 1000.0 / s.fps_; }
  /// Delivers one input event: the variables first, then the callback, as Processing's handleMouseEvent and
  /// handleKeyEvent.
  static void deliver(Sketch& s, const InputEvent& event);
  /// The frame on screen, 8-bit: 3D without `srgb`, the front buffer itself (no copy); else the canvas converted
  /// with `srgb` (2D) or the front buffer sRGB-encoded (3D), written into `scratch`. Valid until the next draw().
  static const ImageRGBA8& shown(Sketch& s, bool srgb, ImageRGBA8& scratch);
  /// Whether exit() was called.
  static bool exiting(const Sketch& s) { return s.exit_; }
  /// --fps: the frame rate from now on, whatever the sketch's frame_rate() calls say.
  static void fix_frame_rate(Sketch& s, double fps) {
    s.fps_ = fps;
    s.fps_fixed_ = true;
  }
  /// The window's drawable size when it opens (later sizes come as window_resize events).
  static void set_window_size(Sketch& s, std::pair<int, int> size) { std::tie(s.window_width, s.window_height) = size; }
  /// Releases the gt current context if it is this sketch's.
  static void end(Sketch& s);
};

}  // namespace tessera::detail
