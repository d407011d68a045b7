#include "tessera/raster2d/canvas.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <tuple>
#include <utility>

#include "tessera/core/memory_budget.hpp"
#include "tessera/math/transform.hpp"

namespace tessera {
namespace {

// A canvas as a counting target: transparent, filled with alpha 1/2 and no stroke, a pixel written n times has
// alpha 1 - 2^-n (0 untouched, 0.5 once, 0.75 twice).
Canvas counting_canvas(int w, int h) {
  Canvas c(w, h);
  c.background(Vec4f(0));
  c.no_stroke();
  c.no_smooth();
  c.fill(Vec4f(1, 1, 1, 0.5f));
  return c;
}

double coverage_sum(const Canvas& c) {
  double s = 0;
  for (const Vec4f& p : c.image().pixels()) s += p.w;
  return s;
}

TEST(Canvas, RectIsHalfOpen) {
  for (const bool smooth : {false, true}) {
    Canvas c(400, 400);
    c.background(Vec4f(0, 0, 0, 1));
    c.no_stroke();
    c.fill(rgb255(255, 150, 150));
    smooth ? c.smooth() : c.no_smooth();
    c.rect(100, 200, 10, 10);
    for (int y = 0; y < 400; ++y)
      for (int x = 0; x < 400; ++x) {
        const bool in = x >= 100 && x < 110 && y >= 200 && y < 210;
        ASSERT_EQ(c.image()(x, y), in ? rgb255(255, 150, 150) : Vec4f(0, 0, 0, 1)) << x << "," << y;
      }
  }
}

TEST(Canvas, RandomAbuttingRectsAndTrianglesWriteEachPixelOnce) {
  std::mt19937 rng(53);
  std::uniform_real_distribution<double> u(0.15, 0.85), jitter(-0.3, 0.3);
  for (int trial = 0; trial < 3; ++trial) {
    // Rects: random real column and row cuts of [0, 45] x [0, 35], scaled by 2 to cover the canvas.
    Canvas rects = counting_canvas(90, 70);
    std::vector<double> xs{0}, ys{0};
    while (xs.back() < 45) xs.push_back(std::min(45.0, xs.back() + 6 * u(rng)));
    while (ys.back() < 35) ys.push_back(std::min(35.0, ys.back() + 6 * u(rng)));
    rects.scale(2);
    for (size_t j = 0; j + 1 < ys.size(); ++j)
      for (size_t i = 0; i + 1 < xs.size(); ++i) rects.rect(xs[i], ys[j], xs[i + 1] - xs[i], ys[j + 1] - ys[j]);
    // Triangles: a jittered grid, each cell split along a random diagonal, rotated and moved about the center.
    Canvas tris = counting_canvas(90, 70);
    const int nx = 12, ny = 9;
    std::vector<Vec2> v;
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        v.push_back(
            {(i + (i % nx ? jitter(rng) : 0)) * 160.0 / nx - 80, (j + (j % ny ? jitter(rng) : 0)) * 160.0 / ny - 80});
    tris.translate(45, 35);
    tris.rotate(0.3);
    auto at = [&](int i, int j) { return v[size_t(j * (nx + 1) + i)]; };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Vec2 a = at(i, j), b = at(i + 1, j), cc = at(i + 1, j + 1), d = at(i, j + 1);
        if (rng() % 2) {
          tris.triangle(a.x, a.y, b.x, b.y, cc.x, cc.y);
          tris.triangle(a.x, a.y, cc.x, cc.y, d.x, d.y);
        } else {
          tris.triangle(a.x, a.y, b.x, b.y, d.x, d.y);
          tris.triangle(b.x, b.y, cc.x, cc.y, d.x, d.y);
        }
      }
    for (const Canvas* c : {&rects, &tris}) {
      int bad = 0;
      for (const Vec4f& p : c->image().pixels()) bad += p.w != 0.5f;
      EXPECT_EQ(bad, 0) << (c == &rects ? "rects" : "triangles");
    }
  }
}

TEST(Canvas, TransformsMultiplyOnTheRightAndPushPopRestores) {
  Canvas c(100, 100);
  c.translate(10, 20);
  c.push_matrix();
  c.scale(2);
  // CTM = T S: the scale acts first.
  EXPECT_EQ(transform_point(c.matrix(), Vec2(5, 5)), Vec2(20, 30));
  c.rotate(kPi / 2);  // +x toward +y
  const Vec2 p = transform_point(c.matrix(), Vec2(1, 0));
  EXPECT_NEAR(p.x, 10, 1e-12);
  EXPECT_NEAR(p.y, 22, 1e-12);
  c.pop_matrix();
  EXPECT_EQ(c.matrix(), translate2d(10, 20));
  c.shear_x(kPi / 4);
  EXPECT_NEAR(transform_point(c.matrix(), Vec2(0, 3)).x, 13, 1e-12);
  c.reset_matrix();
  EXPECT_EQ(c.matrix(), Mat3(1.0));
  c.apply_matrix(scale2d(3, 4));
  EXPECT_EQ(transform_point(c.matrix(), Vec2(1, 1)), Vec2(3, 4));
  // The drawn pixels follow the CTM.
  c.reset_matrix();
  c.background(Vec4f(0, 0, 0, 1));
  c.no_stroke();
  c.fill(Vec4f(1));
  c.no_smooth();
  c.translate(30, 40);
  c.scale(2, 3);
  c.rect(0, 0, 5, 5);  // -> [30, 40) x [40, 55)
  for (int y = 35; y < 60; ++y)
    for (int x = 25; x < 45; ++x)
      EXPECT_EQ(c.image()(x, y).x, (x >= 30 && x < 40 && y >= 40 && y < 55) ? 1.0f : 0.0f) << x << "," << y;
}

TEST(Canvas, PopUnderflowThrows) {
  Canvas c(10, 10);
  EXPECT_THROW(c.pop_matrix(), InvalidInput);
  c.push_matrix();
  EXPECT_NO_THROW(c.pop_matrix());
  EXPECT_THROW(c.pop_matrix(), InvalidInput);
}

TEST(Canvas, ShapeWithAContourHole) {
  for (const FillRule rule : {FillRule::non_zero, FillRule::even_odd}) {
    Canvas c = counting_canvas(60, 60);
    c.fill(Vec4f(1));
    c.fill_rule(rule);
    c.begin_shape();
    for (const auto& [x, y] : {std::pair{10, 10}, {50, 10}, {50, 50}, {10, 50}}) c.vertex(x, y);
    c.begin_contour();  // same orientation: a hole under even-odd only
    for (const auto& [x, y] : {std::pair{20, 20}, {40, 20}, {40, 40}, {20, 40}}) c.vertex(x, y);
    c.end_contour();
    c.end_shape(true);
    EXPECT_EQ(c.image()(30, 30).w, rule == FillRule::even_odd ? 0.0f : 1.0f);
    EXPECT_EQ(c.image()(15, 30).w, 1.0f);
    EXPECT_EQ(c.image()(5, 30).w, 0.0f);
    EXPECT_EQ(coverage_sum(c), rule == FillRule::even_odd ? 1600 - 400 : 1600);
  }
}

TEST(Canvas, ShapeErrors) {
  Canvas c(10, 10);
  EXPECT_THROW(c.vertex(1, 1), InvalidInput);
  EXPECT_THROW(c.end_shape(), InvalidInput);
  EXPECT_THROW(c.end_contour(), InvalidInput);
  c.begin_shape();
  EXPECT_THROW(c.bezier_vertex(1, 1, 2, 2, 3, 3), InvalidInput);
  EXPECT_THROW(c.begin_shape(), InvalidInput);
  c.begin_contour();
  EXPECT_THROW(c.begin_contour(), InvalidInput);
  EXPECT_THROW(c.end_shape(), InvalidInput);
  c.end_contour();
  c.end_shape();
  c.begin_shape(ShapeKind::lines);
  EXPECT_THROW(c.begin_contour(), InvalidInput);
  EXPECT_THROW(c.stroke_weight(-1), InvalidInput);
}

TEST(Canvas, EllipseAndArcAreas) {
  Canvas c = counting_canvas(120, 100);
  c.fill(Vec4f(1));
  c.smooth();
  c.ellipse(60.3, 50.1, 80, 60);
  EXPECT_NEAR(coverage_sum(c), kPi * 40 * 30, 0.5);
  const double quarter = kPi * 40 * 30 / 4, corner_triangle = 40.0 * 30 / 2;
  for (const auto& [mode, area] :
       {std::pair{ArcMode::pie, quarter}, std::pair{ArcMode::chord, quarter - corner_triangle},
        std::pair{ArcMode::open, quarter - corner_triangle}}) {
    Canvas a = counting_canvas(120, 100);
    a.fill(Vec4f(1));
    a.smooth();
    a.arc(60, 50, 80, 60, 0, kPi / 2, mode);
    EXPECT_NEAR(coverage_sum(a), area, 0.5);
    EXPECT_EQ(a.image()(85, 68).w, 1.0f);  // between the chord and the arc: inside every mode's fill
  }
}

TEST(Canvas, BezierShapeFollowsTheCurve) {
  // Controls (0, 0) (0, h) (w, h) (w, 0): x = w (3t^2 - 2t^3), y = 3h t (1 - t), so the area between the curve and
  // its chord is the integral of y dx = 18 w h * integral of t^2 (1 - t)^2 dt = 0.6 w h.
  Canvas c = counting_canvas(100, 100);
  c.fill(Vec4f(1));
  c.smooth();
  c.begin_shape();
  c.vertex(10, 90);
  c.bezier_vertex(10, 10, 90, 10, 90, 90);
  c.end_shape(true);
  EXPECT_NEAR(coverage_sum(c), 0.6 * 80 * 80, 3.0);
  Canvas q = counting_canvas(100, 100);
  q.fill(Vec4f(1));
  q.smooth();
  q.begin_shape();
  q.vertex(10, 90);
  q.quadratic_vertex(50, 10, 90, 90);
  q.end_shape(true);
  EXPECT_NEAR(coverage_sum(q), 2.0 / 3.0 * 80 * 40, 3.0);  // a parabolic segment: 2/3 of base times height 40
}

TEST(Canvas, ThinAliasedLinesAreTheNotesDda) {
  Canvas c = counting_canvas(30, 30);
  c.stroke(Vec4f(1));
  c.line(10, 10, 20, 10);  // pixel-index (9.5, 9.5) -> (19.5, 9.5): round() gives row 10, columns 10..20
  for (int x = 0; x < 30; ++x) EXPECT_EQ(c.image()(x, 10).w, (x >= 10 && x <= 20) ? 1.0f : 0.0f) << x;
  EXPECT_EQ(coverage_sum(c), 11);
}

TEST(Canvas, ThickStrokesAndPoints) {
  Canvas c = counting_canvas(60, 60);
  c.stroke(Vec4f(1));
  c.stroke_weight(4);
  c.stroke_cap(LineCap::butt);
  c.line(10, 20, 50, 20);
  EXPECT_EQ(coverage_sum(c), 40 * 4);
  Canvas p = counting_canvas(60, 60);
  p.stroke(Vec4f(1));
  p.smooth();
  p.stroke_weight(10);
  p.point(30, 30);
  EXPECT_NEAR(coverage_sum(p), kPi * 25, 0.3);
  p.stroke_weight(1);
  p.point(5.7, 5.2);
  EXPECT_EQ(p.image()(5, 5).w, 1.0f);
}

TEST(Canvas, ShapeKinds) {
  Canvas c = counting_canvas(40, 40);
  c.fill(Vec4f(1));
  c.begin_shape(ShapeKind::quads);
  for (const auto& [x, y] : {std::pair{0, 0}, {10, 0}, {10, 10}, {0, 10}, {20, 20}, {30, 20}, {30, 30}, {20, 30}})
    c.vertex(x, y);
  c.end_shape();
  EXPECT_EQ(coverage_sum(c), 200);
  Canvas s = counting_canvas(40, 40);
  s.begin_shape(ShapeKind::triangle_strip);  // a strip of 4 vertices: two triangles tiling the square, each pixel once
  for (const auto& [x, y] : {std::pair{0, 0}, {0, 20}, {20, 0}, {20, 20}}) s.vertex(x, y);
  s.end_shape();
  EXPECT_EQ(coverage_sum(s), 400 * 0.5);
}

TEST(Canvas, WritePixelBlendsAndClips) {
  Canvas c(4, 4);
  c.background(Vec4f(0, 0, 1, 1));
  c.write_pixel(1, 1, Vec4f(1, 0, 0, 0.5f));
  EXPECT_NEAR(c.image()(1, 1).x, 0.5f, 1e-6f);
  EXPECT_NEAR(c.image()(1, 1).z, 0.5f, 1e-6f);
  EXPECT_NO_THROW(c.write_pixel(-1, 7, Vec4f(1)));
  EXPECT_EQ(rgb255(255, 150, 150), Vec4f(1, 150 / 255.0f, 150 / 255.0f, 1));
  EXPECT_EQ(gray255(300, -3), Vec4f(1, 1, 1, 0));
}

TEST(Canvas, SaveWritesAFile) {
  Canvas c(8, 8);
  c.fill(rgb255(255, 150, 150));
  c.rect(2, 2, 4, 4);
  const auto path =
      std::filesystem::temp_directory_path() / ("tessera_canvas_test_" + std::to_string(::getpid()) + ".png");
  c.save(path);
  EXPECT_GT(std::filesystem::file_size(path), 0u);
  std::filesystem::remove(path);
}

// Issue 24, class 3: a canvas of a user's size was allocated whatever it cost. 20 bytes a pixel (float RGBA and the
// 8-bit copy a writer makes) are checked against the budget first: 300x300 (1.7 MiB) is refused in 1 MiB, 200x200
// (0.76 MiB) is made.
TEST(Canvas, SizesOverTheMemoryBudgetAreRefusedBeforeAllocating) {
  MemoryBudget::set_limit(1 << 20);
  std::string message = "no error";
  try {
    Canvas big(300, 300);
  } catch (const MemoryBudgetError& e) {
    message = e.what();
  }
  std::optional<Canvas> fits;
  EXPECT_NO_THROW(fits.emplace(200, 200));
  MemoryBudget::set_limit(0);
  EXPECT_EQ(message,
            "a 300x300 canvas needs about 1.7 MiB, the memory budget is 1.0 MiB (raise it with --max-memory "
            "SIZE)");
  EXPECT_THROW(Canvas(-1, 5), InvalidInput);
}

// ---- Text
// -------------------------------------------------------------------------------------------------------------

// The pixels a canvas drew on (alpha > 0 on a transparent canvas), and their bounding box [x0, x1) x [y0, y1).
struct Ink {
  int count = 0, x0 = 1 << 20, y0 = 1 << 20, x1 = -1, y1 = -1;
};
Ink ink_of(const Canvas& c) {
  Ink ink;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x)
      if (c.image()(x, y).w > 0) {
        ++ink.count;
        ink.x0 = std::min(ink.x0, x);
        ink.y0 = std::min(ink.y0, y);
        ink.x1 = std::max(ink.x1, x + 1);
        ink.y1 = std::max(ink.y1, y + 1);
      }
  return ink;
}

