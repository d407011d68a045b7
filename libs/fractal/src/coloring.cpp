#include "tessera/fractal/coloring.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"

namespace tessera {
namespace {

/// A cyclic ramp: stops at evenly spaced t, the first repeated at t = 1.
using Ramp = std::array<Vec3f, 5>;

const Ramp& ramp(Palette palette) {
  static const Ramp kClassic{Vec3f{0.0f, 0.03f, 0.39f}, Vec3f{0.13f, 0.42f, 0.80f}, Vec3f{0.93f, 1.0f, 1.0f},
                             Vec3f{1.0f, 0.67f, 0.0f}, Vec3f{0.0f, 0.01f, 0.0f}};
  static const Ramp kFire{Vec3f{0.05f, 0.0f, 0.0f}, Vec3f{0.70f, 0.05f, 0.0f}, Vec3f{1.0f, 0.55f, 0.0f},
                          Vec3f{1.0f, 0.95f, 0.45f}, Vec3f{1.0f, 1.0f, 0.95f}};
  static const Ramp kOcean{Vec3f{0.0f, 0.02f, 0.15f}, Vec3f{0.0f, 0.25f, 0.45f}, Vec3f{0.0f, 0.60f, 0.65f},
                           Vec3f{0.65f, 0.95f, 0.95f}, Vec3f{0.15f, 0.35f, 0.60f}};
  static const Ramp kGray{Vec3f{0.0f}, Vec3f{0.35f}, Vec3f{0.7f}, Vec3f{1.0f}, Vec3f{0.5f}};
  switch (palette) {
    case Palette::fire:
      return kFire;
    case Palette::ocean:
      return kOcean;
    case Palette::gray:
      return kGray;
    default:
      return kClassic;
  }
}

}  // namespace

std::string_view palette_name(Palette palette) {
  switch (palette) {
    case Palette::fire:
      return "fire";
    case Palette::ocean:
      return "ocean";
    case Palette::gray:
      return "gray";
    default:
      return "classic";
  }
}

Palette parse_palette(std::string_view name) {
  for (Palette p : {Palette::classic, Palette::fire, Palette::ocean, Palette::gray})
    if (palette_name(p) == name) return p;
  throw InvalidInput(fmt::format("unknown palette '{}' (classic, fire, ocean, gray)", name));
}

Vec3f palette_color(Palette palette, double t) {
  const Ramp& stops = ramp(palette);
  const double u = (t - std::floor(t)) * double(stops.size());
  const auto i = size_t(u) % stops.size();
  const auto f = float(u - std::floor(u));
  // Smoothstep between neighbouring stops: no visible kinks at the stops.
  const float s = f * f * (3.0f - 2.0f * f);
  return stops[i] * (1.0f - s) + stops[(i + 1) % stops.size()] * s;
}

double smooth_iteration(uint32_t n, double norm2, double escape_radius) {
  const double log_z = 0.5 * std::log(norm2);
  return double(n) + 1.0 - std::log2(log_z / std::log(escape_radius));
}

ImageRGB colorize(const EscapeImage& image, const ColorOptions& options) {
  if (!(options.period > 0)) throw InvalidInput(fmt::format("palette period must be positive, got {}", options.period));
  const int w = image.iterations.width(), h = image.iterations.height();
  ImageRGB out(w, h);
  parallel_for(0, h, 16, [&](int64_t y0, int64_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < w; ++x) {
        if (image.inside(x, y)) {
          out(x, y) = options.inside;
          continue;
        }
        const double nu = smooth_iteration(image.iterations(x, y), image.norm2(x, y), image.escape_radius);
        out(x, y) = palette_color(options.palette, std::sqrt(std::max(nu, 0.0)) / options.period + options.phase);
      }
  });
  return out;
}

}  // namespace tessera
