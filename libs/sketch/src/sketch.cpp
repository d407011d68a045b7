#include "tessera/sketch/sketch.hpp"

#include <fmt/format.h>

#include <cmath>

#include "sketch_access.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/glsl/program_files.hpp"
#include "tessera/image/animation.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster3d/gt.hpp"

namespace tessera {

Sketch::Sketch() = default;

Sketch::~Sketch() { detail::SketchAccess::end(*this); }

void Sketch::size(int w, int h, Renderer renderer) {
  if (size_override_) std::tie(w, h) = *size_override_;
  constexpr int kLargest = 16384;
  if (w < 1 || h < 1 || w > kLargest || h > kLargest)
    throw InvalidInput(fmt::format("size({}, {}): each side must be 1 to {} pixels", w, h, kLargest));
  width = w;
  height = h;
  renderer_ = renderer;
  if (renderer == Renderer::p2d) {
    canvas_.emplace(w, h);
    if (context_ && gt::detail::current_context == context_.get()) gt::gtMakeCurrent(nullptr);
    context_.reset();
  } else {
    // Back and front color (4 bytes each), depth (4) and stencil (1) a pixel; the Canvas checks its own size.
    MemoryBudget::check(saturating_product({uint64_t(w), uint64_t(h), 13}), fmt::format("a {}x{} 3D sketch", w, h));
    canvas_.reset();
    context_ = std::make_unique<raster3d::Context>(w, h);
    gt::gtMakeCurrent(context_.get());
  }
}

void Sketch::frame_rate(double fps) {
  if (!(fps > 0 && fps <= 1000)) throw InvalidInput(fmt::format("frame_rate({}): expected 0 < fps <= 1000", fps));
  if (!fps_fixed_) fps_ = fps;
}

int64_t Sketch::millis() const {
  if (wall_clock_)
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start_).count();
  return int64_t(std::floor(frame_time_ms_));
}

void Sketch::save_frame(const std::string& pattern) {
  write_image(numbered_frame_path(pattern, frame_count), picture());
}

Canvas& Sketch::canvas() {
  if (!canvas_)
    throw InvalidInput("a 2D drawing call in a 3D sketch (size(w, h, Renderer::p3d) draws with the gt functions)");
  return *canvas_;
}

raster3d::Context& Sketch::context() {
  if (!context_) throw InvalidInput("context() in a 2D sketch (call size(w, h, Renderer::p3d) for the 3D context)");
  return *context_;
}

std::shared_ptr<glsl::ProgramFiles> Sketch::load_shader(const std::string& fragment, const std::string& vertex) {
  return std::make_shared<glsl::ProgramFiles>(vertex, fragment);
}

void Sketch::shader(const std::shared_ptr<glsl::ProgramFiles>& program) {
  raster3d::Context& ctx = context();
  if (program->reload() && !program->error().empty())
    fmt::print(stderr, "tessera: shader {}: {} (the last good program draws)\n", program->name(), program->error());
  ctx.use_program(program->program());
}

void Sketch::reset_shader() { context().use_program(nullptr); }

ImageRGBA8 Sketch::picture() {
  if (context_) return context_->framebuffer().color();
  return to_rgba8(canvas().image());
}

namespace detail {

void SketchAccess::begin(Sketch& s, uint64_t seed, std::optional<std::pair<int, int>> size_override, bool wall_clock) {
  s.random_seed(seed);
  s.noise_ = ProcessingNoise(int64_t(seed));
  s.size_override_ = size_override;
  s.wall_clock_ = wall_clock;
  s.start_ = std::chrono::steady_clock::now();
  s.frame_time_ms_ = 0;
  s.frame_count = 0;
  s.looping_ = s.redraw_ = true;
  s.exit_ = false;
  s.fps_ = 60;
  s.fps_fixed_ = false;
  s.size(100, 100);
}

void SketchAccess::setup(Sketch& s) {
  if (s.context_) gt::gtMakeCurrent(s.context_.get());
  s.setup();
}

void SketchAccess::draw(Sketch& s) {
  if (s.context_) gt::gtMakeCurrent(s.context_.get());
  s.redraw_ = false;
  ++s.frame_count;
  s.pmouse_x = s.frame_mouse_x_;
  s.pmouse_y = s.frame_mouse_y_;
  s.draw();
  s.frame_mouse_x_ = s.mouse_x;
  s.frame_mouse_y_ = s.mouse_y;
  if (s.context_) s.context_->swap_buffers();
}

void SketchAccess::deliver(Sketch& s, const InputEvent& e) {
  if (s.context_) gt::gtMakeCurrent(s.context_.get());
  // A move, press or release moves the pointer first (a press may come without a move, e.g. on gaining focus).
  const auto move_to = [&](int x, int y) {
    s.pmouse_x = s.event_mouse_x_;
    s.pmouse_y = s.event_mouse_y_;
    s.mouse_x = x;
    s.mouse_y = y;
  };
  switch (e.kind) {
    case InputKind::mouse_move:
      move_to(e.x, e.y);
      s.buttons_down_ > 0 ? s.mouse_dragged() : s.mouse_moved();
      break;
    case InputKind::mouse_press:
      move_to(s.mouse_x, s.mouse_y);
      ++s.buttons_down_;
      s.mouse_is_pressed = true;
      s.mouse_button = e.button;
      s.mouse_pressed();
      break;
    case InputKind::mouse_release:
      s.buttons_down_ = std::max(0, s.buttons_down_ - 1);
      s.mouse_is_pressed = s.buttons_down_ > 0;
      s.mouse_button = e.button;
      s.mouse_released();
      break;
    case InputKind::mouse_wheel:
      s.mouse_wheel(e.wheel);
      break;
    case InputKind::key_press:
      ++s.keys_down_;
      s.key = e.key;
      s.key_code = e.key_code;
      s.key_is_pressed = true;
      s.key_pressed();
      break;
    case InputKind::key_release:
      s.keys_down_ = std::max(0, s.keys_down_ - 1);
      s.key = e.key;
      s.key_code = e.key_code;
      s.key_is_pressed = s.keys_down_ > 0;
      s.key_released();
      break;
    case InputKind::window_resize:
      s.window_width = e.x;
      s.window_height = e.y;
      s.window_resized();
      break;
    case InputKind::focus_lost:
      // Keys and buttons released while another window had the focus never reach the sketch: forget them.
      s.focused = false;
      s.keys_down_ = s.buttons_down_ = 0;
      s.key_is_pressed = s.mouse_is_pressed = false;
      break;
    case InputKind::focus_gained:
      s.focused = true;
      break;
  }
  s.event_mouse_x_ = s.mouse_x;
  s.event_mouse_y_ = s.mouse_y;
}

const ImageRGBA8& SketchAccess::shown(Sketch& s, bool srgb, ImageRGBA8& scratch) {
  if (s.context_) {
    const ImageRGBA8& front = s.context_->framebuffer().front();
    if (!srgb) return front;
    scratch = to_rgba8(to_float(front), true);
  } else {
    scratch = to_rgba8(s.canvas().image(), srgb);
  }
  return scratch;
}

void SketchAccess::end(Sketch& s) {
  if (s.context_ && gt::detail::current_context == s.context_.get()) gt::gtMakeCurrent(nullptr);
}

}  // namespace detail
}  // namespace tessera
