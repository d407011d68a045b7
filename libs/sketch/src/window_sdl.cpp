// The runner's window through SDL2: the sketch's CPU frame streamed to a texture, drawn scaled to fit (letterboxed)
// with nearest-pixel sampling, presented at the vertical sync. SDL's logical size maps window coordinates, HiDPI
// scale included, back to sketch pixels for the mouse events.
#include <SDL.h>
#include <fmt/format.h>

#include <cctype>
#include <cstdlib>

#include "tessera/core/error.hpp"
#include "tessera/sketch/runner.hpp"
#include "window.hpp"

namespace tessera {

bool window_supported() { return true; }

namespace detail {
namespace {

std::string sdl_error(const char* what) { return fmt::format("{} ({})", what, SDL_GetError()); }

MouseButton button_of(Uint8 button) {
  switch (button) {
    case SDL_BUTTON_LEFT:
      return MouseButton::left;
    case SDL_BUTTON_RIGHT:
      return MouseButton::right;
    case SDL_BUTTON_MIDDLE:
      return MouseButton::center;
    default:
      return MouseButton::none;
  }
}

/// Processing's key and keyCode of an SDL key; false for keys Processing does not report.
bool key_of(const SDL_Keysym& k, int& key, int& key_code) {
  const auto coded = [&](int code) {
    key = Key::coded;
    key_code = code;
    return true;
  };
  const auto plain = [&](int c) {
    key = key_code = c;
    return true;
  };
  switch (k.sym) {
    case SDLK_UP:
      return coded(Key::up);
    case SDLK_DOWN:
      return coded(Key::down);
    case SDLK_LEFT:
      return coded(Key::left);
    case SDLK_RIGHT:
      return coded(Key::right);
    case SDLK_LSHIFT:
    case SDLK_RSHIFT:
      return coded(Key::shift);
    case SDLK_LCTRL:
    case SDLK_RCTRL:
      return coded(Key::control);
    case SDLK_LALT:
    case SDLK_RALT:
      return coded(Key::alt);
    case SDLK_RETURN:
    case SDLK_KP_ENTER:
      return plain(Key::enter);
    case SDLK_TAB:
      return plain(Key::tab);
    case SDLK_BACKSPACE:
      return plain(Key::backspace);
    case SDLK_ESCAPE:
      return plain(Key::escape);
    case SDLK_DELETE:
      return plain(Key::delete_key);
    default:
      break;
  }
  if (k.sym < 32 || k.sym > 126) return false;
  // SDL names the unshifted key; a letter with Shift (or Caps Lock) is its capital, as Processing's key.
  const bool upper = ((k.mod & KMOD_SHIFT) != 0) != ((k.mod & KMOD_CAPS) != 0);
  key = upper ? std::toupper(k.sym) : k.sym;
  key_code = std::toupper(k.sym);
  return true;
}

class SdlWindow final : public Window {
 public:
  SdlWindow(const std::string& title, int width, int height) : width_(width), height_(height) {
    // Tessera handles SIGINT and SIGTERM itself (no partial output files): SDL must not turn them into SDL_QUIT.
    SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
    // Without X11 or Wayland SDL falls back to its offscreen driver, whose windows nobody sees: that is no display,
    // unless SDL_VIDEODRIVER asks for it.
    const bool chosen = std::getenv("SDL_VIDEODRIVER") != nullptr;
    if (!chosen && !std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) no_display("DISPLAY is not set");
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) no_display(SDL_GetError());
    const std::string driver = SDL_GetCurrentVideoDriver();
    if (!chosen && (driver == "offscreen" || driver == "dummy")) {
      SDL_QuitSubSystem(SDL_INIT_VIDEO);
      no_display("only SDL's offscreen driver is available");
    }
    window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width, height,
                               SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI);
    if (!window_) fail("cannot open a window");
    // Nearest-pixel scaling: at 1:1 the window shows the frame's exact bytes.
    SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "nearest");
    renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_PRESENTVSYNC);
    if (!renderer_) renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
    if (!renderer_) fail("cannot create a renderer for the window");
    // The sketch keeps its size: SDL scales it to fit the window, letterboxed, and maps mouse positions back.
    if (SDL_RenderSetLogicalSize(renderer_, width, height) != 0) fail("cannot set the window's logical size");
    texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING, width, height);
    if (!texture_) fail("cannot create the window's texture");
    SDL_SetTextureBlendMode(texture_, SDL_BLENDMODE_NONE);
  }

  ~SdlWindow() override { release(); }

  bool poll(std::vector<InputEvent>& events) override {
    SDL_Event e;
    bool open = true;
    while (SDL_PollEvent(&e)) {
      InputEvent out;
      switch (e.type) {
        case SDL_QUIT:
          open = false;
          break;
        case SDL_WINDOWEVENT:
          if (e.window.event == SDL_WINDOWEVENT_CLOSE) open = false;
          if (e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
            out.kind = InputKind::window_resize;
            SDL_GetRendererOutputSize(renderer_, &out.x, &out.y);  // drawable pixels (HiDPI)
            events.push_back(out);
          }
          if (e.window.event == SDL_WINDOWEVENT_FOCUS_LOST) events.push_back({.kind = InputKind::focus_lost});
          if (e.window.event == SDL_WINDOWEVENT_FOCUS_GAINED) events.push_back({.kind = InputKind::focus_gained});
          break;
        case SDL_MOUSEMOTION:
          move(events, e.motion.x, e.motion.y);
          break;
        case SDL_MOUSEBUTTONDOWN:
        case SDL_MOUSEBUTTONUP:
          move(events, e.button.x, e.button.y);  // a press can come without a motion (focus clicks)
          out.kind = e.type == SDL_MOUSEBUTTONDOWN ? InputKind::mouse_press : InputKind::mouse_release;
          out.button = button_of(e.button.button);
          events.push_back(out);
          break;
        case SDL_MOUSEWHEEL:
          // Processing's count is positive toward the user; SDL's y is positive away from the user.
          out.kind = InputKind::mouse_wheel;
          out.wheel = e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? e.wheel.preciseY : -e.wheel.preciseY;
          events.push_back(out);
          break;
        case SDL_KEYDOWN:
        case SDL_KEYUP:
          if (e.key.repeat) break;  // one key_pressed() per press (key_is_pressed stays true while held)
          out.kind = e.type == SDL_KEYDOWN ? InputKind::key_press : InputKind::key_release;
          if (key_of(e.key.keysym, out.key, out.key_code)) events.push_back(out);
          break;
        default:
          break;
      }
    }
    return open;
  }

  std::pair<int, int> drawable_size() const override {
    int w = 0, h = 0;
    SDL_GetRendererOutputSize(renderer_, &w, &h);
    return {w, h};
  }

  void present(const ImageRGBA8& frame) override {
    if (frame.width() != width_ || frame.height() != height_) throw InternalError("the sketch changed size mid-run");
    SDL_UpdateTexture(texture_, nullptr, frame.row(0), width_ * 4);
    SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);  // the letterbox bars
    SDL_RenderClear(renderer_);
    SDL_RenderCopy(renderer_, texture_, nullptr, nullptr);
    SDL_RenderPresent(renderer_);
  }

 private:
  // The pointer moved to (x, y) in sketch pixels (SDL's logical coordinates); presses repeat the last position.
  void move(std::vector<InputEvent>& events, int x, int y) {
    if (has_pointer_ && x == pointer_x_ && y == pointer_y_) return;
    has_pointer_ = true;
    pointer_x_ = x;
    pointer_y_ = y;
    events.push_back({.kind = InputKind::mouse_move, .x = x, .y = y});
  }
  [[noreturn]] static void no_display(const std::string& why) {
    throw Error(fmt::format("no display to open a window on ({}); run with --headless to render without one", why));
  }
  [[noreturn]] void fail(const char* what) {
    const std::string message = sdl_error(what);
    release();
    throw Error(message);
  }
  void release() {
    if (texture_) SDL_DestroyTexture(texture_);
    if (renderer_) SDL_DestroyRenderer(renderer_);
    if (window_) SDL_DestroyWindow(window_);
    texture_ = nullptr;
    renderer_ = nullptr;
    window_ = nullptr;
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
  }

  int width_, height_;
  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  SDL_Texture* texture_ = nullptr;
  bool has_pointer_ = false;
  int pointer_x_ = 0, pointer_y_ = 0;
};

}  // namespace

std::unique_ptr<Window> open_window(const std::string& title, int width, int height) {
  return std::make_unique<SdlWindow>(title, width, height);
}

}  // namespace detail
}  // namespace tessera
