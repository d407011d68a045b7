// Shoemake's arcball and the orbit control against analytic rotations: Rodrigues' formula for twice the arc's angle
// about the arc's axis, the view matrix of a scene turned about its center, a pan that keeps the grabbed point under
// the pointer, and a turntable turn about the world's vertical.
#include "tessera/view/arcball.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

/// Rodrigues' rotation matrix: I cos t + sin t [k]x + (1 - cos t) k k^T for a unit axis k (written out, no GLM).
Mat3 rodrigues(const Vec3& k, double t) {
  const double c = std::cos(t), s = std::sin(t);
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[j][i] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];  // GLM: r[column][row]
  r[1][0] -= s * k.z;                                                                // row 0, column 1: -k.z sin t
  r[2][0] += s * k.y;
  r[0][1] += s * k.z;
  r[2][1] -= s * k.x;
  r[0][2] -= s * k.y;
  r[1][2] += s * k.x;
  return r;
}

void expect_near(const Vec3& a, const Vec3& b, double tolerance) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << i;
}

TEST(Arcball, WindowPointsLieOnTheBallOrItsRim) {
  // A 400 x 200 window: the ball has radius 100 about (200, 100).
  expect_near(arcball_point(200, 100, 400, 200), Vec3(0, 0, 1), 1e-15);
  expect_near(arcball_point(260, 100, 400, 200), Vec3(0.6, 0, 0.8), 1e-15);
  expect_near(arcball_point(200, 40, 400, 200), Vec3(0, 0.6, 0.8), 1e-15);  // rows grow downward, y up
  expect_near(arcball_point(400, 100, 400, 200), Vec3(1, 0, 0), 1e-15);     // outside: the rim
  expect_near(arcball_point(200 + 300, 100 + 400, 400, 200), Vec3(0.6, -0.8, 0), 1e-15);
}

TEST(Arcball, RotationIsTwiceTheArcAboutItsAxis) {
  const Vec3 pairs[][2] = {{{0, 0, 1}, {0.6, 0, 0.8}},
                           {{0, 0, 1}, {0, 0.6, 0.8}},
                           {{0.3, -0.4, std::sqrt(0.75)}, {-0.5, 0.1, std::sqrt(0.74)}},
                           {{1, 0, 0}, {0, 1, 0}},
                           {{0.48, 0.6, 0.64}, {-0.8, 0, 0.6}}};
  for (const auto& [from, to] : pairs) {
    const Mat3 got = glm::mat3_cast(arcball_rotation(from, to));
    const Mat3 want = rodrigues(glm::normalize(glm::cross(from, to)), 2 * std::acos(glm::dot(from, to)));
    for (int c = 0; c < 3; ++c) expect_near(got[c], want[c], 1e-12);
  }
  // A drag from the ball's center to its rim is a half turn: the front comes round to the back.
  expect_near(glm::mat3_cast(arcball_rotation({0, 0, 1}, {1, 0, 0})) * Vec3(0, 0, 1), Vec3(0, 0, -1), 1e-12);
  // No drag, no turn.
  expect_near(glm::mat3_cast(arcball_rotation({0.6, 0, 0.8}, {0.6, 0, 0.8})) * Vec3(1, 2, 3), Vec3(1, 2, 3), 1e-12);
}

Camera home_camera() {
  Camera c;
  c.eye = {3, 2, 6};
  c.center = {1, 0.5, -1};
  c.up = {0, 1, 0};
  c.aspect = 4.0 / 3;
  return c;
}

TEST(OrbitControl, DragTurnsTheSceneAboutItsCenterInEyeCoordinates) {
  const Camera home = home_camera();
  OrbitControl orbit(home, home.center, 2);
  orbit.begin_rotate(200, 150, 400, 300);
  orbit.rotate_to(260, 120, 400, 300);
  const Mat3 q = rodrigues(glm::normalize(glm::cross(Vec3(0, 0, 1), arcball_point(260, 120, 400, 300))),
                           2 * std::acos(arcball_point(260, 120, 400, 300).z));
  const Camera cam = orbit.camera(home.aspect);
  // The new view of p equals the home view of p, turned by q about the center's eye position.
  const Mat4 v0 = home.view(), v1 = cam.view();
  const Vec3 c_eye = Vec3(v0 * Vec4(home.center, 1));
  for (const Vec3 p : {Vec3(0, 0, 0), Vec3(1, 2, 3), Vec3(-2, 0.5, 1)}) {
    const Vec3 want = c_eye + q * (Vec3(v0 * Vec4(p, 1)) - c_eye);
    expect_near(Vec3(v1 * Vec4(p, 1)), want, 1e-12);
  }
  EXPECT_NEAR(glm::length(cam.eye - home.center), glm::length(home.eye - home.center), 1e-12);
}