bool same_pixels(const Canvas& a, const Canvas& b) {
  return std::ranges::equal(a.image().pixels(), b.image().pixels());
}

Canvas text_canvas() {
  Canvas c(120, 90);
  c.background(Vec4f(0));
  c.fill(Vec4f(1, 1, 1, 1));
  return c;
}

TEST(CanvasText, GlyphPixelsAtNativeSizeAndScaled) {
  for (const bool smooth : {false, true}) {
    Canvas c = text_canvas();
    smooth ? c.smooth() : c.no_smooth();
    c.text("I", 10, 20);  // baseline y = 20: the capital covers rows 13 .. 19
    const Ink i = ink_of(c);
    EXPECT_EQ(i.count, 11);
    EXPECT_EQ(std::tuple(i.x0, i.y0, i.x1, i.y1), std::tuple(11, 13, 14, 20));
    EXPECT_EQ(c.image()(12, 16), Vec4f(1, 1, 1, 1));  // the stem, fully covered
    EXPECT_EQ(c.image()(11, 16), Vec4f(0));
  }
  Canvas dot = text_canvas(), space = text_canvas(), big = text_canvas();
  dot.text(".", 0, 30);
  EXPECT_EQ(ink_of(dot).count, 4);
  space.text("   ", 0, 30);
  EXPECT_EQ(ink_of(space).count, 0);
  big.text_size(24);  // 3 pixels a font unit
  big.text("I", 10, 40);
  EXPECT_EQ(ink_of(big).count, 11 * 9);
  EXPECT_EQ(big.text_ascent(), 21);
  EXPECT_EQ(big.text_descent(), 3);
  EXPECT_EQ(big.text_leading(), 30);
  EXPECT_EQ(big.text_width("I."), 36);
  EXPECT_THROW(big.text_size(0), InvalidInput);
  EXPECT_THROW(big.text_size(std::nan("")), InvalidInput);
}

