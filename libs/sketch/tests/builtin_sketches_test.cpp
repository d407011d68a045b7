// The built-in sketches of the notes (bezier, body, mandelbrot_zoom, marching_squares, transformations), headless and
// frame-exact with scripted input, each against an independent expectation: the notes' formulas for the
// transformations and the Bezier basis, the body's angle formula carried through the matrix stack by hand, the
// escape time of z -> z^2 + c iterated here with std::complex, and marching squares' segments counted per cell case.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <string>
#include <vector>

#include "sketches/marching_squares.hpp"
#include "tessera/fractal/coloring.hpp"
#include "tessera/math/noise.hpp"
#include "tessera/sketch/runner.hpp"

namespace tessera {
namespace {

using glm::u8vec4;

constexpr double kPiD = 3.14159265358979323846;
double rad(double degrees) { return degrees * kPiD / 180; }

/// The last frame of a headless run of the built-in `name` for `frames` frames with `script` as input.
ImageRGBA8 last_frame(std::string_view name, int frames, std::string_view script = {}, double fps = 0) {
  const SketchInfo* info = find_sketch(name);
  EXPECT_NE(info, nullptr) << name;
  if (!info) return {};
  RunOptions o;
  o.frames = frames;
  if (fps > 0) o.fps = fps;
  if (!script.empty()) o.events = parse_input_script(script);
  ImageRGBA8 last;
  const auto sketch = info->make();
  run_sketch(*sketch, o, [&](int, const ImageRGBA8& picture) { last = picture; });
  return last;
}

int distance(u8vec4 a, u8vec4 b) { return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)}); }

/// The pixel containing the device point (x, y).
u8vec4 at(const ImageRGBA8& image, double x, double y) { return image(int(std::floor(x)), int(std::floor(y))); }

/// Whether some pixel within `radius` pixels of the device point (x, y) is within `tolerance` of `color`.
bool near(const ImageRGBA8& image, double x, double y, u8vec4 color, int tolerance = 12, int radius = 1) {
  const int cx = int(std::floor(x)), cy = int(std::floor(y));
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int px = cx + dx, py = cy + dy;
      if (px >= 0 && py >= 0 && px < image.width() && py < image.height() &&
          distance(image(px, py), color) <= tolerance)
        return true;
    }
  return false;
}

// ---- bouncing_balls ------------------------------------------------------------------------------------------------

TEST(BouncingBallsSketch, APressDropsABallThatFallsAsGravitySays) {
  // The same run with and without a press at (200, 40) before frame 2: the pixels that differ are the dropped ball,
  // drawn last. Dropped from rest, after m = n - 1 steps of v += g, y += v its center is at y = 40 + g m (m + 1) / 2.
  for (int n : {2, 15, 25}) {
    const ImageRGBA8 without = last_frame("bouncing_balls", n, "1 mouse_move 200 40\n");
    const ImageRGBA8 with = last_frame("bouncing_balls", n, "1 mouse_move 200 40\n2 mouse_press left\n");
    ASSERT_EQ(with.width(), 400);
    int x0 = 400, x1 = -1, y0 = 300, y1 = -1;
    for (int y = 0; y < 300; ++y)
      for (int x = 0; x < 400; ++x)
        if (with(x, y) != without(x, y))
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    ASSERT_GE(x1, 0) << "frame " << n << ": no ball dropped";
    const double m = n - 1, expected_y = 40 + 0.5 * m * (m + 1) / 2;
    EXPECT_NEAR((x0 + x1 + 1) / 2.0, 200, 1.0) << "frame " << n;
    EXPECT_NEAR((y0 + y1 + 1) / 2.0, expected_y, 1.0) << "frame " << n;
    EXPECT_GE(x1 - x0 + 1, 16) << "frame " << n;  // the radius is random(8, 22)
    EXPECT_LE(x1 - x0 + 1, 46) << "frame " << n;
  }
}

