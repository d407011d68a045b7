#include "tessera/raster2d/gt2d.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/math/transform.hpp"
#include "tessera/raster2d/lines.hpp"

namespace tessera::gt2d {
namespace {

// The notes' circle(): GT_LINES over the 20 segments of the unit circle.
void circle() {
  const std::vector<Vec2> v = circle_segments(20);
  gtBeginShape(GT_LINES);
  for (const Vec2& p : v) gtVertex(p.x, p.y);
  gtEndShape();
}

// The notes' circle_image(): three circles with push/pop.
void circle_image() {
  gtPushMatrix();
  gtTranslate(0.5, 0.5);
  gtScale(0.5, 0.5);
  circle();
  gtPopMatrix();
  gtPushMatrix();
  gtTranslate(0.5, 0.25);
  gtScale(0.25, 0.25);
  circle();
  gtPopMatrix();
  gtPushMatrix();
  gtTranslate(0.5, 0.75);
  gtScale(0.25, 0.25);
  circle();
  gtPopMatrix();
}

bool lit(const Context& c, int x, int y) {  // (x, y) in the notes' coordinates, y up
  return c.image()(x, c.image().height() - 1 - y).x > 0;
}

TEST(Gt2d, NotesLineIsDdaWithYUp) {
  Context ctx(400, 400);
  gtMakeCurrent(&ctx);
  gtBeginShape(GT_LINES);
  gtVertex(100.0, 400.0);  // y = 400 is just above the image: clipped
  gtVertex(100.0, 100.0);
  gtEndShape();
  int count = 0;
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) {
      const bool expected = x == 100 && y >= 100 && y < 400;
      EXPECT_EQ(lit(ctx, x, y), expected) << x << "," << y;
      count += lit(ctx, x, y);
    }
  EXPECT_EQ(count, 300);
  EXPECT_EQ(ctx.image()(100, 299), Vec4f(1, 1, 1, 1));  // y = 100 is image row 299
  gtMakeCurrent(nullptr);
}

TEST(Gt2d, CircleImageDrawsThreeCirclesAndRestoresTheStack) {
  Context ctx(400, 400);
  gtMakeCurrent(&ctx);
  gtInitialize(400, 400);
  gtScale(400, 400);
  const Mat3 before = ctx.matrix();
  circle_image();
  EXPECT_EQ(ctx.matrix(), before);
  EXPECT_EQ(ctx.stack_depth(), 1u);
  // Every lit pixel lies on one of the three 20-gons: within a pixel of the circle or inside it by at most the
  // sagitta r (1 - cos(pi / 20)).
  int lit_count = 0;
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) {
      if (!lit(ctx, x, y)) continue;
      ++lit_count;
      bool on_one = false;
      for (const auto& [cx, cy, r] : {std::tuple{200.0, 200.0, 200.0}, {200.0, 100.0, 100.0}, {200.0, 300.0, 100.0}}) {
        const double d = std::hypot(x - cx, y - cy);
        on_one = on_one || (d <= r + 1 && d >= r * std::cos(kPi / 20) - 1);
      }
      EXPECT_TRUE(on_one) << x << "," << y;
    }
  EXPECT_GT(lit_count, 0.9 * 2 * kPi * 400 / std::sqrt(2.0));  // DDA: max(|dx|, |dy|) >= length / sqrt 2 pixels
  // The 20-gon's vertices are lit: (1, 0) of the big circle is (400, 200) -> clipped; (cos 18deg, sin 18deg) is in.
  EXPECT_TRUE(
      lit(ctx, int(std::round(200 + 200 * std::cos(kPi / 10))), int(std::round(200 + 200 * std::sin(kPi / 10)))));
  gtMakeCurrent(nullptr);
}

TEST(Gt2d, TransformsMultiplyOnTheRight) {
  Context ctx(10, 10);
  gtMakeCurrent(&ctx);
  gtTranslate(2, 3);
  gtRotate(kPi / 2);
  gtScale(2, 1);
  // The last call acts first: (1, 0) -> scale (2, 0) -> rotate (0, 2) -> translate (2, 5).
  const Vec2 p = transform_point(ctx.matrix(), Vec2(1, 0));
  EXPECT_NEAR(p.x, 2, 1e-12);
  EXPECT_NEAR(p.y, 5, 1e-12);
  gtPushMatrix();
  gtTranslate(100, 100);
  gtPopMatrix();
  EXPECT_NEAR(transform_point(ctx.matrix(), Vec2(1, 0)).y, 5, 1e-12);
  gtMakeCurrent(nullptr);
}

TEST(Gt2d, ErrorsAndUnderflow) {
  gtMakeCurrent(nullptr);
  EXPECT_THROW(gtPushMatrix(), InvalidInput);
  Context ctx(10, 10);
  gtMakeCurrent(&ctx);
  EXPECT_THROW(gtPopMatrix(), InvalidInput);
  EXPECT_THROW(gtVertex(1, 1), InvalidInput);
  EXPECT_THROW(gtEndShape(), InvalidInput);
  gtBeginShape(GT_LINES);
  EXPECT_THROW(gtBeginShape(GT_LINES), InvalidInput);
  gtEndShape();
  EXPECT_THROW(gtInitialize(-1, 5), InvalidInput);
  gtMakeCurrent(nullptr);
}

TEST(Gt2d, ContextsDoNotInterfere) {
  Context a(20, 20), b(20, 20);
  gtMakeCurrent(&a);
  gtTranslate(5, 5);
  gtMakeCurrent(&b);
  gtColor(1, 0, 0);
  gtBeginShape(GT_POINTS);
  gtVertex(1, 1);
  gtEndShape();
  EXPECT_EQ(b.image()(1, 18), Vec4f(1, 0, 0, 1));
  EXPECT_EQ(a.matrix(), translate2d(5, 5));
  EXPECT_EQ(b.matrix(), Mat3(1.0));
  for (const Vec4f& p : a.image().pixels()) EXPECT_EQ(p, Vec4f(0, 0, 0, 1));
  gtMakeCurrent(nullptr);
}

}  // namespace
}  // namespace tessera::gt2d
