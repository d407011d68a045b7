// The window of a build without SDL2: none.
#include "tessera/core/error.hpp"
#include "tessera/sketch/runner.hpp"
#include "window.hpp"

namespace tessera {

bool window_supported() { return false; }

namespace detail {
std::unique_ptr<Window> open_window(const std::string&, int, int) {
  throw Error(
      "this Tessera was built without SDL2, so it cannot open a window (install libsdl2-dev and configure "
      "again); run with --headless to render without a window");
}
}  // namespace detail

}  // namespace tessera