TEST(CanvasText, AlignmentArithmetic) {
  // "Hi" at text_size 16 (2 pixels a unit) is 24 wide; its ink spans units [0, 10) across and the 7 capital rows.
  const auto box = [](TextAlignX ax, TextAlignY ay, std::string_view text, double x, double y) {
    Canvas c = text_canvas();
    c.no_smooth();
    c.text_size(16);
    c.text_align(ax, ay);
    c.text(text, x, y);
    const Ink i = ink_of(c);
    return std::tuple(i.x0, i.y0, i.x1, i.y1);
  };
  EXPECT_EQ(box(TextAlignX::left, TextAlignY::baseline, "Hi", 10, 30), std::tuple(10, 16, 30, 30));
  EXPECT_EQ(box(TextAlignX::center, TextAlignY::top, "Hi", 50, 30), std::tuple(38, 30, 58, 44));
  EXPECT_EQ(box(TextAlignX::right, TextAlignY::bottom, "Hi", 100, 50), std::tuple(76, 34, 96, 48));  // y - descent
  EXPECT_EQ(box(TextAlignX::left, TextAlignY::center, "Hi", 10, 40), std::tuple(10, 33, 30, 47));    // caps about y
  // Two lines: baseline moves up by one leading (20) for BOTTOM and by half of it for CENTER (Processing's text()).
  EXPECT_EQ(box(TextAlignX::left, TextAlignY::baseline, "H\nH", 10, 30), std::tuple(10, 16, 20, 50));
  EXPECT_EQ(box(TextAlignX::left, TextAlignY::bottom, "H\nH", 10, 80), std::tuple(10, 44, 20, 78));
  EXPECT_EQ(box(TextAlignX::left, TextAlignY::center, "H\nH", 10, 40), std::tuple(10, 23, 20, 57));
  // Each line is aligned on its own.
  EXPECT_EQ(box(TextAlignX::right, TextAlignY::baseline, "H\nHH", 100, 30), std::tuple(76, 16, 98, 50));
  Canvas c = text_canvas();
  c.text_size(16);
  EXPECT_EQ(c.text_width("Hi"), 24);
  EXPECT_EQ(c.text_width("Hi\nthere"), 60);
}

