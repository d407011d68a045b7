#include "tessera/image/image.hpp"

#include <gtest/gtest.h>

namespace tessera {
namespace {

TEST(Image, ConstructsFilledRowMajorFromTheTop) {
  Image<int> image(3, 2, 7);
  EXPECT_EQ(image.width(), 3);
  EXPECT_EQ(image.height(), 2);
  EXPECT_FALSE(image.empty());
  for (int v : image.pixels()) EXPECT_EQ(v, 7);
  image(2, 0) = 1;
  image(0, 1) = 2;
  EXPECT_EQ(image.pixels()[2], 1);  // row 0 first
  EXPECT_EQ(image.pixels()[3], 2);
  EXPECT_EQ(image.row(1)[0], 2);
}

TEST(Image, DefaultIsEmpty) {
  const ImageRGB image;
  EXPECT_TRUE(image.empty());
  EXPECT_EQ(image.width(), 0);
  EXPECT_EQ(image.height(), 0);
}

TEST(Image, RejectsNegativeAndAbsurdSizes) {
  EXPECT_THROW(Image<float>(-1, 3), InvalidInput);
  EXPECT_THROW(Image<float>(3, -1), InvalidInput);
  EXPECT_THROW(Image<float>(1 << 20, 1 << 20), InvalidInput);
}

TEST(Image, AtChecksBounds) {
  Image<int> image(2, 2, 0);
  image.at(1, 1) = 5;
  EXPECT_EQ(std::as_const(image).at(1, 1), 5);
  EXPECT_THROW(image.at(2, 0), InvalidInput);
  EXPECT_THROW(image.at(0, -1), InvalidInput);
  EXPECT_TRUE(image.contains(1, 1));
  EXPECT_FALSE(image.contains(-1, 0));
}

TEST(Image, FillSetsEveryPixel) {
  DepthImage image(4, 3, 0.f);
  image.fill(2.5f);
  for (float v : image.pixels()) EXPECT_EQ(v, 2.5f);
}

TEST(ImageView, SubViewWritesThroughToTheImage) {
  Image<int> image(5, 4, 0);
  const ImageView<int> sub = image.view(1, 2, 3, 2);
  EXPECT_EQ(sub.width(), 3);
  EXPECT_EQ(sub.height(), 2);
  EXPECT_EQ(sub.stride(), 5);
  sub.fill(9);
  int count = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) {
      const bool inside = x >= 1 && x < 4 && y >= 2 && y < 4;
      EXPECT_EQ(image(x, y), inside ? 9 : 0) << x << "," << y;
      count += inside;
    }
  EXPECT_EQ(count, 6);
  sub(0, 0) = 4;
  EXPECT_EQ(image(1, 2), 4);
  EXPECT_EQ(sub.row(1), &image(1, 3));
}

TEST(ImageView, SubViewIsClippedAndNests) {
  Image<int> image(4, 4, 0);
  const ImageView<int> clipped = image.view(-2, 3, 10, 10);
  EXPECT_EQ(clipped.width(), 4);
  EXPECT_EQ(clipped.height(), 1);
  const ImageView<int> nested = image.view(1, 1, 3, 3).sub(1, 1, 5, 5);
  EXPECT_EQ(nested.width(), 2);
  EXPECT_EQ(nested.height(), 2);
  nested(1, 1) = 3;
  EXPECT_EQ(image(3, 3), 3);
  EXPECT_TRUE(nested.contains(1, 1));
  EXPECT_FALSE(nested.contains(2, 0));
  const ImageView<int> outside = image.view(10, 10, 2, 2);
  EXPECT_EQ(outside.width(), 0);
  EXPECT_EQ(outside.height(), 0);
}

TEST(ImageView, ConstViewsReadTheSamePixels) {
  Image<int> image(3, 3, 0);
  image(2, 1) = 8;
  const ImageView<const int> whole = std::as_const(image).view();
  EXPECT_EQ(whole(2, 1), 8);
  const ImageView<const int> converted = image.view(1, 1, 2, 2);
  EXPECT_EQ(converted(1, 0), 8);
  EXPECT_EQ(std::as_const(image).view(2, 1, 1, 1)(0, 0), 8);
}

}  // namespace
}  // namespace tessera
