#include "tessera/math/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"

namespace tessera {
namespace {

TEST(Camera, CenterRayLooksAtCenter) {
  Camera cam;
  cam.eye = {3, 4, 5};
  cam.center = {0, 1, 0};
  EyeRays rays(cam, 64, 64);
  // With an even size the image center is the corner between four pixels: ray(32, 32, 0, 0).
  const Ray r = rays.ray(32, 32, 0, 0);
  const Vec3f g = glm::normalize(Vec3f(cam.center - cam.eye));
  EXPECT_NEAR(glm::dot(r.dir, g), 1.0f, 1e-6f);
  EXPECT_EQ(r.origin, Vec3f(3, 4, 5));
}

TEST(Camera, EdgeRaysSpanTheFieldOfView) {
  Camera cam;
  cam.fovy = radians(60);
  EyeRays rays(cam, 200, 100);  // aspect 2
  // tan(theta/2) = 1/d: the top edge ray is fovy/2 above the gaze.
  EXPECT_NEAR(rays.focal_length(), 1 / std::tan(radians(30)), 1e-12);
  const Ray top = rays.ray(100, 0, 0, 0);
  EXPECT_NEAR(std::acos(glm::dot(top.dir, Vec3f(0, 0, -1))), radians(30), 1e-6);
  EXPECT_GT(top.dir.y, 0);  // row 0 is the top of the image
  // Horizontal extent is aspect times the vertical one.
  const Ray right = rays.ray(200, 50, 0, 0);
  EXPECT_NEAR(right.dir.x / -right.dir.z, 2 * std::tan(radians(30)), 1e-6);
}

TEST(Camera, EyeRayHitsWhereProjectionPutsThePoint) {
  // The ray through a pixel and the projection of a point on that ray agree.
  Camera cam;
  cam.eye = {1, 2, 6};
  cam.center = {0, 0, 0};
  cam.aspect = 4.0 / 3.0;
  EyeRays rays(cam, 80, 60);
  const Ray r = rays.ray(17, 41);
  const Vec3 p = Vec3(r.at(7.0f));
  const Vec4 clip = cam.projection() * cam.view() * Vec4(p, 1);
  const double x = (clip.x / clip.w * 0.5 + 0.5) * 80, y = (1 - (clip.y / clip.w * 0.5 + 0.5)) * 60;
  EXPECT_NEAR(x, 17.5, 1e-3);
  EXPECT_NEAR(y, 41.5, 1e-3);
}

TEST(Camera, OrthographicRaysAreParallelAndLandWhereTheProjectionPutsThem) {
  Camera cam;
  cam.eye = {1, 2, 6};
  cam.center = {0, 0, 0};
  cam.aspect = 4.0 / 3.0;
  cam.orthographic = true;
  cam.ortho_height = 3;
  EyeRays rays(cam, 80, 60);
  const Vec3f gaze = glm::normalize(Vec3f(cam.center - cam.eye));
  for (const auto& [i, j] : {std::pair{17, 41}, std::pair{0, 0}, std::pair{79, 59}}) {
    const Ray r = rays.ray(i, j);
    EXPECT_NEAR(glm::dot(r.dir, gaze), 1.0f, 1e-6f);
    for (float t : {0.5f, 7.0f}) {  // every point of the ray projects to the same pixel
      const Vec4 clip = cam.projection() * cam.view() * Vec4(Vec3(r.at(t)), 1);
      EXPECT_NEAR(clip.w, 1.0, 1e-12);
      EXPECT_NEAR((clip.x * 0.5 + 0.5) * 80, i + 0.5, 1e-3);
      EXPECT_NEAR((1 - (clip.y * 0.5 + 0.5)) * 60, j + 0.5, 1e-3);
    }
  }
  // The view is ortho_height tall: the top edge's origin lies h/2 above the eye along v.
  const Ray top = rays.ray(40, 0, 0, 0);
  Vec3 u, v, w;
  cam.frame(u, v, w);
  EXPECT_NEAR(glm::dot(Vec3(top.origin) - cam.eye, v), 1.5, 1e-6);
  cam.ortho_height = 0;
  EXPECT_THROW(cam.projection(), InvalidInput);
  EXPECT_THROW(EyeRays(cam, 8, 8), InvalidInput);
}

TEST(Camera, BadInputThrows) {
  Camera cam;
  cam.center = cam.eye;
  EXPECT_THROW(cam.view(), InvalidInput);
  Camera c2;
  c2.up = {0, 0, 1};  // parallel to the gaze
  EXPECT_THROW(c2.view(), InvalidInput);
  EXPECT_THROW(EyeRays(Camera{}, 0, 10), InvalidInput);
  Camera c3;
  c3.near = 0;
  EXPECT_THROW(c3.projection(), InvalidInput);
}

}  // namespace
}  // namespace tessera