TEST(CanvasText, FollowsTheMatrixAndTheFill) {
  // Text under translate(30, 40) is the text drawn at (30, 40); under scale(2) the text at size 16.
  Canvas moved = text_canvas(), direct = text_canvas(), scaled = text_canvas(), sized = text_canvas();
  moved.translate(30, 40);
  moved.text("Tessera 26", 0, 0);
  direct.text("Tessera 26", 30, 40);
  EXPECT_TRUE(same_pixels(moved, direct));
  scaled.scale(2);
  scaled.text("g!", 5, 20);
  sized.text_size(16);
  sized.text("g!", 10, 40);
  EXPECT_TRUE(same_pixels(scaled, sized));
  // A quarter turn about the anchor: the stem of 'I' (column 2, rows -6 .. -2) becomes a row, as rotate() maps
  // (u, v) to (-v, u) about it.
  Canvas turned = text_canvas();
  turned.no_smooth();
  turned.translate(50, 50);
  turned.rotate(kPi / 2);
  turned.text("I", 0, 0);
  const Ink t = ink_of(turned);
  EXPECT_EQ(t.count, 11);
  EXPECT_EQ(std::tuple(t.x0, t.y0, t.x1, t.y1), std::tuple(50, 51, 57, 54));  // x = 50 - v, v in [-7, 0]; y = 50 + u
  for (int x = 51; x < 56; ++x) EXPECT_EQ(turned.image()(x, 52).w, 1.0f) << x;
  // The fill color, composited; nothing without a fill.
  Canvas red = text_canvas();
  red.fill(Vec4f(1, 0, 0, 0.5f));
  red.text(".", 0, 10);
  EXPECT_EQ(red.image()(1, 8), Vec4f(1, 0, 0, 0.5f));
  red.no_fill();
  red.text("I", 20, 20);
  EXPECT_EQ(ink_of(red).count, 4);
}

