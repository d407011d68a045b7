#pragma once
// The sketch runner: ONE loop with two faces (docs/sketch.md).
//
//   setup()                                   once, frame_count 0
//   every frame:  input events of the frame   the window's, then the script's (input.hpp), each to its callback
//                 draw()                      while looping, or once after redraw()
//                 present                     window: the frame streamed to the screen; the output file: one frame
//
// Headless (the default) has no display and a fixed frame rate: millis() is the frames' time, input comes only from
// a script, and the same sketch and options give the same bytes for any --threads. Windowed (SDL2, when Tessera was
// built with it) shows the frames in a resizable, HiDPI-aware window, vsync'd and paced to the frame rate, and
// delivers the real mouse and keyboard between frames; the sketch keeps its size and the window scales the picture
// to fit, letterboxed.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/sketch/input.hpp"
#include "tessera/sketch/registry.hpp"
#include "tessera/sketch/sketch.hpp"

namespace tessera {

/// Where the frames go.
enum class RunMode {
  headless,  ///< no display, a fixed frame rate, deterministic
  window,    ///< a real window (SDL2)
};

/// The face the runner's flags ask for, as Processing's Run: a window with --window, or when neither --headless nor
/// an output (-o) is given; headless otherwise.
RunMode run_mode(bool window, bool headless, const std::filesystem::path& output);

/// What run_sketch does; every field has a default (the runner's command-line flags in brackets).
struct RunOptions {
  std::optional<int> frames;                ///< [--frames N] stop after N frames
  std::optional<double> seconds;            ///< [--seconds S] stop after S seconds (headless: round(S fps) frames)
  std::optional<double> fps;                ///< [--fps F] the frame rate, replacing the sketch's frame_rate()
  std::optional<std::pair<int, int>> size;  ///< [--size WxH] replaces the (w, h) of the sketch's size()
  std::filesystem::path output;             ///< [-o] out.gif, out.mp4|.webm|.mov|.mkv, dir/, frame-####.png (every
                                            ///< frame, AnimationWriter) or one picture.png (the last frame)
  RunMode mode = RunMode::headless;         ///< [--window | --headless]
  std::filesystem::path input;              ///< [--input script.txt] scripted input events (input.hpp)
  std::vector<InputEvent> events;           ///< more scripted events (a built-in's demo input, tests)
  int threads = 0;                          ///< [--threads N] worker threads (0 = all cores); never changes pixels
  uint64_t seed = 0;                        ///< [--seed N] the seed of random() and noise() before setup()
  bool srgb = false;                        ///< [--srgb] 8-bit frames sRGB-encoded (window and files alike)
  std::string title = "tessera sketch";     ///< the window's title
};

/// What a run did.
struct RunResult {
  int frames = 0;             ///< frames presented (and written)
  int draws = 0;              ///< draw() calls (fewer than frames after no_loop())
  int width = 0, height = 0;  ///< the sketch's size
  double draw_seconds = 0;    ///< time in setup(), draw() and the callbacks
  double write_seconds = 0;   ///< time writing the output
};

/// Called with each presented frame: its number in the run (1, 2, ...) and its 8-bit picture.
using FrameCallback = std::function<void(int frame, const ImageRGBA8& picture)>;

/// Runs `sketch` (setup() and its frames) as `options` say, calling `on_frame` with every frame. Headless, the run
/// draws `frames` frames (or round(seconds fps); by default one second's), ending early after exit() or when the
/// sketch has stopped looping and no scripted event is left (nothing can change any more). In a window it runs until
/// the window is closed (or Escape, as Processing), exit(), or the frames or seconds given. Throws InvalidInput for
/// bad options or a bad input script, IoError for output that cannot be written, and Error for a window without a
/// display ("no display ...; run with --headless") or in a build without SDL2.
RunResult run_sketch(Sketch& sketch, const RunOptions& options, const FrameCallback& on_frame = {});

/// Whether this build can open windows (Tessera found SDL2 when it was configured).
bool window_supported();

/// A program's main for one sketch: parses the runner's flags (--frames N, --seconds S, --fps F, -o PATH,
/// --size WxH, --window/--headless, --input FILE, --threads N, --seed N, --srgb, --stats), runs a sketch made by
/// `factory`, and returns the exit status: 0, 2 for a usage error, 1 for a runtime error (printed as "NAME: error:
/// ..."). It opens a window as run_mode() says.
int sketch_main(int argc, char** argv, const SketchFactory& factory);

}  // namespace tessera

/// Defines main() for a sketch class: `TESSERA_SKETCH_MAIN(MySketch)` (tessera_add_sketch's programs end with it).
#define TESSERA_SKETCH_MAIN(SketchClass)                                                       \
  int main(int argc, char** argv) {                                                            \
    return ::tessera::sketch_main(argc, argv, [] { return std::make_unique<SketchClass>(); }); \
  }
