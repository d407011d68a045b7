#include "tessera/fractal/draw.hpp"

#include <gtest/gtest.h>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

TEST(Draw, UnitSquareMapsOntoThePictureWithYUp) {
  const PictureFrame frame{100, 50, 10, {0, 0, 1, 1}};
  EXPECT_EQ(to_pixels(frame, {0, 0}), Vec2(10, 40));
  EXPECT_EQ(to_pixels(frame, {1, 1}), Vec2(90, 10));
}

TEST(Draw, FrameAroundKeepsTheAspectAndCenters) {
  const PictureFrame frame = frame_around({{0, 0}, {2, 1}}, 100, 100, 10);
  EXPECT_EQ(to_pixels(frame, {0, 0.5}), Vec2(10, 50));
  EXPECT_EQ(to_pixels(frame, {2, 0.5}), Vec2(90, 50));
  EXPECT_NEAR(to_pixels(frame, {1, 1}).y, 30, 1e-12);  // 40 pixels per unit in both directions
  EXPECT_THROW(frame_around({}, 100, 100, 10), InvalidInput);
}

TEST(Draw, CarpetPixelsAreExactAtPowersOfThree) {
  // Depth 2 on 27 x 27: every remaining cell is a 3 x 3 block of ink; 64 cells of 9 pixels.
  const PictureFrame frame{27, 27};
  const Image<uint8_t> mask = ink_mask(draw_polygons(as_polygons(sierpinski_carpet(2)), frame));
  int ink = 0;
  for (uint8_t v : mask.pixels()) ink += v;
  EXPECT_EQ(ink, 64 * 9);
  EXPECT_EQ(mask(13, 13), 0);  // the middle ninth
  EXPECT_EQ(mask(4, 4), 0);    // the middle of the top-left ninth
  EXPECT_EQ(mask(0, 0), 1);
}

TEST(Draw, CurvesLeaveInkAlongThePolyline) {
  const PictureFrame frame{64, 64, 4};
  const ImageRGBA picture = draw_curve(hilbert_curve(2), false, frame, DrawStyle{{0, 0, 0}, {1, 1, 1}, 2.0, false});
  const Image<uint8_t> mask = ink_mask(picture);
  for (const Vec2& p : hilbert_curve(2)) {
    const Vec2 q = to_pixels(frame, p);
    EXPECT_EQ(mask(int(q.x), int(q.y)), 1) << q.x << "," << q.y;
  }
  EXPECT_EQ(mask(1, 1), 0);  // inside the margin
  EXPECT_THROW(draw_curve({{0, 0}, {1, 1}}, false, frame, DrawStyle{{0, 0, 0}, {1, 1, 1}, 0.0, false}), InvalidInput);
}

TEST(Draw, InkMaskThresholdAndInvert) {
  ImageRGBA picture(2, 1, Vec4f(1.0f));
  picture(0, 0) = Vec4f(0.1f, 0.1f, 0.1f, 1.0f);
  EXPECT_EQ(ink_mask(picture)(0, 0), 1);
  EXPECT_EQ(ink_mask(picture)(1, 0), 0);
  EXPECT_EQ(ink_mask(picture, 0.5f, true)(0, 0), 0);
}

TEST(Draw, InkMaskSeesTransparencyAsPaper) {
  // Black ink on a transparent background (straight alpha, as PNG and canvas render store it): over white paper the
  // background is white, the ink black, and half-transparent black is mid gray (luminance 0.5: not below 0.5).
  ImageRGBA picture(4, 1, Vec4f(0.0f));
  picture(0, 0) = Vec4f(0, 0, 0, 1), picture(1, 0) = Vec4f(0, 0, 0, 0.5f), picture(2, 0) = Vec4f(0, 0, 0, 0.6f);
  const Image<uint8_t> mask = ink_mask(picture);
  EXPECT_EQ(mask(0, 0), 1);
  EXPECT_EQ(mask(1, 0), 0);
  EXPECT_EQ(mask(2, 0), 1);
  EXPECT_EQ(mask(3, 0), 0);
  // Light on dark: white ink on a transparent background, seen over black paper.
  picture(0, 0) = Vec4f(1, 1, 1, 1), picture(1, 0) = Vec4f(1, 1, 1, 0.4f);
  const Image<uint8_t> light = ink_mask(picture, 0.5f, true);
  EXPECT_EQ(light(0, 0), 1);
  EXPECT_EQ(light(1, 0), 0);
  EXPECT_EQ(light(3, 0), 0);
}

}  // namespace
}  // namespace tessera
