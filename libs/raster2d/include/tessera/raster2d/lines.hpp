#pragma once
// Lines of pixels: the notes' DDA line(), Bresenham's integer line, Xiaolin Wu's antialiased line, and the notes'
// circle() made of n line segments.
//
// These work in pixel-index coordinates, as the notes' loop does: the center of pixel (i, j) is the integer point
// (i, j), and line() writes pixel (round(x), round(y)). (The Canvas, whose pixel centers are at (i + 0.5, j + 0.5) as
// DESIGN.md says, subtracts 0.5 before calling these.) Nothing here clips: the plot callback sees every pixel the
// algorithm produces, including negative ones; draw_line() clips to the image.
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// A non-owning reference to a callable `void(int x, int y, float intensity)` (intensity in (0, 1]); cheap to pass
/// by value. The referenced callable must outlive the call it is passed to.
class PixelPlot {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, PixelPlot>>>
  PixelPlot(F&& f)  // NOLINT(google-explicit-constructor): lambdas convert implicitly, as with std::function
      : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
        call_([](void* o, int x, int y, float c) { (*static_cast<std::remove_reference_t<F>*>(o))(x, y, c); }) {}
  void operator()(int x, int y, float intensity) const { call_(object_, x, y, intensity); }

 private:
  void* object_;
  void (*call_)(void*, int, int, float);
};

/// The notes' DDA line() exactly as written: dx = x1 - x0, dy = y1 - y0, length = max(|dx|, |dy|),
/// xinc = dx / length, yinc = dy / length, then for (i = 0; i <= length; i++) plot(round(x), round(y)) and step
/// x += xinc, y += yinc. round() is C's (halves away from zero), and a non-integer length stops at floor(length).
/// Where the notes divide by zero (both ends equal) one pixel, (round(x0), round(y0)), is plotted. Intensity is 1.
void line_dda(double x0, double y0, double x1, double y1, PixelPlot plot);

/// Bresenham's line with integer arithmetic only, in all eight octants, both endpoints included: one pixel per step
/// along the major axis, the minor coordinate being the nearest to the true line (exact halves round toward the start
/// point). Intensity is 1. (Bresenham 1965; the decision variable D = 2 dy - dx form.)
void line_bresenham(int x0, int y0, int x1, int y1, PixelPlot plot);

/// Xiaolin Wu's antialiased line (Wu 1991): per step along the major axis two pixels straddling the line share
/// intensity 1 by distance (fpart / 1 - fpart); the end pixels are weighted by the fraction of their pixel the line
/// covers along the major axis. Pixels with intensity 0 are skipped.
void line_wu(double x0, double y0, double x1, double y1, PixelPlot plot);

/// The vertices the notes' circle() hands to GT_LINES: for i = 1..n, the pair (xold, yold), (cos t, sin t) with
/// t = 2 pi i / n, starting from (1, 0): 2n points, n segments of the unit circle. Throws InvalidInput when n < 1.
std::vector<Vec2> circle_segments(int n = 20);

/// Which line algorithm draw_line() uses.
enum class LineAlgorithm { dda, bresenham, wu };

/// Draws a line into `image` (pixel-index coordinates as above), blending `color` (straight RGBA) source-over with
/// its alpha scaled by each pixel's intensity; pixels outside the image are skipped. Bresenham rounds the endpoints
/// to the nearest integers first.
void draw_line(ImageRGBA& image, const Vec2& a, const Vec2& b, const Vec4f& color, LineAlgorithm algorithm);

}  // namespace tessera
