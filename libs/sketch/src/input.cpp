#include "tessera/sketch/input.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <string>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {
namespace {

struct NamedKey {
  std::string_view name;
  int key, key_code;
};
constexpr std::array kNamedKeys = {
    NamedKey{"space", ' ', ' '},
    NamedKey{"enter", Key::enter, Key::enter},
    NamedKey{"tab", Key::tab, Key::tab},
    NamedKey{"backspace", Key::backspace, Key::backspace},
    NamedKey{"escape", Key::escape, Key::escape},
    NamedKey{"delete", Key::delete_key, Key::delete_key},
    NamedKey{"up", Key::coded, Key::up},
    NamedKey{"down", Key::coded, Key::down},
    NamedKey{"left", Key::coded, Key::left},
    NamedKey{"right", Key::coded, Key::right},
    NamedKey{"shift", Key::coded, Key::shift},
    NamedKey{"control", Key::coded, Key::control},
    NamedKey{"alt", Key::coded, Key::alt},
};

struct NamedEvent {
  std::string_view name;
  InputKind kind;
  size_t arguments;
};
constexpr std::array kEvents = {
    NamedEvent{"mouse_move", InputKind::mouse_move, 2},       NamedEvent{"mouse_press", InputKind::mouse_press, 1},
    NamedEvent{"mouse_release", InputKind::mouse_release, 1}, NamedEvent{"mouse_wheel", InputKind::mouse_wheel, 1},
    NamedEvent{"key_press", InputKind::key_press, 1},         NamedEvent{"key_release", InputKind::key_release, 1},
    NamedEvent{"window_resize", InputKind::window_resize, 2}, NamedEvent{"focus_lost", InputKind::focus_lost, 0},
    NamedEvent{"focus_gained", InputKind::focus_gained, 0},
};

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

}  // namespace

bool key_from_name(std::string_view name, int& key, int& key_code) {
  if (name.size() == 1 && std::isgraph(static_cast<unsigned char>(name[0]))) {
    key = static_cast<unsigned char>(name[0]);
    key_code = std::toupper(key);  // Java's virtual-key code of a letter is its upper case
    return true;
  }
  for (const NamedKey& k : kNamedKeys)
    if (k.name == name) {
      key = k.key;
      key_code = k.key_code;
      return true;
    }
  return false;
}

std::vector<InputEvent> parse_input_script(std::string_view text, std::string_view name) {
  std::vector<InputEvent> events;
  int line_number = 0;
  for (std::string_view line : split(text, '\n')) {
    ++line_number;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::vector<std::string_view> w = words(line);
    if (w.empty()) continue;
    const std::string where = fmt::format("{} line {}", name, line_number);
    const auto fail = [&](std::string_view what) {
      throw InvalidInput(fmt::format("{}: {} (expected 'FRAME EVENT ARGS', e.g. '12 mouse_move 100 80')", where, what));
    };
    InputEvent e;
    const long long frame = parse_int(w[0], where + ": the frame");
    if (frame < 1 || frame > (1 << 30)) fail(fmt::format("frame {} is not between 1 and 2^30", frame));
    e.frame = int(frame);
    if (w.size() < 2) fail("no event after the frame");
    const auto event =
        std::find_if(kEvents.begin(), kEvents.end(), [&](const NamedEvent& n) { return n.name == w[1]; });
    if (event == kEvents.end())
      fail(
          fmt::format("unknown event '{}' (mouse_move, mouse_press, mouse_release, mouse_wheel, key_press, "
                      "key_release, window_resize, focus_lost, focus_gained)",
                      printable(w[1])));
    e.kind = event->kind;
    if (w.size() - 2 != event->arguments)
      fail(fmt::format("{} takes {} argument(s), got {}", event->name, event->arguments, w.size() - 2));
    const auto coordinate = [&](std::string_view t, const char* what) {
      const long long v = parse_int(t, where + ": " + what);
      if (v < -(1 << 20) || v > (1 << 20)) fail(fmt::format("{} {} is out of range", what, v));
      return int(v);
    };
    switch (e.kind) {
      case InputKind::mouse_move:
        e.x = coordinate(w[2], "x");
        e.y = coordinate(w[3], "y");
        break;
      case InputKind::window_resize:
        e.x = coordinate(w[2], "width");
        e.y = coordinate(w[3], "height");
        if (e.x < 1 || e.y < 1) fail("a window size must be positive");
        break;
      case InputKind::mouse_press:
      case InputKind::mouse_release:
        if (w[2] == "left")
          e.button = MouseButton::left;
        else if (w[2] == "right")
          e.button = MouseButton::right;
        else if (w[2] == "center")
          e.button = MouseButton::center;
        else
          fail(fmt::format("unknown button '{}' (left, right, center)", printable(w[2])));
        break;
      case InputKind::mouse_wheel:
        e.wheel = parse_double(w[2], where + ": the wheel count");
        break;
      case InputKind::key_press:
      case InputKind::key_release:
        if (!key_from_name(w[2], e.key, e.key_code))
          fail(
              fmt::format("unknown key '{}' (one character, or space enter tab backspace escape delete up down left "
                          "right shift control alt)",
                          printable(w[2])));
        break;
      case InputKind::focus_lost:
      case InputKind::focus_gained:
        break;
    }
    events.push_back(e);
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const InputEvent& a, const InputEvent& b) { return a.frame < b.frame; });
  return events;
}

std::vector<InputEvent> read_input_script(const std::filesystem::path& path) {
  return parse_input_script(read_file(path), path.string());
}

}  // namespace tessera
