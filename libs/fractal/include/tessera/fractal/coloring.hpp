#pragma once
// Coloring of escape-time pictures: the continuous ("smooth") iteration count and a few cyclic palettes.
#include <string_view>

#include "tessera/fractal/escape_time.hpp"
#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// Cyclic color ramps for escape times.
enum class Palette {
  classic,  ///< deep blue -> white -> gold -> dark (the familiar Ultra Fractal look)
  fire,     ///< black -> red -> orange -> yellow -> white
  ocean,    ///< navy -> teal -> pale cyan
  gray,     ///< black -> white
};

/// "classic", "fire", "ocean" or "gray".
std::string_view palette_name(Palette palette);
/// Parses a palette_name(); throws InvalidInput listing the names for anything else.
Palette parse_palette(std::string_view name);

/// The palette's color at t in [0, 1] (t = 0 and t = 1 give the same color: the ramps are cyclic).
Vec3f palette_color(Palette palette, double t);

/// The continuous escape count nu = n + 1 - log2(log|z_n| / log R) for a point that escaped at n with
/// |z_n|^2 = norm2 > R^2; nu is continuous across the bands of equal n (Linas Vepstas' renormalized count).
double smooth_iteration(uint32_t n, double norm2, double escape_radius);

/// How escape times become colors.
struct ColorOptions {
  Palette palette = Palette::classic;
  double period = 12;              ///< the palette repeats every `period` units of sqrt(nu) (> 0)
  double phase = 0;                ///< palette offset in [0, 1)
  Vec3f inside{0.0f, 0.0f, 0.0f};  ///< color of points that never escaped
};

/// Colors every pixel: inside points get options.inside, the others palette((sqrt(nu) / period + phase) mod 1).
/// Throws InvalidInput for a non-positive period.
ImageRGB colorize(const EscapeImage& image, const ColorOptions& options = {});

}  // namespace tessera
