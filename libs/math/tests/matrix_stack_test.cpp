#include "tessera/math/matrix_stack.hpp"

#include <gtest/gtest.h>

#include "tessera/math/transform.hpp"

namespace tessera {
namespace {

TEST(MatrixStack, StartsAsIdentity) {
  MatrixStack3 s;
  EXPECT_EQ(s.depth(), 1u);
  EXPECT_EQ(s.top(), Mat4(1.0));
}

TEST(MatrixStack, PushDuplicatesPopDiscards) {
  MatrixStack2 s;
  s.multiply(translate2d(1, 2));
  s.push();
  EXPECT_EQ(s.depth(), 2u);
  EXPECT_EQ(s.top(), translate2d(1, 2));
  s.multiply(scale2d(3, 3));
  s.pop();
  EXPECT_EQ(s.top(), translate2d(1, 2));
}

TEST(MatrixStack, UnderflowIsAnError) {
  MatrixStack3 s;
  EXPECT_THROW(s.pop(), InvalidInput);
  s.push();
  s.pop();
  EXPECT_THROW(s.pop(), InvalidInput);
}

TEST(MatrixStack, LastWrittenActsFirst) {
  // The notes: glScale(2,2); glTranslate(-2,0); draw -> the translate happens first, then the scale.
  MatrixStack2 s;
  s.multiply(scale2d(2, 2));
  s.multiply(translate2d(-2, 0));
  const Vec2 p = transform_point(s.top(), {1, 1});
  EXPECT_EQ(p, Vec2(-2, 2));  // (1,1) -> (-1,1) -> (-2,2)
}

TEST(MatrixStack, CircleImageExample) {
  // The notes' circle_image: push, translate(0.5,0.5), scale(0.5,0.5) maps the unit circle's (1,0) to (1,0.5).
  MatrixStack2 s;
  s.push();
  s.multiply(translate2d(0.5, 0.5));
  s.multiply(scale2d(0.5, 0.5));
  EXPECT_EQ(transform_point(s.top(), {1, 0}), Vec2(1, 0.5));
  s.pop();
  EXPECT_EQ(s.top(), Mat3(1.0));
}

}  // namespace
}  // namespace tessera
