#include "tessera/fractal/dimension.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/fractal/draw.hpp"
#include "tessera/fractal/self_similar.hpp"

namespace tessera {
namespace {

// The analytic dimensions the tests compare with (docs/fractal.md lists the tolerances).
const double kCantor = std::log(2.0) / std::log(3.0);      // 0.6309
const double kSierpinski = std::log(3.0) / std::log(2.0);  // 1.5850
const double kKoch = std::log(4.0) / std::log(3.0);        // 1.2619
const double kCarpet = std::log(8.0) / std::log(3.0);      // 1.8928

Image<uint8_t> rendered(const std::vector<std::vector<Vec2>>& polygons, int width, int height) {
  return ink_mask(draw_polygons(polygons, PictureFrame{width, height}));
}

/// The depth-n Cantor set as a row (or a column) of `length` pixels starting at pixel (x, y) of a width x height
/// mask: a pixel is set where its center lies in one of the 2^n intervals.
Image<uint8_t> cantor_line(int width, int height, int x, int y, int length, int depth, bool vertical = false) {
  Image<uint8_t> mask(width, height, 0);
  for (const Interval& i : cantor_set(depth))
    for (int p = 0; p < length; ++p) {
      const double center = (p + 0.5) / length;
      if (center >= i.a && center < i.b) (vertical ? mask(x, y + p) : mask(x + p, y)) = 1;
    }
  return mask;
}

TEST(Dimension, FilledSquaresAndLinesAreExactAtAnySizeAndPlace) {
  // Boxes of extent / 2^k cut a filled L x L square into 4^k boxes and a line of L pixels into 2^k, whatever L.
  for (int side : {100, 256, 300, 731}) {
    Image<uint8_t> square(side + 57, side + 3, 0), row(side + 20, 64, 0), diagonal(side + 9, side + 5, 0);
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) square(x + 41, y + 2) = 1;
    for (int x = 0; x < side; ++x) row(x + 13, 40) = 1, diagonal(x + 4, x + 1) = 1;
    EXPECT_NEAR(box_counting_dimension(square).dimension, 2.0, 1e-12) << side;
    EXPECT_NEAR(box_counting_dimension(row).dimension, 1.0, 1e-12) << side;
    EXPECT_NEAR(box_counting_dimension(diagonal).dimension, 1.0, 1e-12) << side;
  }
}

TEST(Dimension, CantorRowAcrossAWidePicture) {
  // The case: the depth-7 Cantor set as one row of 2187 pixels across a 2187 x 64 picture. The old default
  // (boxes up to a quarter of the shorter side, 16 pixels) measured 0.53.
  const Image<uint8_t> mask = cantor_line(2187, 64, 0, 31, 2187, 7);
  const BoxCountResult r = box_counting_dimension(mask);
  EXPECT_EQ(r.extent, 2187);
  EXPECT_DOUBLE_EQ(r.sizes.front(), 2187.0);
  EXPECT_GE(r.sizes.back(), 1.0);
  EXPECT_LT(r.sizes.back(), 2.0);
  EXPECT_EQ(r.counts.back(), 128);  // the 2^7 one-pixel intervals
  EXPECT_NEAR(r.dimension, kCantor, 0.02);
  // Triadic boxes line up with the construction: N(3^k) = 2^(7-k) exactly.
  EXPECT_NEAR(box_counting_dimension(mask, {1, 0, 3}).dimension, kCantor, 1e-9);
}

TEST(Dimension, CantorRowsAndColumnsOfOtherLengthsAspectsAndOffsets) {
  struct Case {
    int width, height, x, y, length, depth;
    bool vertical;
  };
  // Lengths that are not powers of 3 (intervals of a pixel or more), odd aspect ratios, offsets, a column.
  for (const Case& c :
       {Case{64, 2187, 20, 0, 2187, 7, true}, Case{3050, 5, 17, 4, 3000, 7, false},
        Case{1200, 7, 150, 3, 1000, 6, false}, Case{9, 740, 8, 11, 729, 6, true}, Case{6600, 3, 39, 0, 6561, 8, false},
        Case{520, 520, 3, 500, 500, 5, false}, Case{250, 1, 7, 0, 243, 5, false}}) {
    const Image<uint8_t> mask = cantor_line(c.width, c.height, c.x, c.y, c.length, c.depth, c.vertical);
    EXPECT_NEAR(box_counting_dimension(mask).dimension, kCantor, 0.04) << c.width << "x" << c.height;
  }
}

TEST(Dimension, WhereTheSetLiesDoesNotChangeTheCounts) {
  const Image<uint8_t> corner = rendered(as_polygons(sierpinski_triangle(6)), 256, 256);
  Image<uint8_t> moved(400, 333, 0);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) moved(x + 97, y + 61) = corner(x, y);
  const BoxCountResult a = box_counting_dimension(corner), b = box_counting_dimension(moved);
  EXPECT_EQ(a.sizes, b.sizes);
  EXPECT_EQ(a.counts, b.counts);
  EXPECT_DOUBLE_EQ(a.dimension, b.dimension);
}

