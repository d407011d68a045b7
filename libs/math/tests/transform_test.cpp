// The notes' transforms checked against GLM's own implementations (an independent reference) and the notes' facts.
#include "tessera/math/transform.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

template <class M>
double max_diff(const M& a, const M& b) {
  double d = 0;
  for (int c = 0; c < M::length(); ++c)
    for (int r = 0; r < M::col_type::length(); ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
  return d;
}

class RandomInputs : public ::testing::Test {
 protected:
  std::mt19937 gen{12345};
  double uni(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
  Vec3 vec(double lo, double hi) { return {uni(lo, hi), uni(lo, hi), uni(lo, hi)}; }
};

TEST_F(RandomInputs, RotateAboutAxisMatchesGlm) {
  for (int i = 0; i < 500; ++i) {
    const Vec3 axis = vec(-5, 5);
    const double theta = uni(-2 * kPi, 2 * kPi);
    EXPECT_LT(max_diff(rotate(theta, axis), glm::rotate(Mat4(1.0), theta, axis)), 1e-6) << i;
  }
  // The axes the notes' choice of N is about: ax = 0 and axes along y and x.
  for (const Vec3 axis : {Vec3(0, 1, 0), Vec3(0, -2, 0), Vec3(0, 1, 1), Vec3(3, 0, 0), Vec3(0, 0, 1)})
    EXPECT_LT(max_diff(rotate(0.7, axis), glm::rotate(Mat4(1.0), 0.7, axis)), 1e-12);
}

TEST_F(RandomInputs, AxisRotationsMatchGlm) {
  for (int i = 0; i < 200; ++i) {
    const double t = uni(-7, 7);
    EXPECT_LT(max_diff(rotate_x(t), glm::rotate(Mat4(1.0), t, Vec3(1, 0, 0))), 1e-12);
    EXPECT_LT(max_diff(rotate_y(t), glm::rotate(Mat4(1.0), t, Vec3(0, 1, 0))), 1e-12);
    EXPECT_LT(max_diff(rotate_z(t), glm::rotate(Mat4(1.0), t, Vec3(0, 0, 1))), 1e-12);
  }
}

TEST_F(RandomInputs, TranslateScaleMatchGlm) {
  for (int i = 0; i < 200; ++i) {
    const Vec3 v = vec(-10, 10);
    EXPECT_LT(max_diff(translate(v.x, v.y, v.z), glm::translate(Mat4(1.0), v)), 1e-12);
    EXPECT_LT(max_diff(scale(v.x, v.y, v.z), glm::scale(Mat4(1.0), v)), 1e-12);
  }
}

TEST_F(RandomInputs, LookAtMatchesGlm) {
  int tested = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 eye = vec(-20, 20), center = vec(-20, 20), up = vec(-1, 1);
    if (glm::length(glm::cross(center - eye, up)) < 1e-3) continue;
    const Mat4 ref = glm::lookAtRH(eye, center, up);
    EXPECT_LT(max_diff(look_at(eye, center, up), ref), 1e-6 * (1 + glm::length(eye)));
    ++tested;
  }
  EXPECT_GT(tested, 400);
}

TEST_F(RandomInputs, ProjectionsMatchGlm) {
  for (int i = 0; i < 300; ++i) {
    const double l = uni(-10, -0.1), r = uni(0.1, 10), b = uni(-10, -0.1), t = uni(0.1, 10);
    const double n = uni(0.01, 5), f = n + uni(0.1, 100);
    EXPECT_LT(max_diff(ortho(l, r, b, t, n, f), glm::orthoRH_NO(l, r, b, t, n, f)), 1e-6);
    const double fovy = uni(0.05, 3.0), aspect = uni(0.2, 5);
    EXPECT_LT(max_diff(perspective(fovy, aspect, n, f), glm::perspectiveRH_NO(fovy, aspect, n, f)), 1e-6);
    EXPECT_LT(max_diff(infinite_perspective(fovy, aspect, n), glm::infinitePerspectiveRH(fovy, aspect, n)), 1e-6);
  }
}

TEST(Transform, NotesCameraFacts) {
  // camera(0,0,8, 0,0,0, 0,1,0) is the same as translate(0,0,-8).
  EXPECT_LT(max_diff(look_at({0, 0, 8}, {0, 0, 0}, {0, 1, 0}), translate(0, 0, -8)), 1e-15);
  // camera(0,0,0, 1,0,0, 0,1,0) is the same as a 90 degree rotation about y.
  EXPECT_LT(max_diff(look_at({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), rotate_y(radians(90))), 1e-15);
  // The view matrix puts the gaze on -z: R g = (0, 0, -|g|).
  const Vec3 eye(1, 2, 3), center(-4, 0, 7);
  const Vec3 g = transform_point(look_at(eye, center, {0, 1, 0}), center);
  EXPECT_NEAR(g.x, 0, 1e-12);
  EXPECT_NEAR(g.y, 0, 1e-12);
  EXPECT_NEAR(g.z, -glm::length(center - eye), 1e-12);
}

// Distances past 1e154 (or below 1e-154) and huge or tiny up vectors: the rotation is the unit case's (the lengths
// and the cross product are taken on vectors scaled by powers of two; before, they overflowed and were refused).
TEST(Transform, LookAtAtExtremeScalesKeepsTheUnitRotation) {
  const Mat4 unit = look_at({0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // rotate_y(90)
  for (double scale : {1e300, 1e160, 1e-160, 1e-300}) {
    const Mat4 m = look_at({0, 0, 0}, {scale, 0, 0}, {0, scale, 0});
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) EXPECT_EQ(m[c][r], unit[c][r]) << scale;
  }
  EXPECT_THROW(look_at({-1e308, 0, 0}, {1e308, 0, 0}, {0, 1, 0}), InvalidInput);   // the gaze is not finite
  EXPECT_THROW(look_at({0, 0, 0}, {1e-320, 0, 0}, {1e-320, 0, 0}), InvalidInput);  // up along the gaze
}

TEST(Transform, NotesRotationFacts) {
  // Counterclockwise: x axis goes to y axis under Rz(90), y to z under Rx(90), z to x under Ry(90).
  auto near = [](const Vec3& a, const Vec3& b) { return glm::length(a - b) < 1e-12; };
  EXPECT_TRUE(near(transform_vector(rotate_z(kPi / 2), {1, 0, 0}), {0, 1, 0}));
  EXPECT_TRUE(near(transform_vector(rotate_x(kPi / 2), {0, 1, 0}), {0, 0, 1}));
  EXPECT_TRUE(near(transform_vector(rotate_y(kPi / 2), {0, 0, 1}), {1, 0, 0}));
  // R1 A = (1, 0, 0): the notes' frame rotates the axis onto x.
  const Vec3 a = glm::normalize(Vec3(1, 2, -3));
  EXPECT_TRUE(near(transform_vector(axis_frame(a), a), {1, 0, 0}));
  EXPECT_THROW(rotate(1.0, {0, 0, 0}), InvalidInput);
}

TEST(Transform, TwoDimensionalNotesFacts) {
  auto near = [](const Vec2& a, const Vec2& b) { return glm::length(a - b) < 1e-12; };
  EXPECT_TRUE(near(transform_point(rotate2d(kPi / 2), {1, 0}), {0, 1}));
  EXPECT_TRUE(near(transform_point(translate2d(2, 3), {1, 1}), {3, 4}));
  EXPECT_TRUE(near(transform_point(scale2d(2, 3), {1, 1}), {2, 3}));
  EXPECT_TRUE(near(transform_point(shear2d(0.5), {2, 2}), {3, 2}));  // x' = x + a y
  EXPECT_TRUE(near(transform_point(reflect2d_y_axis(), {2, 3}), {-2, 3}));
  EXPECT_TRUE(near(transform_point(reflect2d_x_axis(), {2, 3}), {2, -3}));
  // Rotation about a point leaves that point fixed (T2 R T1).
  EXPECT_TRUE(near(transform_point(rotate2d_about(1.1, 3, 4), {3, 4}), {3, 4}));
  // The notes' [-2, 2] -> [0, 400] mapping: add 2, multiply by 100.
  EXPECT_TRUE(near(transform_point(scale2d(100, 100) * translate2d(2, 2), {-2, 2}), {0, 400}));
}

// The notes' commutativity table, property-tested: which pairs of transform kinds commute.
enum Kind { kTranslation, kRotation, kUniformScale, kNonUniformScale };

class Commutativity : public RandomInputs {
 protected:
  Mat3 make2d(Kind k) {
    switch (k) {
      case kTranslation:
        return translate2d(uni(-5, 5), uni(-5, 5));
      case kRotation:
        return rotate2d(uni(0.3, 2.8));
      case kUniformScale: {
        const double s = uni(0.3, 3);
        return scale2d(s, s);
      }
      case kNonUniformScale:
        return scale2d(uni(0.3, 1.0), uni(1.5, 3));
    }
    return Mat3(1.0);
  }
  Mat4 make3d(Kind k, int variant) {
    switch (k) {
      case kTranslation: {
        const Vec3 t = vec(-5, 5);
        return translate(t.x, t.y, t.z);
      }
      case kRotation:
        return variant == 0 ? rotate_x(uni(0.3, 2.8)) : rotate_y(uni(0.3, 2.8));
      case kUniformScale: {
        const double s = uni(0.3, 3);
        return scale(s, s, s);
      }
      case kNonUniformScale:
        return scale(uni(0.3, 1.0), uni(1.5, 3), uni(0.3, 3));
    }
    return Mat4(1.0);
  }
};

TEST_F(Commutativity, MatchesTheNotesTable) {
  // Rows/columns: translation, rotation, uniform scale, non-uniform scale. 1 = commutes (2D).
  const int table2d[4][4] = {{1, 0, 0, 0}, {0, 1, 1, 0}, {0, 1, 1, 1}, {0, 0, 1, 1}};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int trial = 0; trial < 50; ++trial) {
        const Mat3 A = make2d(Kind(a)), B = make2d(Kind(b));
        const bool commutes = max_diff(A * B, B * A) < 1e-9;
        EXPECT_EQ(commutes, bool(table2d[a][b])) << "2D kinds " << a << "," << b;
      }
  // "Yes (No in 3D)": two rotations about different axes do not commute in 3D.
  for (int trial = 0; trial < 50; ++trial) {
    const Mat4 A = make3d(kRotation, 0), B = make3d(kRotation, 1);
    EXPECT_GT(max_diff(A * B, B * A), 1e-6);
    const Mat4 C = make3d(kRotation, 0), D = make3d(kUniformScale, 0);
    EXPECT_LT(max_diff(C * D, D * C), 1e-9);
  }
}

TEST(Transform, ReflectAndShear3d) {
  const Mat4 m = reflect({0, 0, 2});
  EXPECT_LT(glm::length(transform_point(m, {1, 2, 3}) - Vec3(1, 2, -3)), 1e-12);
  const Mat4 s = shear(0.5, 0, 0, 0, 0, 0);
  EXPECT_LT(glm::length(transform_point(s, {1, 2, 3}) - Vec3(2, 2, 3)), 1e-12);
  EXPECT_THROW(reflect({0, 0, 0}), InvalidInput);
}

TEST(Transform, NormalMatrixKeepsNormalsPerpendicular) {
  const Mat4 mv = scale(1, 3, 0.5) * rotate(0.4, {1, 1, 0});
  const Vec3 tangent(1, -1, 0), normal(1, 1, 0.5);
  ASSERT_NEAR(glm::dot(tangent, normal), 0, 1e-12);
  EXPECT_NEAR(glm::dot(transform_vector(mv, tangent), normal_matrix(mv) * normal), 0, 1e-12);
}

}  // namespace
}  // namespace tessera
