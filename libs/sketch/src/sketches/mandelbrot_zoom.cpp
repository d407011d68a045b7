// The notes' Mandelbrot set ("Mandelbrot Set": fix z0 = (0, 0), test different c values for convergence) as a
// zoom: each frame is libs/fractal's escape-time picture (mandelbrot(), colored by colorize()'s classic palette) of a
// view whose width shrinks smoothly and exponentially, halving three times a second of millis(),
//   scale = 3 * 2^-depth,   depth = 3 millis() / 1000 (wrapping after 36 halvings, before doubles run out),
// toward a point of the seahorse valley, -0.743643887037151 + 0.131825904205330 i; the iteration cap grows with the
// depth (200 + 50 depth). A mouse press recenters the zoom on the point under the pointer.
#include <cmath>

#include "sketches/sketches.hpp"
#include "tessera/fractal/coloring.hpp"
#include "tessera/fractal/escape_time.hpp"

namespace tessera::sketches {
namespace {

class MandelbrotZoom : public Sketch {
 public:
  void setup() override {
    size(320, 240);
    view_ = ComplexView{center_, 3.0, width, height};
  }

  void draw() override {
    const double depth = std::fmod(3.0 * double(millis()) / 1000.0, kMaxDepth);
    view_ = ComplexView{center_, 3.0 * std::exp2(-depth), width, height};
    const EscapeImage escape = mandelbrot(view_, EscapeOptions{.max_iterations = 200 + int(50 * depth)});
    const ImageRGB colors = colorize(escape);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) canvas().write_pixel(x, y, Vec4f(colors(x, y), 1.0f));
  }

  void mouse_pressed() override { center_ = view_.pixel_center(mouse_x, mouse_y); }

 private:
  static constexpr double kMaxDepth = 36;  // 3 * 2^-36 wide: about 2^-44 a pixel, still many ulps of |c| ~ 1

  std::complex<double> center_{-0.743643887037151, 0.131825904205330};
  ComplexView view_;  // the view of the last frame drawn (what a press points at)
};

}  // namespace

std::unique_ptr<Sketch> make_mandelbrot_zoom() { return std::make_unique<MandelbrotZoom>(); }

}  // namespace tessera::sketches
