#pragma once
// tessera::Sketch: a Processing sketch as a C++ class. Override setup() and draw() (and the event callbacks you need),
// call size() in setup(), and hand the sketch to run_sketch() (runner.hpp) or sketch_main(); the runner drives the
// one loop, in a window or headless (docs/sketch.md).
//
// Processing -> Tessera (Processing's names in Tessera's lower_case spelling, as canvas.hpp maps the drawing calls):
//   setup, draw -> setup, draw (virtual);
//   mousePressed(), mouseReleased(), mouseDragged(), mouseMoved(), mouseWheel(event), keyPressed(), keyReleased(),
//   windowResized() -> mouse_pressed(), mouse_released(), mouse_dragged(), mouse_moved(), mouse_wheel(delta),
//   key_pressed(), key_released(), window_resized() (virtual);
//   frameCount, mouseX, mouseY, pmouseX, pmouseY, mouseButton, key, keyCode, width, height, focused -> frame_count,
//   mouse_x, mouse_y, pmouse_x, pmouse_y, mouse_button (MouseButton::left ...), key, key_code (Key::up ...), width,
//   height, focused;
//   the variables mousePressed and keyPressed -> mouse_is_pressed and key_is_pressed (the callbacks keep the names);
//   size(w, h), size(w, h, P3D) -> size(w, h), size(w, h, Renderer::p3d); frameRate(fps) -> frame_rate(fps);
//   millis, noLoop, loop, redraw, exit -> millis, no_loop, loop, redraw, exit; saveFrame("frame-####.png") ->
//   save_frame("frame-####.png"); random(hi), random(lo, hi), randomSeed -> random, random_seed;
//   noise(x, y, z), noiseSeed, noiseDetail -> noise, noise_seed, noise_detail (math/noise.hpp's ProcessingNoise: the
//   values of Processing's noise() for the same seed);
//   the drawing calls (background, fill, stroke, rect, ellipse, beginShape, pushMatrix, translate, colorMode, color,
//   text, textSize, textAlign, textWidth, image, ...) -> the Canvas's names (canvas.hpp: background, fill, stroke,
//   rect, ellipse, begin_shape, push_matrix, translate, color_mode, color, text, text_size, text_align, text_width,
//   image, ...), forwarded with all their overloads; canvas() is the Canvas itself.
// In 3D (size(w, h, Renderer::p3d)) the sketch draws with the notes' gt functions (raster3d/gt.hpp) on a
// raster3d::Context that is current whenever the runner calls the sketch; the runner presents each frame by swapping
// the context's buffers after draw() (double buffering: the window shows the front buffer while draw() paints the
// back), so draw() does not call gtSwapBuffers itself.
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "tessera/core/rng.hpp"
#include "tessera/image/image.hpp"
#include "tessera/math/noise.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/sketch/input.hpp"

namespace tessera {

namespace glsl {
class ProgramFiles;  // a program from shader files (tessera/glsl/program_files.hpp)
}

/// What size() draws with: the 2D Canvas (Processing's default renderer) or the 3D gt context (P3D).
enum class Renderer { p2d, p3d };

namespace detail {
struct SketchAccess;  // the runner's access to a sketch's private state (src/sketch_access.hpp)
}

/// A Processing-style sketch. The public variables are Processing's: the runner writes them before each callback,
/// the sketch reads them.
class Sketch {
 public:
  Sketch();
  virtual ~Sketch();
  Sketch(const Sketch&) = delete;
  Sketch& operator=(const Sketch&) = delete;

  // ---- What a sketch overrides (each does nothing by default) -----------------------------------------------------
  /// Runs once before the first frame, with frame_count 0. Call size() here (else the sketch is 100 x 100, 2D).
  virtual void setup() {}
  /// Draws one frame: every frame while looping, once per redraw() after no_loop().
  virtual void draw() {}
  /// A mouse button went down (mouse_button says which); mouse_x/mouse_y are where.
  virtual void mouse_pressed() {}
  /// A mouse button went up.
  virtual void mouse_released() {}
  /// The mouse moved with a button down.
  virtual void mouse_dragged() {}
  /// The mouse moved with no button down.
  virtual void mouse_moved() {}
  /// The wheel turned: `delta` is Processing's count, positive when scrolling down (toward the user).
  virtual void mouse_wheel(double delta) { static_cast<void>(delta); }
  /// A key went down (key, key_code).
  virtual void key_pressed() {}
  /// A key went up.
  virtual void key_released() {}
  /// The window's drawable size changed to window_width x window_height (the sketch keeps width x height).
  virtual void window_resized() {}