TEST(OrbitControl, DraggingBackToTheStartRestoresTheView) {
  const Camera home = home_camera();
  OrbitControl orbit(home, home.center, 2);
  orbit.begin_rotate(100, 100, 400, 300);
  for (int i = 0; i < 20; ++i) orbit.rotate_to(100 + 13 * i, 100 + 7 * (i % 5), 400, 300);
  orbit.rotate_to(100, 100, 400, 300);
  const Camera cam = orbit.camera(home.aspect);
  expect_near(cam.eye, home.eye, 1e-12);
  expect_near(glm::normalize(cam.up),
              glm::normalize(home.up - glm::dot(home.up, glm::normalize(home.eye - home.center)) *
                                           glm::normalize(home.eye - home.center)),
              1e-12);
}

/// Where `p` lands in a width x height picture of `camera` (pixels, row 0 at the top).
Vec2 project(const Camera& camera, const Vec3& p, int width, int height) {
  const Vec4 clip = camera.projection() * camera.view() * Vec4(p, 1);
  return {(clip.x / clip.w + 1) / 2 * width, (1 - clip.y / clip.w) / 2 * height};
}

TEST(OrbitControl, PanKeepsThePointAtTheCentersDepthUnderThePointer) {
  const Camera home = home_camera();
  OrbitControl orbit(home, home.center, 2);
  orbit.begin_rotate(200, 150, 400, 300);
  orbit.rotate_to(230, 170, 400, 300);  // any orientation
  const Camera before = orbit.camera(home.aspect);
  orbit.begin_pan(120, 80);
  orbit.pan_to(150, 60, 300);
  const Camera after = orbit.camera(home.aspect);
  const Vec2 a = project(before, home.center, 400, 300), b = project(after, home.center, 400, 300);
  EXPECT_NEAR(b.x - a.x, 30, 1e-9);
  EXPECT_NEAR(b.y - a.y, -20, 1e-9);
}

TEST(OrbitControl, ZoomScalesTheDistanceAndResetGoesHome) {
  const Camera home = home_camera();
  OrbitControl orbit(home, home.center, 2);
  const double d = glm::length(home.eye - home.center);
  orbit.zoom(3);
  EXPECT_NEAR(orbit.distance(), d * 1.331, 1e-12);
  EXPECT_NEAR(glm::length(orbit.camera(1).eye - home.center), d * 1.331, 1e-12);
  orbit.zoom(-1000);
  EXPECT_DOUBLE_EQ(orbit.distance(), 2.0 / 100);  // radius / 100 at the closest
  orbit.reset();
  expect_near(orbit.camera(1).eye, home.eye, 1e-12);
}

TEST(OrbitControl, TurntableTurnsTheEyeAboutTheWorldsVertical) {
  const Camera home = home_camera();
  OrbitControl orbit(home, home.center, 2);
  const double angle = 0.7;
  orbit.set_orientation(orbit.turn_about_up(angle));
  const Camera cam = orbit.camera(home.aspect);
  // The scene turns by +angle about +y through the center, so the eye turns by -angle.
  expect_near(cam.eye - home.center, rodrigues(Vec3(0, 1, 0), -angle) * (home.eye - home.center), 1e-12);
}

TEST(OrbitControl, RefusesABadSphereOrCamera) {
  const Camera home = home_camera();
  EXPECT_THROW(OrbitControl(home, home.center, 0), InvalidInput);
  EXPECT_THROW(OrbitControl(home, home.center, NAN), InvalidInput);
  EXPECT_THROW(OrbitControl(home, home.eye, 1), InvalidInput);
}

}  // namespace
}  // namespace tessera
