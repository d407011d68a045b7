#pragma once
// The runner's window (private): src/window_sdl.cpp with SDL2, src/window_none.cpp without.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/sketch/input.hpp"

namespace tessera::detail {

/// A window showing a sketch's frames.
class Window {
 public:
  virtual ~Window() = default;
  /// Appends the input events since the last call (mouse positions in sketch pixels, window sizes in drawable
  /// pixels). Returns false once the window was closed.
  virtual bool poll(std::vector<InputEvent>& events) = 0;
  /// Shows `frame` (the sketch's size) scaled to fit the window, letterboxed, at the next vertical sync.
  virtual void present(const ImageRGBA8& frame) = 0;
  /// The window's drawable size in pixels (HiDPI: more than its size in points).
  virtual std::pair<int, int> drawable_size() const = 0;
};

/// Opens a window for a width x height sketch. Throws Error when there is no display (suggesting --headless) or the
/// build has no SDL2.
std::unique_ptr<Window> open_window(const std::string& title, int width, int height);

}  // namespace tessera::detail
