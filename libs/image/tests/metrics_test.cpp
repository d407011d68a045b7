#include "tessera/image/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tessera {
namespace {

TEST(Metrics, EqualImagesHaveZeroErrorAndInfinitePsnr) {
  const ImageRGB a(4, 3, glm::vec3(0.25f, 0.5f, 1.f));
  EXPECT_EQ(max_abs_difference(a, a), 0.0);
  EXPECT_EQ(rmse(a, a), 0.0);
  EXPECT_EQ(psnr(a, a), std::numeric_limits<double>::infinity());
  EXPECT_EQ(count_differing_pixels(a, a), 0);
}

TEST(Metrics, HandWorkedFloatExample) {
  // Two pixels; one channel off by 0.5 and another by -0.25 in the second pixel only.
  ImageRGB a(2, 1, glm::vec3(0.f)), b(2, 1, glm::vec3(0.f));
  b(1, 0) = glm::vec3(0.5f, -0.25f, 0.f);
  EXPECT_DOUBLE_EQ(max_abs_difference(a, b), 0.5);
  const double mse = (0.25 + 0.0625) / 6.0;
  EXPECT_DOUBLE_EQ(rmse(a, b), std::sqrt(mse));
  EXPECT_DOUBLE_EQ(psnr(a, b), 10.0 * std::log10(1.0 / mse));
  EXPECT_DOUBLE_EQ(psnr(a, b, 2.0), 10.0 * std::log10(4.0 / mse));
  EXPECT_EQ(count_differing_pixels(a, b), 1);
  EXPECT_EQ(count_differing_pixels(a, b, 0.3), 1);
  EXPECT_EQ(count_differing_pixels(a, b, 0.5), 0);
}

TEST(Metrics, EightBitUsesPeak255AndCountsAlpha) {
  ImageRGBA8 a(3, 1, glm::u8vec4(10, 20, 30, 255)), b = a;
  b(0, 0).w = 250;  // alpha differs by 5
  b(2, 0).x = 13;   // red differs by 3
  EXPECT_EQ(max_abs_difference(a, b), 5.0);
  const double mse = (25.0 + 9.0) / 12.0;
  EXPECT_DOUBLE_EQ(rmse(a, b), std::sqrt(mse));
  EXPECT_DOUBLE_EQ(psnr(a, b), 10.0 * std::log10(255.0 * 255.0 / mse));
  EXPECT_EQ(count_differing_pixels(a, b), 2);
  EXPECT_EQ(count_differing_pixels(a, b, 3), 1);
  EXPECT_EQ(count_differing_pixels(a, b, 5), 0);
}

TEST(Metrics, RgbaAndDepthOverloads) {
  ImageRGBA a(2, 2, glm::vec4(1.f)), b = a;
  b(1, 1).w = 0.f;
  EXPECT_EQ(max_abs_difference(a, b), 1.0);
  EXPECT_DOUBLE_EQ(rmse(a, b), std::sqrt(1.0 / 16.0));
  EXPECT_EQ(count_differing_pixels(a, b), 1);
  DepthImage da(2, 1, 1.f), db(2, 1, 1.f);
  db(0, 0) = 0.5f;
  EXPECT_EQ(max_abs_difference(da, db), 0.5);
  EXPECT_DOUBLE_EQ(rmse(da, db), std::sqrt(0.125));
  EXPECT_DOUBLE_EQ(psnr(da, db), 20.0 * std::log10(1.0 / std::sqrt(0.125)));
}

TEST(Metrics, NanCountsAsDifferent) {
  DepthImage a(1, 1, 0.f), b(1, 1, std::numeric_limits<float>::quiet_NaN());
  EXPECT_EQ(count_differing_pixels(a, b, 1e9), 1);
  EXPECT_TRUE(std::isnan(max_abs_difference(a, b)));
}

TEST(Metrics, SizeMismatchThrows) {
  const ImageRGB a(2, 2), b(2, 3);
  EXPECT_THROW(max_abs_difference(a, b), InvalidInput);
  EXPECT_THROW(rmse(a, b), InvalidInput);
  EXPECT_THROW(psnr(a, b), InvalidInput);
  EXPECT_THROW(count_differing_pixels(a, b), InvalidInput);
  EXPECT_THROW(rmse(ImageRGBA8(1, 2), ImageRGBA8(2, 1)), InvalidInput);
}

TEST(Metrics, EmptyImagesCompareEqual) {
  const ImageRGB a, b;
  EXPECT_EQ(rmse(a, b), 0.0);
  EXPECT_EQ(count_differing_pixels(a, b), 0);
}

}  // namespace
}  // namespace tessera