TEST(Dimension, SierpinskiTriangle) {
  // Pixel-exact: the pixels (x, y) with x & y == 0 (Pascal's triangle mod 2) over 2^9 pixels, placed off the corner;
  // boxes of 2^k pixels hold exactly 3^(9-k) of them.
  Image<uint8_t> pascal(600, 530, 0);
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) pascal(x + 70, y + 9) = (x & y) == 0;
  const BoxCountResult exact = box_counting_dimension(pascal);
  EXPECT_EQ(exact.counts.back(), 19683);  // 3^9
  EXPECT_NEAR(exact.dimension, kSierpinski, 1e-9);
  // Drawn filled, its smallest triangles 16 pixels wide: below that the picture is solid (or loses the pixels whose
  // centers miss a thin triangle), so the fit over 1 pixel to the extent lands within 0.03.
  for (const auto& [side, depth] : {std::pair{512, 5}, {1000, 6}, {1024, 6}, {2048, 7}}) {
    const Image<uint8_t> mask = rendered(as_polygons(sierpinski_triangle(depth)), side, side);
    EXPECT_NEAR(box_counting_dimension(mask).dimension, kSierpinski, 0.03) << side;
  }
}

TEST(Dimension, SierpinskiCarpet) {
  const Image<uint8_t> mask = rendered(as_polygons(sierpinski_carpet(6)), 729, 729);
  // Boxes of 3^k pixels line up with the construction: N(3^k) = 8^(6-k) exactly.
  const BoxCountResult triadic = box_counting_dimension(mask, {1, 81, 3});
  EXPECT_EQ(triadic.counts.back(), 262144);
  EXPECT_NEAR(triadic.dimension, kCarpet, 1e-9);
  // Power-of-two divisions do not line up, and still land within 0.05.
  EXPECT_NEAR(box_counting_dimension(mask).dimension, kCarpet, 0.05);
}

TEST(Dimension, CantorDustIsTwiceTheCantorSet) {
  // Cantor dust = Cantor set x Cantor set: 4 copies at 1/3, D = log 4 / log 3 = 2 * 0.6309 = 1.2619.
  const Image<uint8_t> mask = rendered(as_polygons(cantor_dust(6)), 729, 729);
  EXPECT_NEAR(box_counting_dimension(mask, {1, 0, 3}).dimension, similarity_dimension(4, 3), 1e-9);
  EXPECT_NEAR(box_counting_dimension(mask).dimension, similarity_dimension(4, 3), 0.05);
}

TEST(Dimension, KochCurve) {
  // A one-pixel stroke of the depth-7 curve (segments of ~1 pixel) over 2187 pixels, and a smaller one off center.
  const PictureFrame frame{2187, 700, 0, {0.0, -0.02, 1.0, 700.0 / 2187.0}};
  const Image<uint8_t> mask = ink_mask(draw_curve(koch_curve(7), false, frame));
  EXPECT_NEAR(box_counting_dimension(mask).dimension, kKoch, 0.05);
  EXPECT_NEAR(box_counting_dimension(mask, {3, 729, 3}).dimension, kKoch, 0.05);
  const PictureFrame small{900, 900, 0, {-0.7, -1.2, 2.0, 2.0}};
  EXPECT_NEAR(box_counting_dimension(ink_mask(draw_curve(koch_curve(6), false, small))).dimension, kKoch, 0.05);
}

TEST(Dimension, RejectsEmptyImagesAndBadOptions) {
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(64, 64, 0)), InvalidInput);
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(64, 64, 1), {0, 8, 2}), InvalidInput);
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(64, 64, 1), {2, 8, 1.0}), InvalidInput);
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(64, 64, 1), {1, -4, 2}), InvalidInput);
  // Boxes of 2 and 4 pixels over a 4 x 4 set: only one size sees more than one box.
  EXPECT_THROW(box_counting_dimension(Image<uint8_t>(4, 4, 1), {2, 4, 2}), InvalidInput);
  Image<uint8_t> dot(50, 50, 0);
  dot(20, 30) = 1;
  EXPECT_THROW(box_counting_dimension(dot), InvalidInput);  // one pixel: every box count is 1
}

}  // namespace
}  // namespace tessera
