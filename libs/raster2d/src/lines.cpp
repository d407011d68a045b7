#include "tessera/raster2d/lines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "tessera/core/error.hpp"
#include "tessera/raster2d/blend.hpp"

namespace tessera {

void line_dda(double x0, double y0, double x1, double y1, PixelPlot plot) {
  const double dx = x1 - x0, dy = y1 - y0;
  const double length = std::max(std::fabs(dx), std::fabs(dy));
  if (length == 0) {
    plot(int(std::round(x0)), int(std::round(y0)), 1.0f);
    return;
  }
  const double xinc = dx / length, yinc = dy / length;
  double x = x0, y = y0;
  for (int i = 0; i <= length; i++) {
    plot(int(std::round(x)), int(std::round(y)), 1.0f);
    x += xinc;
    y += yinc;
  }
}

void line_bresenham(int x0, int y0, int x1, int y1, PixelPlot plot) {
  const int dx = std::abs(x1 - x0), dy = std::abs(y1 - y0);
  const int sx = x1 >= x0 ? 1 : -1, sy = y1 >= y0 ? 1 : -1;
  // Walk the major axis; D = 2 (k + 1) minor - (2 j + 1) major decides whether the next minor step is taken.
  const bool x_major = dx >= dy;
  const int major = x_major ? dx : dy, minor = x_major ? dy : dx;
  int d = 2 * minor - major;
  int x = x0, y = y0;
  for (int k = 0; k <= major; ++k) {
    plot(x, y, 1.0f);
    if (d > 0) {
      (x_major ? y : x) += x_major ? sy : sx;
      d -= 2 * major;
    }
    d += 2 * minor;
    (x_major ? x : y) += x_major ? sx : sy;
  }
}

namespace {
double fpart(double v) { return v - std::floor(v); }
double rfpart(double v) { return 1.0 - fpart(v); }
}  // namespace

void line_wu(double x0, double y0, double x1, double y1, PixelPlot plot) {
  const bool steep = std::fabs(y1 - y0) > std::fabs(x1 - x0);
  if (steep) {
    std::swap(x0, y0);
    std::swap(x1, y1);
  }
  if (x0 > x1) {
    std::swap(x0, x1);
    std::swap(y0, y1);
  }
  auto put = [&](int major, int minor, double intensity) {
    if (intensity <= 0) return;
    if (steep)
      plot(minor, major, float(intensity));
    else
      plot(major, minor, float(intensity));
  };
  const double dx = x1 - x0, dy = y1 - y0;
  const double gradient = dx == 0 ? 1.0 : dy / dx;
  // First end: the pixel column nearest x0, weighted by how much of that column the line covers.
  const double xend0 = std::floor(x0 + 0.5);
  const double yend0 = y0 + gradient * (xend0 - x0);
  const double xgap0 = rfpart(x0 + 0.5);
  const int xpixel0 = int(xend0), ypixel0 = int(std::floor(yend0));
  put(xpixel0, ypixel0, rfpart(yend0) * xgap0);
  put(xpixel0, ypixel0 + 1, fpart(yend0) * xgap0);
  double y_at = yend0 + gradient;
  // Second end.
  const double xend1 = std::floor(x1 + 0.5);
  const double yend1 = y1 + gradient * (xend1 - x1);
  const double xgap1 = fpart(x1 + 0.5);
  const int xpixel1 = int(xend1), ypixel1 = int(std::floor(yend1));
  put(xpixel1, ypixel1, rfpart(yend1) * xgap1);
  put(xpixel1, ypixel1 + 1, fpart(yend1) * xgap1);
  // Between: two pixels per column sharing intensity 1 by distance to the line.
  for (int x = xpixel0 + 1; x < xpixel1; ++x) {
    const int y = int(std::floor(y_at));
    put(x, y, rfpart(y_at));
    put(x, y + 1, fpart(y_at));
    y_at += gradient;
  }
}

std::vector<Vec2> circle_segments(int n) {
  if (n < 1) throw InvalidInput(fmt::format("circle_segments: n must be at least 1, got {}", n));
  std::vector<Vec2> vertices;
  vertices.reserve(size_t(2 * n));
  double xold = 1, yold = 0;
  for (int i = 1; i <= n; i++) {
    const double theta = 2 * kPi * i / n;
    vertices.push_back({xold, yold});
    vertices.push_back({std::cos(theta), std::sin(theta)});
    xold = std::cos(theta);
    yold = std::sin(theta);
  }
  return vertices;
}

void draw_line(ImageRGBA& image, const Vec2& a, const Vec2& b, const Vec4f& color, LineAlgorithm algorithm) {
  auto plot = [&](int x, int y, float intensity) {
    if (image.contains(x, y)) image(x, y) = blend_over(image(x, y), color, intensity);
  };
  switch (algorithm) {
    case LineAlgorithm::dda:
      line_dda(a.x, a.y, b.x, b.y, plot);
      break;
    case LineAlgorithm::bresenham:
      line_bresenham(int(std::lround(a.x)), int(std::lround(a.y)), int(std::lround(b.x)), int(std::lround(b.y)), plot);
      break;
    case LineAlgorithm::wu:
      line_wu(a.x, a.y, b.x, b.y, plot);
      break;
  }
}

}  // namespace tessera