TEST(BouncingBallsSketch, BallsStayBetweenTheWallsAndAboveTheFloor) {
  // After 300 frames of bounces nothing but the paper is on the left and right edge columns (at most the faint
  // antialiased rim of a ball touching a wall): each ball's center stays at least its radius from the walls.
  const ImageRGBA8 f = last_frame("bouncing_balls", 300);
  const u8vec4 paper = at(f, 200, 0);
  for (int y = 0; y < 300; ++y) {
    EXPECT_LE(distance(f(0, y), paper), 30) << y;
    EXPECT_LE(distance(f(399, y), paper), 30) << y;
  }
}

// ---- body ----------------------------------------------------------------------------------------------------------

struct Point {
  double x, y;
};
Point rotate(Point p, double a) {
  return {p.x * std::cos(a) - p.y * std::sin(a), p.x * std::sin(a) + p.y * std::cos(a)};
}
// The body's units to pixels: translate(200, 240), scale(14, -14).
Point body_to_device(Point p) { return {200 + 14 * p.x, 240 - 14 * p.y}; }

TEST(BodySketch, TheWavingArmFollowsTheAngleFormula) {
  for (int n : {1, 17, 40, 52}) {
    const ImageRGBA8 f = last_frame("body", n);
    ASSERT_EQ(f.width(), 400);
    // The formula: raise = 40 + 25 sin(2 pi n / 60) degrees at the shoulder (2, 3), wave = 35 sin(3 2 pi n / 60)
    // at the wrist, 6 units along the arm.
    const double phase = 2 * kPiD * n / 60;
    const double raise = rad(40) + rad(25) * std::sin(phase), wave = rad(35) * std::sin(3 * phase);
    const auto arm = [&](Point p, double r) {
      const Point q = rotate(p, r);
      return body_to_device({2 + q.x, 3 + q.y});
    };
    const u8vec4 black(0, 0, 0, 255), white(255, 255, 255, 255);
    for (double along : {1.5, 3.0, 4.5})
      for (double side : {-0.5, 0.5}) {
        const Point d = arm({along, side}, raise);
        EXPECT_TRUE(near(f, d.x, d.y, black, 100)) << "frame " << n << ": upper arm edge at " << d.x << "," << d.y;
      }
    // 15 degrees further up, the same edge point is empty paper.
    const Point off = arm({3.0, 0.5}, raise + rad(15));
    EXPECT_TRUE(near(f, off.x, off.y, white, 0, 0)) << "frame " << n;
    // The palm's far edge, (2, 0) in the hand's frame: the wrist (6, 0) turned by raise, then by wave.
    const Point wrist = rotate({6, 0}, raise), palm = rotate(rotate({2, 0}, wave), raise);
    const Point d = body_to_device({2 + wrist.x + palm.x, 3 + wrist.y + palm.y});
    EXPECT_TRUE(near(f, d.x, d.y, black, 100)) << "frame " << n << ": palm edge";
  }
}

// ---- transformations -----------------------------------------------------------------------------------------------

TEST(TransformationsSketch, EachPanelsHouseIsWhereTheNotesMatrixPutsIt) {
  const u8vec4 colors[4] = {{90, 150, 230, 255}, {240, 120, 90, 255}, {110, 190, 110, 255}, {190, 120, 210, 255}};
  for (int n : {1, 23, 61, 100}) {
    const ImageRGBA8 f = last_frame("transformations", n);
    ASSERT_EQ(f.width(), 400);
    const double theta = 2 * kPiD * n / 90, c = std::cos(theta), s = std::sin(theta);
    for (int panel = 0; panel < 4; ++panel) {
      // Points well inside the house: the square [0, 2]^2 and the roof up to (1, 3).
      for (const Point p : {Point{0.5, 0.5}, Point{1.5, 1.0}, Point{1.0, 2.4}, Point{0.6, 1.6}}) {
        Point q{};
        switch (panel) {
          case 0:  // P' = P + T
            q = {p.x + 1.5 * c, p.y + 1.5 * s};
            break;
          case 1:  // about the pivot (1, 1): P''' = T2 R T1 P
            q = {1 + c * (p.x - 1) - s * (p.y - 1), 1 + s * (p.x - 1) + c * (p.y - 1)};
            break;
          case 2:
            q = {p.x * (1 + 0.5 * s), p.y * (1 + 0.5 * c)};
            break;
          default:  // x' = x + a y
            q = {p.x + s * p.y, p.y};
        }
        const double dx = 200 * (panel % 2) + 80 + 20 * q.x, dy = 200 * (panel / 2) + 130 - 20 * q.y;
        EXPECT_LE(distance(at(f, dx, dy), colors[panel]), 1)
            << "frame " << n << " panel " << panel << " point " << p.x << "," << p.y << " at " << dx << "," << dy;
      }
    }
  }
}