// ---- Images
// -----------------------------------------------------------------------------------------------------------

ImageRGBA test_image(int w, int h, float alpha = 1) {
  ImageRGBA img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img(x, y) = Vec4f(float(x) / w, float(y) / h, float((x * 7 + y * 3) % 5) / 4, alpha);
  return img;
}

TEST(CanvasImage, IdentityAndTranslateCopyExactly) {
  const ImageRGBA img = test_image(13, 9);
  for (const bool smooth : {false, true}) {
    Canvas c(40, 30);
    const Vec4f back(0.2f, 0.3f, 0.4f, 1);
    c.background(back);
    smooth ? c.smooth() : c.no_smooth();
    c.translate(5, 2);
    c.image(img, 2, 3);  // lands at (7, 5)
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) {
        const bool in = x >= 7 && x < 20 && y >= 5 && y < 14;
        ASSERT_EQ(c.image()(x, y), in ? img(x - 7, y - 5) : back) << x << "," << y << " smooth " << smooth;
      }
  }
}

TEST(CanvasImage, TwiceTheSizeNearestAndBilinear) {
  const ImageRGBA img = test_image(6, 5);
  Canvas nearest(20, 16), bilinear(20, 16);
  nearest.no_smooth();
  nearest.image(img, 3, 4, 12, 10);
  bilinear.image(img, 3, 4, 12, 10);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 12; ++i) {
      // Nearest: each texel a 2 x 2 block.
      ASSERT_EQ(nearest.image()(3 + i, 4 + j), img(i / 2, j / 2)) << i << "," << j;
      // Bilinear: destination pixel i samples u = (i + 0.5) / 2, a quarter texel before or after texel i / 2's
      // center, so weights 1/4 and 3/4 toward the neighbour on that side (clamped at the edges).
      const auto axis = [](int i, int n) {
        const int t = i / 2, other = std::clamp(i % 2 ? t + 1 : t - 1, 0, n - 1);
        return std::pair(std::pair(t, 0.75), std::pair(other, 0.25));
      };
      const auto [ux, vx] = axis(i, 6);
      const auto [uy, vy] = axis(j, 5);
      const Vec4 want = Vec4(img(ux.first, uy.first)) * ux.second * uy.second +
                        Vec4(img(vx.first, uy.first)) * vx.second * uy.second +
                        Vec4(img(ux.first, vy.first)) * ux.second * vy.second +
                        Vec4(img(vx.first, vy.first)) * vx.second * vy.second;
      const Vec4f got = bilinear.image()(3 + i, 4 + j);
      for (int k = 0; k < 4; ++k) ASSERT_NEAR(got[k], want[k], 1e-6) << i << "," << j << " channel " << k;
    }
  // Outside the rectangle nothing changed.
  EXPECT_EQ(nearest.image()(2, 4), gray255(204));
  EXPECT_EQ(nearest.image()(15, 4), gray255(204));
  EXPECT_EQ(nearest.image()(3, 14), gray255(204));
}

