#include "tessera/sketch/registry.hpp"

#include <algorithm>
#include <array>

#include "sketches/sketches.hpp"

namespace tessera {
namespace {

// Sorted by name (find_sketch searches it; --list prints it in this order).
const std::array kSketches = {
    SketchInfo{"bezier", "The notes' cubic Bezier curve with draggable control points and de Casteljau's construction",
               sketches::make_bezier, sketches::kBezierDemo, 120},
    SketchInfo{"body",
               "The notes' body hierarchy (torso, arms of extent + hand) waving, angles from frame_count",
               sketches::make_body,
               {},
               60},
    SketchInfo{"bouncing_balls",
               "A demo of random() and colorMode(HSB): balls bouncing under gravity (a press drops one more)",
               sketches::make_bouncing_balls, sketches::kBouncingBallsDemo, 150},
    SketchInfo{"mandelbrot_zoom",
               "A smooth exponential zoom into the Mandelbrot set's seahorse valley (click recenters)",
               sketches::make_mandelbrot_zoom,
               {},
               240},
    SketchInfo{"marching_squares",
               "The notes' marching squares: contours of a field, the iso value following the mouse's x",
               sketches::make_marching_squares, sketches::kMarchingSquaresDemo, 120},
    SketchInfo{"noise_hills",
               "Processing's noise(): three ridges of Perlin-noise hills scrolling with parallax (mouse x: speed)",
               sketches::make_noise_hills, sketches::kNoiseHillsDemo, 120},
    SketchInfo{"pink_square", "The notes' pink (255, 150, 150) square following the mouse (2D; s: outline)",
               sketches::make_pink_square, sketches::kPinkSquareDemo, 60},
    SketchInfo{"rotating_cube",
               "A cube with colored faces turning in 3D, double buffered (space pauses)",
               sketches::make_rotating_cube,
               {},
               60},
    SketchInfo{"transformations",
               "The notes' 2D transformations animated: translate, rotate about a pivot, scale, shear",
               sketches::make_transformations,
               {},
               90},
};

}  // namespace

std::span<const SketchInfo> builtin_sketches() { return kSketches; }

const SketchInfo* find_sketch(std::string_view name) {
  const auto it = std::find_if(kSketches.begin(), kSketches.end(), [&](const SketchInfo& s) { return s.name == name; });
  return it == kSketches.end() ? nullptr : &*it;
}

}  // namespace tessera
