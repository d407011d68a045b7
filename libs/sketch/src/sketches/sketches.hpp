#pragma once
// The built-in sketches' factories (one source each under src/sketches/), listed in src/registry.cpp's table.
#include <memory>

#include "tessera/sketch/sketch.hpp"

namespace tessera::sketches {

std::unique_ptr<Sketch> make_pink_square();
std::unique_ptr<Sketch> make_rotating_cube();

}  // namespace tessera::sketches