// ---- bezier --------------------------------------------------------------------------------------------------------

Point cubic(const Point (&p)[4], double t) {  // the notes' Q(t) = B1 P1 + B2 P2 + B3 P3 + B4 P4
  const double b[4] = {(1 - t) * (1 - t) * (1 - t), 3 * t * (1 - t) * (1 - t), 3 * t * t * (1 - t), t * t * t};
  Point q{0, 0};
  for (int i = 0; i < 4; ++i) q.x += b[i] * p[i].x, q.y += b[i] * p[i].y;
  return q;
}

TEST(BezierSketch, ADraggedControlPointGoesWhereTheMouseWentAndTheCurveFollows) {
  // Press 3 pixels from P2 = (110, 80), drag in two steps to (200, 250), release.
  const ImageRGBA8 f = last_frame("bezier", 6,
                                  "1 mouse_move 113 82\n2 mouse_press left\n3 mouse_move 150 160\n"
                                  "4 mouse_move 200 250\n5 mouse_release left\n");
  ASSERT_EQ(f.width(), 400);
  const u8vec4 point_color(250, 160, 40, 255), curve_color(40, 90, 220, 255);
  EXPECT_EQ(at(f, 200, 250), point_color);
  EXPECT_FALSE(near(f, 110, 80, point_color, 30, 3)) << "P2 left its old place";
  for (const Point p : {Point{60, 320}, Point{290, 60}, Point{340, 300}}) EXPECT_EQ(at(f, p.x, p.y), point_color);
  const Point control[4] = {{60, 320}, {200, 250}, {290, 60}, {340, 300}};
  for (double t = 0.2; t <= 0.81; t += 0.1) {
    const Point q = cubic(control, t);
    EXPECT_TRUE(near(f, q.x, q.y, curve_color, 16)) << "Q(" << t << ") = " << q.x << "," << q.y;
  }
}

TEST(BezierSketch, APressAwayFromEveryPointDragsNothing) {
  const ImageRGBA8 f =
      last_frame("bezier", 4, "1 mouse_move 200 200\n2 mouse_press left\n3 mouse_move 110 80\n4 mouse_move 5 5\n");
  const u8vec4 point_color(250, 160, 40, 255), dragged_color(200, 100, 0, 255);
  for (const Point p : {Point{60, 320}, Point{110, 80}, Point{290, 60}, Point{340, 300}})
    EXPECT_EQ(at(f, p.x, p.y), point_color);
  EXPECT_FALSE(near(f, 5, 5, dragged_color, 30, 3));
}

TEST(BezierSketch, TheConstructionPointIsQOfTheFramesT) {
  const u8vec4 red(220, 40, 40, 255);
  const Point control[4] = {{60, 320}, {110, 80}, {290, 60}, {340, 300}};
  for (int n : {60, 100, 150}) {
    const double t = 0.5 - 0.5 * std::cos(2 * kPiD * n / 240);
    const Point q = cubic(control, t);
    EXPECT_EQ(at(last_frame("bezier", n), q.x, q.y), red) << "frame " << n << " t " << t;
  }
}