  // ---- Processing's variables (written by the runner) -------------------------------------------------------------
  int frame_count = 0;                           ///< frames drawn so far; 1 during the first draw(), 0 in setup()
  int mouse_x = 0, mouse_y = 0;                  ///< the pointer in sketch pixels
  int pmouse_x = 0, pmouse_y = 0;                ///< in draw(): at the previous frame; in a callback: the last event
  bool mouse_is_pressed = false;                 ///< a mouse button is down (Processing's mousePressed variable)
  MouseButton mouse_button = MouseButton::none;  ///< the button of the last press or release
  int key = 0;                                   ///< the last key's character, or Key::coded
  int key_code = 0;                              ///< the last key's code (Key::up, ...; the upper-case letter)
  bool key_is_pressed = false;                   ///< a key is down (Processing's keyPressed variable)
  int width = 100, height = 100;                 ///< the sketch's size in pixels
  int window_width = 0, window_height = 0;       ///< the window's drawable size in pixels (0 when headless)
  bool focused = true;                           ///< the window has the keyboard focus

  // ---- Setting up, time and the loop ------------------------------------------------------------------------------
  /// The sketch's size and renderer: p2d a Canvas (Processing's gray 204 background), p3d a raster3d::Context
  /// (cleared black) made current for the gt functions. The runner's --size replaces (w, h). Throws InvalidInput
  /// for a size < 1 or over 16384.
  void size(int w, int h, Renderer renderer = Renderer::p2d);
  /// The renderer size() chose.
  Renderer renderer() const { return renderer_; }
  /// The target frame rate (Processing's default 60). The runner's --fps replaces it: then the sketch's calls are
  /// checked but change nothing. Throws InvalidInput unless 0 < fps <= 1000.
  void frame_rate(double fps);
  /// The target frame rate in frames per second.
  double frame_rate() const { return fps_; }
  /// Milliseconds since setup() began: wall time in a window; headless, the frames' time at the frame rate(s)
  /// (0 during setup() and the first draw(), 1000 / fps more each frame), so a headless run is deterministic.
  int64_t millis() const;
  /// Stops calling draw() every frame (events are still delivered; redraw() draws once more).
  void no_loop() { looping_ = false; }
  /// Calls draw() every frame again.
  void loop() { looping_ = true; }
  /// Calls draw() once more at the next frame, also after no_loop().
  void redraw() { redraw_ = true; }
  /// Whether draw() runs every frame.
  bool is_looping() const { return looping_; }
  /// Ends the run after the current frame (Processing's exit()).
  void exit() { exit_ = true; }
  /// Writes the picture drawn so far (what the frame shows when called at the end of draw()) to `pattern` with its
  /// run of '#' replaced by frame_count, zero-padded to the run's length ("frame-####.png" -> frame-0012.png); the
  /// format follows the extension (write_image). Throws IoError / InvalidInput as write_image.
  void save_frame(const std::string& pattern = "screen-####.png");

  // ---- Random numbers ---------------------------------------------------------------------------------------------
  /// A uniform number in [0, hi), from the sketch's generator (PCG32; seeded by the runner's --seed).
  double random(double hi) { return random(0, hi); }
  /// A uniform number in [lo, hi).
  double random(double lo, double hi) { return rng_.uniform(lo, hi); }
  /// Restarts the generator from `seed` (the same seed, the same numbers).
  void random_seed(uint64_t seed) { rng_ = Rng(0, seed); }
  /// Processing's noise(x, y, z): smooth noise in [0, 1) (ProcessingNoise; seeded by the runner's --seed).
  float noise(double x, double y = 0, double z = 0) const { return noise_.noise(float(x), float(y), float(z)); }
  /// noiseSeed(seed): the values Processing's noise() gives after noiseSeed(seed).
  void noise_seed(int64_t seed) { noise_.noise_seed(seed); }
  /// noiseDetail(octaves) and noiseDetail(octaves, falloff).
  void noise_detail(int octaves) { noise_.noise_detail(octaves); }
  void noise_detail(int octaves, double falloff) { noise_.noise_detail(octaves, falloff); }

  // ---- The pictures -----------------------------------------------------------------------------------------------
  /// The 2D canvas. Throws InvalidInput in a 3D sketch.
  Canvas& canvas();
  /// The 3D context (current for the gt functions while the runner calls the sketch). Throws InvalidInput in a 2D
  /// sketch.
  raster3d::Context& context();
  /// The picture drawn so far, 8-bit (2D: the canvas; 3D: the back buffer, after drawing what is pending).
  ImageRGBA8 picture();

