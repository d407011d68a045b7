#pragma once
// The built-in sketches' factories (one source each under src/sketches/), listed in src/registry.cpp's table.
#include <memory>
#include <string_view>

#include "tessera/sketch/sketch.hpp"

namespace tessera::sketches {

std::unique_ptr<Sketch> make_pink_square();
extern const std::string_view kPinkSquareDemo;  // pink_square's demo input
std::unique_ptr<Sketch> make_rotating_cube();
std::unique_ptr<Sketch> make_bezier();
extern const std::string_view kBezierDemo;  // bezier's demo input
std::unique_ptr<Sketch> make_body();
std::unique_ptr<Sketch> make_mandelbrot_zoom();
std::unique_ptr<Sketch> make_marching_squares();
extern const std::string_view kMarchingSquaresDemo;  // marching_squares' demo input
std::unique_ptr<Sketch> make_noise_hills();
extern const std::string_view kNoiseHillsDemo;  // noise_hills' demo input
std::unique_ptr<Sketch> make_transformations();
std::unique_ptr<Sketch> make_bouncing_balls();
extern const std::string_view kBouncingBallsDemo;  // bouncing_balls' demo input

}  // namespace tessera::sketches
