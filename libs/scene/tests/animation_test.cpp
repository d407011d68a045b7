// Keyed values of scene files (docs/scene-format.md, "Animation"), checked against values worked out by hand.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tessera/core/error.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera {
namespace {

using ::testing::HasSubstr;

// A scene whose camera eye is `eye` (JSON) and whose one sphere is placed by `transform` (JSON), over `frames`.
std::string scene_json(const std::string& eye, const std::string& transform = "[]",
                       const std::string& animation = R"({"frames": [0, 48], "shutter": 0.5})") {
  return R"({"animation": )" + animation + R"(, "camera": {"eye": )" + eye + R"(, "center": [0, 0, 0]},
            "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "m", "transform": )" +
         transform + "}]}";
}

Vec3 eye_at(const std::string& eye, int frame) {
  return AnimatedScene(scene_json(eye), "test", {}).at(frame).camera.eye;
}

TEST(Animation, LinearKeysInterpolateAndHoldOutsideTheirFrames) {
  const std::string eye = R"({"keys": [[8, [0, 0, 4]], [16, [8, 4, 12]]]})";
  EXPECT_EQ(eye_at(eye, 0), Vec3(0, 0, 4));  // before the first key: held
  EXPECT_EQ(eye_at(eye, 8), Vec3(0, 0, 4));
  EXPECT_EQ(eye_at(eye, 10), Vec3(2, 1, 6));  // a quarter of the way
  EXPECT_EQ(eye_at(eye, 16), Vec3(8, 4, 12));
  EXPECT_EQ(eye_at(eye, 40), Vec3(8, 4, 12));  // after the last: held
}

TEST(Animation, StepKeysJump) {
  const std::string eye = R"({"keys": [[0, [0, 0, 4]], [10, [0, 0, 9]]], "interpolation": "step"})";
  EXPECT_EQ(eye_at(eye, 9), Vec3(0, 0, 4));
  EXPECT_EQ(eye_at(eye, 10), Vec3(0, 0, 9));
}

// Catmull-Rom's tangents are central differences, exact for a quadratic: between interior keys of z = 4 + f^2 / 4 (at
// frames 0, 2, 4, 6, 8) the curve is that parabola; it passes through every key.
TEST(Animation, SmoothKeysFollowAQuadraticExactlyBetweenInteriorKeys) {
  std::string eye = R"({"interpolation": "smooth", "keys": [)";
  for (int f = 0; f <= 8; f += 2)
    eye +=
        (f ? ", " : "") + std::string("[") + std::to_string(f) + ", [0, 0, " + std::to_string(4 + f * f / 4.0) + "]]";
  eye += "]}";
  for (int f = 0; f <= 8; f += 2) EXPECT_DOUBLE_EQ(eye_at(eye, f).z, 4 + f * f / 4.0) << f;
  EXPECT_NEAR(eye_at(eye, 3).z, 4 + 9 / 4.0, 1e-12);
  EXPECT_NEAR(eye_at(eye, 5).z, 4 + 25 / 4.0, 1e-12);
}

// Integer settings are keyed with "step" (linear keys give fractions between the keys, which they refuse).
TEST(Animation, KeyedIntegerSettingsStep) {
  const auto samples = [](const std::string& interpolation) {
    return R"({"animation": {"frames": [0, 10]}, "image": {"samples": {"keys": [[0, 1], [10, 8]], "interpolation": ")" +
           interpolation +
           R"("}}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})";
  };
  EXPECT_EQ(AnimatedScene(samples("step"), "test", {}).at(5).image.samples, 1);
  EXPECT_EQ(AnimatedScene(samples("step"), "test", {}).at(10).image.samples, 8);
  const AnimatedScene linear(samples("linear"), "test", {});
  EXPECT_EQ(linear.at(10).image.samples, 8);
  EXPECT_THROW(linear.at(5), InvalidInput);  // 4.5 samples
}