TEST(CanvasImage, RotatedMirroredBlendedAndEightBit) {
  // A quarter turn: image pixel (i, j) lands on device pixel (9 - j, i) under translate(10, 0) rotate(pi / 2).
  const ImageRGBA img = test_image(4, 3);
  Canvas turned(12, 12);
  turned.no_smooth();
  turned.translate(10, 0);
  turned.rotate(kPi / 2);
  turned.image(img, 0, 0);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) EXPECT_EQ(turned.image()(9 - j, i), img(i, j)) << i << "," << j;
  // A negative width mirrors: image(img, x + w, y, -w, h) puts texel i at x + w - 1 - i.
  Canvas mirrored(12, 12);
  mirrored.image(img, 8, 1, -4, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) EXPECT_EQ(mirrored.image()(7 - i, 1 + j), img(i, j));
  // Straight alpha composited over an opaque background: a src + (1 - a) dst.
  const ImageRGBA glass = test_image(3, 3, 0.25f);
  Canvas over(5, 5);
  over.background(Vec4f(0, 0, 1, 1));
  over.image(glass, 1, 1);
  const Vec4f got = over.image()(2, 3), src = glass(1, 2);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], 0.25f * src[k] + 0.75f * (k == 2 ? 1.0f : 0.0f), 1e-6);
  EXPECT_FLOAT_EQ(got.w, 1);
  // 8-bit images: each channel / 255.
  ImageRGBA8 bytes(2, 1);
  bytes(0, 0) = {255, 0, 51, 255};
  bytes(1, 0) = {0, 102, 255, 255};
  Canvas eight(3, 2);
  eight.image(bytes, 1, 1);
  EXPECT_EQ(eight.image()(1, 1), Vec4f(1, 0, 0.2f, 1));
  EXPECT_EQ(eight.image()(2, 1), Vec4f(0, 0.4f, 1, 1));
  // Empty images and singular placements draw nothing.
  Canvas none(4, 4);
  none.image(ImageRGBA(), 0, 0);
  none.image(img, 0, 0, 0, 3);
  none.scale(0);
  none.image(img, 0, 0);
  EXPECT_TRUE(same_pixels(none, Canvas(4, 4)));
}