// ---- mandelbrot_zoom -----------------------------------------------------------------------------------------------

/// The color the zoom should show at pixel (x, y) of a w x h view of width `scale` around `center`: the escape time
/// of z -> z^2 + c iterated here (|z| > 256 escapes), colored as colorize()'s documentation says (black inside;
/// otherwise the classic palette at sqrt(nu) / 12, nu = n + 1 - log2(log|z_n| / log 256)).
u8vec4 expected_mandelbrot(std::complex<double> center, double scale, int w, int h, int x, int y, int max_iter) {
  const double pixel = scale / w;
  const std::complex<double> c =
      center + std::complex<double>((x + 0.5 - w / 2.0) * pixel, -(y + 0.5 - h / 2.0) * pixel);
  std::complex<double> z = 0;
  for (int n = 1; n <= max_iter; ++n) {
    z = z * z + c;
    if (std::norm(z) > 256.0 * 256.0) {
      const double nu = n + 1 - std::log2(std::log(std::abs(z)) / std::log(256.0));
      const Vec3f rgb = palette_color(Palette::classic, std::sqrt(nu) / 12);
      const auto byte = [](float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
      return {byte(rgb.x), byte(rgb.y), byte(rgb.z), 255};
    }
  }
  return {0, 0, 0, 255};
}

/// The share of the pixels on a 4-pixel grid (and whether the center pixel) matches expected_mandelbrot within 3.
void expect_mandelbrot(const ImageRGBA8& f, std::complex<double> center, double depth, const std::string& what) {
  const double scale = 3 * std::exp2(-depth);
  const int max_iter = 200 + int(50 * depth), w = f.width(), h = f.height();
  int good = 0, total = 0;
  for (int y = 0; y < h; y += 4)
    for (int x = 0; x < w; x += 4) {
      ++total;
      good += distance(f(x, y), expected_mandelbrot(center, scale, w, h, x, y, max_iter)) <= 3;
    }
  EXPECT_GE(good, total * 99 / 100) << what << ": " << good << " of " << total;
  EXPECT_LE(distance(f(w / 2, h / 2), expected_mandelbrot(center, scale, w, h, w / 2, h / 2, max_iter)), 3) << what;
}

TEST(MandelbrotZoomSketch, EachFrameIsTheEscapeTimeOfItsZoomedView) {
  const std::complex<double> target(-0.743643887037151, 0.131825904205330);
  // At 50 frames per second millis() is exactly 20 (n - 1); the depth is 3 millis / 1000 halvings.
  for (int n : {1, 26, 76}) {
    const ImageRGBA8 f = last_frame("mandelbrot_zoom", n, {}, 50);
    ASSERT_EQ(f.width(), 320);
    ASSERT_EQ(f.height(), 240);
    expect_mandelbrot(f, target, 3 * 20.0 * (n - 1) / 1000, "frame " + std::to_string(n));
  }
  // Deep in the seahorse valley: at 10 frames per second frame 41 is 4 seconds in, 12 halvings (2^-12 of the width).
  expect_mandelbrot(last_frame("mandelbrot_zoom", 41, {}, 10), target, 12, "frame 41 at 10 fps");
}

TEST(MandelbrotZoomSketch, APressRecentersOnThePointUnderThePointer) {
  const std::complex<double> target(-0.743643887037151, 0.131825904205330);
  // The press before frame 26 picks pixel (80, 60) of frame 25's view (depth 1.44); frame 26 is drawn at depth 1.5
  // around that point.
  const ImageRGBA8 f = last_frame("mandelbrot_zoom", 26, "25 mouse_move 80 60\n26 mouse_press left\n", 50);
  const double pixel = 3 * std::exp2(-1.44) / 320;
  const std::complex<double> picked = target + std::complex<double>((80.5 - 160) * pixel, -(60.5 - 120) * pixel);
  expect_mandelbrot(f, picked, 1.5, "after the press");
}

// ---- noise_hills ---------------------------------------------------------------------------------------------------

TEST(NoiseHillsSketch, TheFrontRidgeIsTheNoiseFormula) {
  // Processing's noise() of the run's seed (0): the front ridge (k = 2) at column x after n frames at speed 1 is
  // y = 300 (0.45 + 0.34) + 300 (0.3 - 0.1) (0.5 - noise((x + 2.5 n) 0.006 * 2, 14.6)).
  const ProcessingNoise noise(0);
  const u8vec4 front(40, 60, 80, 255);
  for (int n : {1, 30, 77}) {
    const ImageRGBA8 f = last_frame("noise_hills", n);
    ASSERT_EQ(f.width(), 400);
    ASSERT_EQ(f.height(), 300);
    for (int x = 8; x < 400; x += 24) {
      const double u = (x + 2.5 * n) * 0.006 * 2;
      const double y = 300 * (0.45 + 0.17 * 2) + 300 * (0.3 - 0.05 * 2) * (0.5 - noise.noise(float(u), float(7.3 * 2)));
      EXPECT_LE(distance(at(f, x + 0.5, y + 3), front), 1) << "frame " << n << " x " << x << " ridge " << y;
      EXPECT_GT(distance(at(f, x + 0.5, y - 3), front), 10) << "frame " << n << " x " << x << " ridge " << y;
    }
  }
}

// ---- marching_squares ----------------------------------------------------------------------------------------------

/// Marching squares' segments counted per cell from the corner classes alone (inside: value >= iso): no segment for
/// 0 or 4 inside corners, two for the two diagonal saddles, one for every other case.
int count_segments(const DepthImage& field, float iso) {
  int segments = 0;
  for (int j = 0; j + 1 < field.height(); ++j)
    for (int i = 0; i + 1 < field.width(); ++i) {
      const bool a = field(i, j) >= iso, b = field(i + 1, j) >= iso, c = field(i + 1, j + 1) >= iso,
                 d = field(i, j + 1) >= iso;
      const int inside = a + b + c + d;
      if (inside == 0 || inside == 4) continue;
      segments += (inside == 2 && a == c) ? 2 : 1;
    }
  return segments;
}

int drawn_segments(const std::vector<Polyline>& contours) {
  int segments = 0;
  for (const Polyline& line : contours) segments += int(line.points.size()) - 1 + (line.closed ? 1 : 0);
  return segments;
}

TEST(MarchingSquaresSketch, TheIsoValueFollowsTheMouseAndTheContourHasEveryCellsSegments) {
  for (const auto& [x, iso] : {std::pair{-1, 5.0f}, std::pair{130, 3.25f}, std::pair{330, 8.25f}}) {
    sketches::MarchingSquaresSketch sketch;
    RunOptions o;
    o.frames = 3;
    if (x >= 0) o.events = parse_input_script("2 mouse_move " + std::to_string(x) + " 37\n");
    ImageRGBA8 f;
    run_sketch(sketch, o, [&](int, const ImageRGBA8& picture) { f = picture; });
    EXPECT_EQ(sketch.iso(), iso);
    const int expected = count_segments(sketch.field(), iso);
    EXPECT_GT(expected, 4) << "iso " << iso;
    EXPECT_EQ(drawn_segments(sketch.contours()), expected) << "iso " << iso;
    // Every polyline is drawn in red through the middle of its segments.
    const double cell = 400.0 / sketches::MarchingSquaresSketch::kSamples;
    for (const Polyline& line : sketch.contours()) {
      const Vec2 m = ((line.points[0] + line.points[1]) * 0.5 + 0.5) * cell;
      EXPECT_TRUE(near(f, m.x, m.y, u8vec4(220, 30, 30, 255), 40)) << "iso " << iso << " at " << m.x << "," << m.y;
    }
  }
}

}  // namespace
}  // namespace tessera
