#pragma once
// The built-in sketches: the notes' Processing programs that move or react, and a few demos (`tessera sketch --list`).
// Each lives in libs/sketch/src/sketches/<name>.cpp and has one row in the table of src/registry.cpp.
#include <functional>
#include <memory>
#include <span>
#include <string_view>

#include "tessera/sketch/sketch.hpp"

namespace tessera {

/// Makes a fresh sketch (the runner needs a new one for each run).
using SketchFactory = std::function<std::unique_ptr<Sketch>()>;

/// One built-in sketch.
struct SketchInfo {
  std::string_view name;              ///< what `tessera sketch NAME` takes (lower_case)
  std::string_view description;       ///< one line for --list
  std::unique_ptr<Sketch> (*make)();  ///< a fresh instance
  /// An input script (input.hpp's format) that shows the sketch off in a headless recording (`--demo`, the gallery
  /// animation): the mouse moving, keys pressed. Empty when the sketch needs no input.
  std::string_view demo_input = {};
  /// How many frames the demo recording draws.
  int demo_frames = 60;
};

/// Every built-in sketch, sorted by name.
std::span<const SketchInfo> builtin_sketches();
/// The built-in sketch called `name`, or null.
const SketchInfo* find_sketch(std::string_view name);

}  // namespace tessera