// ---- Color modes
// ------------------------------------------------------------------------------------------------------

void expect_color(const Vec4f& got, const Vec4& want) {
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[k], want[k], 1e-6) << "channel " << k;
}

TEST(CanvasColor, RgbDefaultsAndRanges) {
  Canvas c(4, 4);
  expect_color(c.color(255, 0, 0), {1, 0, 0, 1});
  expect_color(c.color(51, 102, 153, 127.5), {0.2, 0.4, 0.6, 0.5});
  expect_color(c.color(127.5), {0.5, 0.5, 0.5, 1});
  expect_color(c.color(300, -5, std::nan(""), 999), {1, 0, 0, 1});  // clamped, NaN as 0
  c.color_mode(ColorMode::rgb, 1.0);
  expect_color(c.color(0.2, 0.4, 0.6, 0.5), {0.2, 0.4, 0.6, 0.5});
  expect_color(c.color(0.25, 0.5), {0.25, 0.25, 0.25, 0.5});
  c.color_mode(ColorMode::rgb, 10, 20, 40);  // alpha keeps its range (1)
  expect_color(c.color(5, 5, 10, 0.5), {0.5, 0.25, 0.25, 0.5});
  EXPECT_THROW(c.color_mode(ColorMode::rgb, 0), InvalidInput);
  EXPECT_THROW(c.color_mode(ColorMode::hsb, 360, 100, -1), InvalidInput);
  EXPECT_THROW(c.color_mode(ColorMode::hsb, 360, 100, 100, std::numeric_limits<double>::infinity()), InvalidInput);
}

TEST(CanvasColor, HsbAsColorsys) {
  Canvas c(4, 4);
  c.color_mode(ColorMode::hsb, 360, 100, 100);
  // colorsys.hsv_to_rgb(h / 360, s / 100, b / 100).
  expect_color(c.color(200, 40, 80), {0.48, 0.6933333333333334, 0.8, 1});
  expect_color(c.color(30, 100, 100), {1, 0.5, 0, 1});
  expect_color(c.color(324, 25, 60, 127.5), {0.6, 0.45, 0.54, 0.5});  // alpha keeps 255
  expect_color(c.color(0, 100, 100), {1, 0, 0, 1});
  expect_color(c.color(360, 100, 100), {1, 0, 0, 1});  // the top of the hue range is red again
  expect_color(c.color(120, 100, 100), {0, 1, 0, 1});
  expect_color(c.color(240, 100, 50), {0, 0, 0.5, 1});
  expect_color(c.color(77, 0, 30), {0.3, 0.3, 0.3, 1});
  expect_color(c.color(180), {0.5, 0.5, 0.5, 1});  // a gray reads against the first range, as Processing's
  // color_mode(mode) keeps the ranges; color_mode(mode, max) sets alpha's too.
  Canvas d(4, 4);
  d.color_mode(ColorMode::hsb);
  expect_color(d.color(85, 255, 255), {0, 1, 0, 1});
  d.color_mode(ColorMode::hsb, 100);
  expect_color(d.color(50, 100, 100, 50), {0, 1, 1, 0.5});
  // fill, stroke and background read their numbers the same way.
  d.background(0, 0, 100);
  expect_color(d.image()(0, 0), {1, 1, 1, 1});
  d.background(25);
  expect_color(d.image()(0, 0), {0.25, 0.25, 0.25, 1});
  d.no_stroke();
  d.fill(0, 100, 100);
  d.rect(1, 1, 2, 2);
  expect_color(d.image()(1, 1), {1, 0, 0, 1});
  d.stroke(100.0 / 3, 100, 100);
  d.no_smooth();
  d.point(0.5, 0.5);
  expect_color(d.image()(0, 0), {0, 1, 0, 1});
}

}  // namespace
}  // namespace tessera