// An object whose placement is keyed moves over the shutter: transform at the frame, transform_end half a frame on.
TEST(Animation, KeyedPlacementsBlurOverTheShutter) {
  const std::string transform = R"([{"translate": {"keys": [[0, [0, 0, 0]], [10, [5, 0, 0]]]}}])";
  const AnimatedScene scene(scene_json("[0, 0, 5]", transform), "test", {});
  EXPECT_TRUE(scene.keyed());
  const SceneObject sphere = scene.at(4).objects[0];
  EXPECT_EQ(sphere.transform[3], Mat4::col_type(2, 0, 0, 1));
  ASSERT_TRUE(sphere.motion.has_end);
  EXPECT_EQ(sphere.motion.end_transform[3], Mat4::col_type(2.25, 0, 0, 1));
  // Without a shutter, nothing blurs; a still placement never does.
  const AnimatedScene sharp(scene_json("[0, 0, 5]", transform, R"({"frames": [0, 10], "shutter": 0})"), "test", {});
  EXPECT_FALSE(sharp.at(4).objects[0].motion.moving());
  EXPECT_FALSE(AnimatedScene(scene_json("[0, 0, 5]"), "test", {}).at(4).objects[0].motion.moving());
}

TEST(Animation, AStillSceneHasFrameZeroOnly) {
  const AnimatedScene scene(
      R"({"materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})", "still", {});
  EXPECT_FALSE(scene.keyed());
  EXPECT_EQ(scene.animation().first, 0);
  EXPECT_EQ(scene.animation().last, 0);
  EXPECT_NO_THROW(scene.at(0));
  try {
    scene.at(1);
    ADD_FAILURE() << "frame 1 of a still scene";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr("frame 1 is outside the scene's frames 0..0"));
  }
}

TEST(Animation, ParseSceneGivesTheFirstFrame) {
  const std::string json =
      scene_json(R"({"keys": [[0, [0, 0, 4]], [10, [0, 0, 9]]]})", "[]", R"({"frames": [5, 10], "fps": 30})");
  EXPECT_EQ(parse_scene(json, "test", {}).camera.eye, Vec3(0, 0, 6.5));
  EXPECT_EQ(AnimatedScene(json, "test", {}).animation().fps, 30);
}

TEST(Animation, BadKeysAndTimeLinesNameTheirPath) {
  const auto expect_error = [](const std::string& json, const std::string& part) {
    try {
      AnimatedScene(json, "s.json", {});
      ADD_FAILURE() << "accepted: " << json;
    } catch (const InvalidInput& e) {
      EXPECT_THAT(e.what(), HasSubstr(part)) << json;
    }
  };
  expect_error(scene_json(R"({"keys": [[4, [0, 0, 4]], [4, [0, 0, 5]]]})"),
               "camera.eye.keys[1]: key frames must increase: 4 follows 4");
  expect_error(scene_json(R"({"keys": [[0, [0, 0, 4]], [4, [0, 5]]]})"),
               "camera.eye.keys[1]: every key's value must have the shape of the first");
  expect_error(scene_json(R"({"keys": [[0, "a"], [4, "b"]]})"), "camera.eye.keys[0]: expected a number or an array");
  expect_error(scene_json(R"({"keys": [[0, [0, 0, 4]]], "interpolation": "cubic"})"),
               "camera.eye.interpolation: expected linear, smooth or step");
  expect_error(scene_json(R"({"keys": []})"), "camera.eye.keys: expected an array of [frame, value] pairs");
  expect_error(scene_json(R"({"keys": [[0]]})"), "camera.eye.keys[0]: expected [frame, value]");
  expect_error(scene_json("[0, 0, 5]", "[]", R"({"frames": [3, 1]})"), "animation.frames: expected [first, last]");
  expect_error(scene_json("[0, 0, 5]", "[]", R"({"fps": 0})"), "animation.fps");
  expect_error(scene_json("[0, 0, 5]", "[]", R"({"shutter": 2})"), "animation.shutter");
  expect_error(scene_json("[0, 0, 5]", "[]", R"({"speed": 2})"), "animation.speed: unknown key");
  // A million nested arrays (each level's path kept, and a recursive walk's stack) are refused at depth 64.
  expect_error(R"({"objects": )" + std::string(1'000'000, '[') + std::string(1'000'000, ']') + "}",
               "objects and arrays nested deeper than 64 levels");
  // A value that is valid at some frames only fails at those: the eye meets the center at frame 5.
  const AnimatedScene crossing(scene_json(R"({"keys": [[0, [0, 0, 5]], [10, [0, 0, -5]]]})"), "s.json", {});
  EXPECT_NO_THROW(crossing.at(4));
  try {
    crossing.at(5);
    ADD_FAILURE() << "the eye met the center";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr("camera: eye and center coincide (at frame 5)"));
  }
}

}  // namespace
}  // namespace tessera
