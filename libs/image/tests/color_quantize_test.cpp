#include "color_quantize.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tessera/core/error.hpp"

namespace tessera::detail {
namespace {

int squared_distance(Rgb8 a, Rgb8 b) {
  const int dr = a.x - b.x, dg = a.y - b.y, db = a.z - b.z;
  return dr * dr + dg * dg + db * db;
}

// The brute-force nearest color with the mapper's tie rule (lowest index).
int brute_nearest(const std::vector<Rgb8>& palette, Rgb8 c) {
  int best = 0;
  for (size_t i = 1; i < palette.size(); ++i)
    if (squared_distance(palette[i], c) < squared_distance(palette[size_t(best)], c)) best = int(i);
  return best;
}

std::vector<Rgb8> random_colors(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Rgb8> colors(n);
  for (Rgb8& c : colors) c = Rgb8(rng() & 255, rng() & 255, rng() & 255);
  return colors;
}

// A smooth two-dimensional gradient with 64 x 64 = 4096 distinct colors.
std::vector<Rgb8> gradient(int w, int h) {
  std::vector<Rgb8> pixels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) pixels.emplace_back(x * 255 / (w - 1), y * 255 / (h - 1), 255 - x * 255 / (w - 1));
  return pixels;
}

TEST(ColorQuantize, DistinctColorsAreSortedAndLimited) {
  const std::vector<Rgb8> pixels = {{9, 9, 9}, {1, 2, 3}, {9, 9, 9}, {0, 0, 255}, {1, 2, 3}};
  const auto colors = distinct_colors(pixels);
  ASSERT_TRUE(colors);
  EXPECT_EQ(*colors, (std::vector<Rgb8>{{0, 0, 255}, {1, 2, 3}, {9, 9, 9}}));
  EXPECT_FALSE(distinct_colors(pixels, 2));
  EXPECT_TRUE(distinct_colors(pixels, 3));
}

TEST(ColorQuantize, FewColorsGiveTheExactPalette) {
  std::vector<Rgb8> pixels = random_colors(256, 1);
  for (int i = 0; i < 1000; ++i) pixels.push_back(pixels[size_t(i * 7 % 256)]);
  const std::vector<Rgb8> palette = quantize_palette(pixels);
  ASSERT_EQ(palette.size(), 256u);
  PaletteMapper mapper(palette);
  for (const Rgb8& p : pixels) EXPECT_EQ(palette[mapper.nearest(p.x, p.y, p.z)], p);
}

TEST(ColorQuantize, NearestIsTheBruteForceNearest) {
  for (size_t size : {1u, 2u, 17u, 200u, 256u}) {
    const std::vector<Rgb8> palette = random_colors(size, unsigned(size));
    PaletteMapper mapper(palette);
    for (const Rgb8& c : random_colors(20000, 99)) ASSERT_EQ(mapper.nearest(c.x, c.y, c.z), brute_nearest(palette, c));
    for (int corner = 0; corner < 8; ++corner) {
      const Rgb8 c((corner & 1) * 255, (corner >> 1 & 1) * 255, (corner >> 2) * 255);
      EXPECT_EQ(mapper.nearest(c.x, c.y, c.z), brute_nearest(palette, c));
    }
  }
}

TEST(ColorQuantize, MedianCutFitsASmoothGradient) {
  const std::vector<Rgb8> pixels = gradient(64, 64);
  const std::vector<Rgb8> palette = quantize_palette(pixels);
  EXPECT_LE(palette.size(), 256u);
  EXPECT_GE(palette.size(), 200u);  // 4096 colors spread evenly use nearly all entries
  PaletteMapper mapper(palette);
  double sum = 0;
  int worst = 0;
  for (const Rgb8& p : pixels) {
    const Rgb8 q = palette[mapper.nearest(p.x, p.y, p.z)];
    for (int a = 0; a < 3; ++a) {
      sum += std::abs(p[a] - q[a]);
      worst = std::max(worst, std::abs(p[a] - q[a]));
    }
  }
  // 4096 colors on a 2D sheet shared by 256 colors: about 4 x 4 gradient steps of 4 levels each per color, whose mean
  // distance from their center is 4 levels along each axis; never more than a few steps.
  EXPECT_LT(sum / (3.0 * double(pixels.size())), 4.5);
  EXPECT_LE(worst, 16);
}

TEST(ColorQuantize, DitheringKeepsTheMeanOfAFlatArea) {
  // Floyd-Steinberg diffuses all of each pixel's error, so a flat gray g between black and white becomes white on
  // g/255 of the pixels (up to the error left at the borders).
  const int w = 128, h = 128;
  PaletteMapper mapper({{0, 0, 0}, {255, 255, 255}});
  for (int gray : {64, 128, 200}) {
    const std::vector<Rgb8> pixels(size_t(w * h), Rgb8(gray));
    std::vector<uint8_t> out(pixels.size());
    map_to_palette(pixels, w, h, mapper, true, out);
    const double white = double(std::count(out.begin(), out.end(), 1)) / double(out.size());
    EXPECT_NEAR(white, gray / 255.0, 0.005) << gray;
    map_to_palette(pixels, w, h, mapper, false, out);
    EXPECT_EQ(std::count(out.begin(), out.end(), gray < 128 ? 0 : 1), w * h) << gray;
  }
}

TEST(ColorQuantize, DitheringReproducesPaletteColorsExactly) {
  const std::vector<Rgb8> palette = random_colors(50, 7);
  std::mt19937 rng(3);
  std::vector<Rgb8> pixels(40 * 30);
  for (Rgb8& p : pixels) p = palette[rng() % palette.size()];
  PaletteMapper mapper(palette);
  std::vector<uint8_t> out(pixels.size());
  map_to_palette(pixels, 40, 30, mapper, true, out);
  for (size_t i = 0; i < pixels.size(); ++i) ASSERT_EQ(palette[out[i]], pixels[i]) << i;
}

TEST(ColorQuantize, RefusesBadPaletteSizes) {
  EXPECT_THROW(PaletteMapper({}), InvalidInput);
  EXPECT_THROW(PaletteMapper(std::vector<Rgb8>(257)), InvalidInput);
  EXPECT_THROW(quantize_palette(gradient(4, 4), 0), InvalidInput);
}

}  // namespace
}  // namespace tessera::detail
