#pragma once
// Input events, as the window delivers them and as an input script writes them (docs/sketch.md, "Input scripts").
//
// A script is a text file of one event per line, `FRAME EVENT ARGS...`, delivered before the draw() of frame FRAME
// (1 is the first draw; the frame of the run, which is frame_count while the sketch loops). `#` starts a comment:
//
//   12 mouse_move 100 80        # the pointer moves to (100, 80) in sketch pixels
//   12 mouse_press left         # a button goes down where the pointer is (left, right or center)
//   14 mouse_release left
//   20 mouse_wheel 3            # Processing's count: positive scrolls down, toward the user
//   30 key_press a              # a character, or a name: space enter tab backspace escape delete up down left
//   31 key_release a            #   right shift control alt
//   40 window_resize 800 600    # the window's new drawable size (the sketch keeps its size)
//   41 focus_lost               # and focus_gained
#include <filesystem>
#include <string_view>
#include <vector>

namespace tessera {

/// Processing's mouseButton values.
enum class MouseButton { none, left, right, center };

/// Processing's key constants: `key` holds the character typed, or Key::coded for a key without one (then `key_code`
/// says which: Key::up, Key::shift, ...). For a character key, `key_code` is its Java virtual-key code, as Processing's
/// (the upper-case letter or the digit).
struct Key {
  enum : int {
    coded = 0xFFFF,
    backspace = 8,
    tab = 9,
    enter = 10,
    escape = 27,
    delete_key = 127,
    shift = 16,
    control = 17,
    alt = 18,
    left = 37,
    up = 38,
    right = 39,
    down = 40,
  };
};

/// What happened.
enum class InputKind {
  mouse_move,
  mouse_press,
  mouse_release,
  mouse_wheel,
  key_press,
  key_release,
  window_resize,
  focus_lost,
  focus_gained
};

/// One input event. Only the fields of its kind are meaningful.
struct InputEvent {
  int frame = 1;                           ///< delivered before the draw() of this frame of the run (scripts)
  InputKind kind = InputKind::mouse_move;  ///< what happened
  int x = 0, y = 0;                        ///< mouse_move: sketch pixels; window_resize: drawable pixels
  MouseButton button = MouseButton::none;  ///< mouse_press, mouse_release
  double wheel = 0;                        ///< mouse_wheel: Processing's count (positive: toward the user)
  int key = 0;                             ///< key_press, key_release: the character, or Key::coded
  int key_code = 0;                        ///< key_press, key_release: Processing's keyCode
};

/// The `key` and `key_code` of a key named as in a script: one character ("a", "7", "?"), or a name (space, enter,
/// tab, backspace, escape, delete, up, down, left, right, shift, control, alt). Returns false for anything else.
bool key_from_name(std::string_view name, int& key, int& key_code);

/// Parses an input script (format above), sorted by frame (events of one frame keep their order). Throws
/// InvalidInput naming `name` and the line for a malformed line (unknown event, missing or extra arguments, a frame
/// < 1).
std::vector<InputEvent> parse_input_script(std::string_view text, std::string_view name = "input script");
/// Reads and parses an input script file. Throws IoError when it cannot be read, InvalidInput as parse_input_script.
std::vector<InputEvent> read_input_script(const std::filesystem::path& path);

}  // namespace tessera
