#include "tessera/fractal/dimension.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/fractal/draw.hpp"
#include "tessera/fractal/self_similar.hpp"

namespace tessera {
namespace {

Image<uint8_t> rendered(const std::vector<std::vector<Vec2>>& polygons, int width, int height) {
  return ink_mask(draw_polygons(polygons, PictureFrame{width, height}));
}

TEST(Dimension, FilledSquareAndLine) {
  Image<uint8_t> full(256, 256, 1);
  EXPECT_NEAR(box_counting_dimension(full).dimension, 2.0, 1e-12);
  Image<uint8_t> line(256, 256, 0);
  for (int x = 0; x < 256; ++x) line(x, 100) = 1;
  EXPECT_NEAR(box_counting_dimension(line).dimension, 1.0, 1e-12);
}

TEST(Dimension, SierpinskiCarpet) {
  const double formula = similarity_dimension(8, 3);  // 1.8928
  const Image<uint8_t> mask = rendered(as_polygons(sierpinski_carpet(6)), 729, 729);
  // Boxes of 3^k pixels line up with the construction: N(3^k) = 8^(6-k) exactly.
  const BoxCountResult triadic = box_counting_dimension(mask, {1, 81, 3});
  EXPECT_EQ(triadic.counts.front(), 262144);
  EXPECT_NEAR(triadic.dimension, formula, 1e-9);
  // Power-of-two boxes do not line up, and still land within 0.05.
  EXPECT_NEAR(box_counting_dimension(mask).dimension, formula, 0.05);
}

TEST(Dimension, CantorSetOnARowOfPixels) {
  // The 1D Cantor set (0.6309) as one row of 3^8 pixels: boxes of s x s pixels count the covering intervals.
  const double formula = similarity_dimension(2, 3);
  std::vector<Rect> bars;
  for (const Interval& i : cantor_set(8)) bars.push_back({i.a, 0.0, i.b - i.a, 1.0});
  const Image<uint8_t> mask = rendered(as_polygons(bars), 6561, 1);
  EXPECT_NEAR(box_counting_dimension(mask, {1, 729, 3}).dimension, formula, 1e-9);
  EXPECT_NEAR(box_counting_dimension(mask, {2, 1024, 2}).dimension, formula, 0.05);
}

TEST(Dimension, CantorDustIsTwiceTheCantorSet) {
  // Cantor dust = Cantor set x Cantor set: 4 copies at 1/3, D = log 4 / log 3 = 2 * 0.6309 = 1.2619.
  const Image<uint8_t> mask = rendered(as_polygons(cantor_dust(6)), 729, 729);
  EXPECT_NEAR(box_counting_dimension(mask, {1, 81, 3}).dimension, similarity_dimension(4, 3), 1e-9);
  EXPECT_NEAR(box_counting_dimension(mask).dimension, similarity_dimension(4, 3), 0.05);
}

TEST(Dimension, KochCurve) {
  // A one-pixel stroke of the depth-7 curve (segments of ~1 pixel) over 2187 pixels.
  const PictureFrame frame{2187, 700, 0, {0.0, -0.02, 1.0, 700.0 / 2187.0}};
  const Image<uint8_t> mask = ink_mask(draw_curve(koch_curve(7), false, frame));
  EXPECT_NEAR(box_counting_dimension(mask, {3, 243, 3}).dimension, similarity_dimension(4, 3), 0.05);
  EXPECT_NEAR(box_counting_dimension(mask, {2, 256, 2}).dimension, similarity_dimension(4, 3), 0.05);
}

TEST(Dimension, RejectsEmptyImagesAndBadOptions) {
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(64, 64, 0)), InvalidInput);
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(64, 64, 1), {0, 8, 2}), InvalidInput);
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(64, 64, 1), {2, 8, 1.0}), InvalidInput);
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(4, 4, 1), {2, 2, 2}), InvalidInput);
}

}  // namespace
}  // namespace tessera
