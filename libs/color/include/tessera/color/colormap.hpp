#pragma once
// Color ramps for visualizing scalar quantities (traversal cost, error maps).
#include "tessera/math/types.hpp"

namespace tessera {

/// The blue-cyan-green-yellow-red "jet" heat ramp: x in [0, 1] (clamped) to RGB in [0, 1]^3, each channel the tent
/// clamp(1.5 - |4x - c|, 0, 1) with c = 3, 2, 1 for red, green, blue: 0 -> (0, 0, 0.5), 0.5 -> (0.5, 1, 0.5), 1 ->
/// (0.5, 0, 0).
Vec3f heat_color(float x);

}  // namespace tessera