  // ---- GLSL programs (3D sketches; docs/shaders.md) -----------------------------------------------------------------
  /// Processing's loadShader(fragment, vertex): a GLSL program from two files. Throws as glsl::ProgramFiles (a
  /// compile error names the file and line).
  std::shared_ptr<glsl::ProgramFiles> load_shader(const std::string& fragment, const std::string& vertex);
  /// Processing's shader(s): the 3D triangles drawn after it go through the program, its built-ins from the gt
  /// context's state. Each call first compiles the files again if they changed on disk (live editing: call it in
  /// draw()); a broken edit keeps the last good program and prints its error once. Throws InvalidInput in a 2D
  /// sketch.
  void shader(const std::shared_ptr<glsl::ProgramFiles>& program);
  /// Processing's resetShader(): the fixed function again.
  void reset_shader();

  // ---- Drawing: Processing's calls, forwarded to the Canvas (canvas.hpp documents each, with every overload) -------
  // Each throws InvalidInput in a 3D sketch, as canvas().
#define TESSERA_SKETCH_FORWARD(name)                   \
  template <class... Args>                             \
  decltype(auto) name(Args&&... args) {                \
    return canvas().name(std::forward<Args>(args)...); \
  }
  TESSERA_SKETCH_FORWARD(background)
  TESSERA_SKETCH_FORWARD(fill)
  TESSERA_SKETCH_FORWARD(no_fill)
  TESSERA_SKETCH_FORWARD(stroke)
  TESSERA_SKETCH_FORWARD(no_stroke)
  TESSERA_SKETCH_FORWARD(stroke_weight)
  TESSERA_SKETCH_FORWARD(stroke_join)
  TESSERA_SKETCH_FORWARD(stroke_cap)
  TESSERA_SKETCH_FORWARD(smooth)
  TESSERA_SKETCH_FORWARD(no_smooth)
  TESSERA_SKETCH_FORWARD(point)
  TESSERA_SKETCH_FORWARD(line)
  TESSERA_SKETCH_FORWARD(rect)
  TESSERA_SKETCH_FORWARD(ellipse)
  TESSERA_SKETCH_FORWARD(arc)
  TESSERA_SKETCH_FORWARD(triangle)
  TESSERA_SKETCH_FORWARD(quad)
  TESSERA_SKETCH_FORWARD(begin_shape)
  TESSERA_SKETCH_FORWARD(vertex)
  TESSERA_SKETCH_FORWARD(bezier_vertex)
  TESSERA_SKETCH_FORWARD(quadratic_vertex)
  TESSERA_SKETCH_FORWARD(begin_contour)
  TESSERA_SKETCH_FORWARD(end_contour)
  TESSERA_SKETCH_FORWARD(end_shape)
  TESSERA_SKETCH_FORWARD(push_matrix)
  TESSERA_SKETCH_FORWARD(pop_matrix)
  TESSERA_SKETCH_FORWARD(translate)
  TESSERA_SKETCH_FORWARD(rotate)
  TESSERA_SKETCH_FORWARD(scale)
  TESSERA_SKETCH_FORWARD(shear_x)
  TESSERA_SKETCH_FORWARD(shear_y)
  TESSERA_SKETCH_FORWARD(apply_matrix)
  TESSERA_SKETCH_FORWARD(reset_matrix)
  TESSERA_SKETCH_FORWARD(color_mode)
  TESSERA_SKETCH_FORWARD(color)
  TESSERA_SKETCH_FORWARD(text)
  TESSERA_SKETCH_FORWARD(text_size)
  TESSERA_SKETCH_FORWARD(text_align)
  TESSERA_SKETCH_FORWARD(text_width)
  TESSERA_SKETCH_FORWARD(text_ascent)
  TESSERA_SKETCH_FORWARD(text_descent)
  TESSERA_SKETCH_FORWARD(text_leading)
  TESSERA_SKETCH_FORWARD(image)
#undef TESSERA_SKETCH_FORWARD

 private:
  friend struct detail::SketchAccess;

  Renderer renderer_ = Renderer::p2d;
  std::optional<Canvas> canvas_;
  std::unique_ptr<raster3d::Context> context_;
  std::optional<std::pair<int, int>> size_override_;  // the runner's --size
  double fps_ = 60;
  bool fps_fixed_ = false;  // the runner's --fps is in force
  bool looping_ = true, redraw_ = true, exit_ = false;
  // Time: headless, the frames' time summed at their frame rates; in a window, the clock since setup() began.
  bool wall_clock_ = false;
  double frame_time_ms_ = 0;
  std::chrono::steady_clock::time_point start_;
  Rng rng_;
  ProcessingNoise noise_;
  // Processing's three mouse positions: the last event's (pmouse in callbacks) and the last frame's (pmouse in draw).
  int event_mouse_x_ = 0, event_mouse_y_ = 0, frame_mouse_x_ = 0, frame_mouse_y_ = 0;
  int buttons_down_ = 0, keys_down_ = 0;
};

}  // namespace tessera
