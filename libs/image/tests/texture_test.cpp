#include "tessera/image/texture.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "tessera/core/rng.hpp"
#include "tessera/image/image_io.hpp"

namespace tessera {
namespace {

void expect_near(const glm::vec4& actual, const glm::vec4& expected, float tolerance, const std::string& where = "") {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << "channel " << c << " " << where;
}

// The 2x2 texture of the tests: t00 bottom-left, t10 bottom-right, t01 top-left, t11 top-right.
const glm::vec4 t00(0.f, 0.f, 0.f, 1.f), t10(1.f, 0.f, 0.5f, 1.f), t01(0.f, 1.f, 0.25f, 0.5f), t11(1.f, 1.f, 1.f, 0.f);

Texture2D two_by_two(Wrap wrap, Filter filter) {
  ImageRGBA image(2, 2);
  image(0, 0) = t01;  // row 0 is the top row
  image(1, 0) = t11;
  image(0, 1) = t00;
  image(1, 1) = t10;
  return Texture2D(image, Sampler{wrap, wrap, filter});
}

ImageRGBA random_image(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  ImageRGBA image(width, height);
  for (glm::vec4& p : image.pixels()) p = glm::vec4(unit(rng), unit(rng), unit(rng), unit(rng));
  return image;
}

glm::vec4 mean(const ImageRGBA& image) {
  glm::dvec4 sum(0.0);
  for (const glm::vec4& p : image.pixels()) sum += glm::dvec4(p);
  return glm::vec4(sum / double(image.pixels().size()));
}

TEST(Texture2D, OriginIsTheBottomLeftTexel) {
  const Texture2D texture = two_by_two(Wrap::clamp, Filter::nearest);
  expect_near(texture.sample({0.1f, 0.1f}), t00, 0.f);
  expect_near(texture.sample({0.9f, 0.1f}), t10, 0.f);
  expect_near(texture.sample({0.1f, 0.9f}), t01, 0.f);
  expect_near(texture.sample({0.9f, 0.9f}), t11, 0.f);
}

TEST(Texture2D, BilinearMatchesTheNotesFormula) {
  const Texture2D texture = two_by_two(Wrap::clamp, Filter::bilinear);
  for (float a : {0.f, 0.3f, 0.5f, 0.75f, 1.f})
    for (float b : {0.f, 0.2f, 0.5f, 1.f}) {
      // a, b: distance from the bottom-left texel center, in texels; texel centers are at u, v = 0.25 and 0.75.
      const glm::vec4 expected = (1 - a) * (1 - b) * t00 + a * (1 - b) * t10 + (1 - a) * b * t01 + a * b * t11;
      expect_near(texture.sample({0.25f + 0.5f * a, 0.25f + 0.5f * b}), expected, 1e-6f,
                  "a=" + std::to_string(a) + " b=" + std::to_string(b));
    }
  expect_near(texture.sample({0.5f, 0.5f}), (t00 + t10 + t01 + t11) / 4.f, 1e-6f);
}

TEST(Texture2D, WrapModesPickTheOpenGLTexel) {
  // Nearest texel column along u for a 2-texel row: index floor(2u).
  struct Case {
    float u;
    glm::vec4 repeat, clamp, mirror;
  };
  const Case cases[] = {
      {1.25f, t00, t10, t10},   // index 2
      {1.75f, t10, t10, t00},   // index 3
      {-0.25f, t10, t00, t00},  // index -1
      {-0.75f, t00, t00, t10},  // index -2
      {2.25f, t00, t10, t00},   // index 4
  };
  for (const Case& c : cases) {
    expect_near(two_by_two(Wrap::repeat, Filter::nearest).sample({c.u, 0.25f}), c.repeat, 0.f, "repeat");
    expect_near(two_by_two(Wrap::clamp, Filter::nearest).sample({c.u, 0.25f}), c.clamp, 0.f, "clamp");
    expect_near(two_by_two(Wrap::mirror, Filter::nearest).sample({c.u, 0.25f}), c.mirror, 0.f, "mirror");
  }
  // Bilinear at the left edge blends with the wrapped neighbour only when repeating.
  expect_near(two_by_two(Wrap::repeat, Filter::bilinear).sample({0.f, 0.25f}), (t00 + t10) / 2.f, 1e-6f);
  expect_near(two_by_two(Wrap::clamp, Filter::bilinear).sample({0.f, 0.25f}), t00, 1e-6f);
  expect_near(two_by_two(Wrap::mirror, Filter::bilinear).sample({0.f, 0.25f}), t00, 1e-6f);
  // Repeat is periodic with period 1 in u and v.
  const Texture2D repeat = two_by_two(Wrap::repeat, Filter::bilinear);
  expect_near(repeat.sample({0.37f + 3.f, 0.61f - 2.f}), repeat.sample({0.37f, 0.61f}), 1e-5f);
}

TEST(Texture2D, SeparateWrapModesPerAxis) {
  ImageRGBA image(2, 2);
  image(0, 0) = t01;
  image(1, 0) = t11;
  image(0, 1) = t00;
  image(1, 1) = t10;
  const Texture2D texture(image, Sampler{Wrap::repeat, Wrap::clamp, Filter::nearest});
  expect_near(texture.sample({1.25f, 5.f}), t01, 0.f);  // u wraps to column 0, v clamps to the top row
}

TEST(Texture2D, NonFiniteCoordinatesAreDefined) {
  const Texture2D texture = two_by_two(Wrap::repeat, Filter::bilinear);
  const glm::vec4 v = texture.sample({std::nanf(""), 1e30f});
  for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(v[c]));
}

TEST(Mipmaps, LevelSizesHalveDownToOne) {
  const auto sizes = [](int w, int h) {
    std::vector<std::pair<int, int>> out;
    for (const ImageRGBA& level : build_mipmaps(ImageRGBA(w, h))) out.emplace_back(level.width(), level.height());
    return out;
  };
  using S = std::vector<std::pair<int, int>>;
  EXPECT_EQ(sizes(8, 4), (S{{8, 4}, {4, 2}, {2, 1}, {1, 1}}));
  EXPECT_EQ(sizes(5, 3), (S{{5, 3}, {2, 1}, {1, 1}}));
  EXPECT_EQ(sizes(1, 7), (S{{1, 7}, {1, 3}, {1, 1}}));
  EXPECT_EQ(sizes(1, 1), (S{{1, 1}}));
  EXPECT_EQ(Texture2D(ImageRGBA(100, 37)).levels(), 7);  // 1 + floor(log2(100))
  EXPECT_THROW(build_mipmaps(ImageRGBA()), InvalidInput);
  EXPECT_THROW(Texture2D(ImageRGBA(0, 3)), InvalidInput);
  EXPECT_THROW(Texture2D(ImageRGBA(2, 2)).level(2), InvalidInput);
}

TEST(Mipmaps, EvenSizesAverageSquaresOfFour) {
  ImageRGBA image(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) image(x, y) = glm::vec4(float(x + 4 * y));
  const auto levels = build_mipmaps(image);
  ASSERT_EQ(levels.size(), 3u);
  expect_near(levels[1](0, 0), glm::vec4((0 + 1 + 4 + 5) / 4.f), 1e-6f);
  expect_near(levels[1](1, 0), glm::vec4((2 + 3 + 6 + 7) / 4.f), 1e-6f);
  expect_near(levels[1](0, 1), glm::vec4((8 + 9 + 12 + 13) / 4.f), 1e-6f);
  expect_near(levels[1](1, 1), glm::vec4((10 + 11 + 14 + 15) / 4.f), 1e-6f);
  expect_near(levels[2](0, 0), glm::vec4(7.5f), 1e-6f);
}

TEST(Mipmaps, OddSizesUseTheThreeTapBox) {
  ImageRGBA row(5, 1);
  for (int x = 0; x < 5; ++x) row(x, 0) = glm::vec4(float(x));
  const auto levels = build_mipmaps(row);
  ASSERT_EQ(levels[1].width(), 2);
  expect_near(levels[1](0, 0), glm::vec4((2 * 0 + 2 * 1 + 1 * 2) / 5.f), 1e-6f);  // weights (2, 2, 1)/5
  expect_near(levels[1](1, 0), glm::vec4((1 * 2 + 2 * 3 + 2 * 4) / 5.f), 1e-6f);  // weights (1, 2, 2)/5
  expect_near(levels[2](0, 0), glm::vec4(2.f), 1e-6f);
}

TEST(Mipmaps, EveryLevelKeepsTheMean) {
  for (const auto& [w, h] : {std::pair{7, 5}, std::pair{16, 9}, std::pair{3, 11}, std::pair{13, 1}}) {
    const ImageRGBA image = random_image(w, h, unsigned(w * 100 + h));
    const glm::vec4 expected = mean(image);
    for (const ImageRGBA& level : build_mipmaps(image))
      expect_near(mean(level), expected, 1e-5f, std::to_string(w) + "x" + std::to_string(h));
  }
}

TEST(Texture2D, ConstantTextureIsConstantEverywhere) {
  const glm::vec4 c(0.2f, 0.4f, 0.6f, 0.8f);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coord(-3.f, 3.f), lod(-2.f, 9.f);
  for (Wrap wrap : {Wrap::repeat, Wrap::clamp, Wrap::mirror})
    for (Filter filter : {Filter::nearest, Filter::bilinear, Filter::trilinear}) {
      const Texture2D texture(ImageRGBA(7, 5, c), Sampler{wrap, wrap, filter});
      for (int i = 0; i < 200; ++i) expect_near(texture.sample({coord(rng), coord(rng)}, lod(rng)), c, 1e-6f);
    }
}

TEST(Texture2D, TrilinearBlendsTheTwoLevelsAroundLod) {
  const Texture2D texture(random_image(16, 8, 5), Sampler{Wrap::repeat, Wrap::repeat, Filter::trilinear});
  const glm::vec2 uv(0.3f, 0.7f);
  expect_near(texture.sample(uv, 0.f), texture.bilinear(uv, 0), 1e-6f);
  expect_near(texture.sample(uv, 1.f), texture.bilinear(uv, 1), 1e-6f);
  expect_near(texture.sample(uv, 1.25f), 0.75f * texture.bilinear(uv, 1) + 0.25f * texture.bilinear(uv, 2), 1e-6f);
  expect_near(texture.sample(uv, -4.f), texture.bilinear(uv, 0), 1e-6f);  // magnification: level 0
  expect_near(texture.sample(uv, 50.f), mean(texture.level(0)), 1e-5f);
}

TEST(Texture2D, LodFromDerivativesIsLog2OfTheFootprintInTexels) {
  const Texture2D texture(random_image(64, 32, 9), Sampler{Wrap::repeat, Wrap::repeat, Filter::trilinear});
  EXPECT_NEAR(texture.lod({1.f / 64, 0.f}, {0.f, 1.f / 32}), 0.f, 1e-6f);
  EXPECT_NEAR(texture.lod({4.f / 64, 0.f}, {0.f, 1.f / 32}), 2.f, 1e-6f);
  EXPECT_NEAR(texture.lod({0.f, 0.f}, {3.f / 64, 4.f / 32}), std::log2(5.f), 1e-6f);  // |(3, 4)| = 5 texels
  EXPECT_EQ(texture.lod({0.f, 0.f}, {0.f, 0.f}), -std::numeric_limits<float>::infinity());
  const glm::vec2 uv(0.41f, 0.13f);
  expect_near(texture.sample(uv, {4.f / 64, 0.f}, {0.f, 4.f / 32}), texture.sample(uv, 2.f), 1e-6f);
  expect_near(texture.sample(uv, {0.f, 0.f}, {0.f, 0.f}), texture.bilinear(uv, 0), 1e-6f);
}

TEST(Texture2D, MinifiedCheckerboardTurnsGrayInsteadOfSparkling) {
  ImageRGBA checker(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) checker(x, y) = glm::vec4(float((x + y) % 2));
  const Texture2D texture(checker, Sampler{Wrap::repeat, Wrap::repeat, Filter::trilinear});
  // A footprint of 8 texels per pixel: level 3, where every texel averages 8x8 checks.
  for (float u : {0.1f, 0.37f, 0.8f})
    expect_near(texture.sample({u, 0.5f}, {8.f / 64, 0.f}, {0.f, 8.f / 64}), glm::vec4(0.5f), 1e-6f);
}

TEST(LatLong, KnownDirections) {
  const auto near2 = [](glm::vec2 a, glm::vec2 b) { return glm::length(a - b) < 1e-6f; };
  EXPECT_TRUE(near2(latlong_uv({0, 0, -1}), {0.5f, 0.5f}));
  EXPECT_TRUE(near2(latlong_uv({1, 0, 0}), {0.75f, 0.5f}));
  EXPECT_TRUE(near2(latlong_uv({-2, 0, 0}), {0.25f, 0.5f}));
  EXPECT_NEAR(latlong_uv({0, 1, 0}).y, 1.f, 1e-6f);
  EXPECT_NEAR(latlong_uv({0, -1, 0}).y, 0.f, 1e-6f);
  EXPECT_NEAR(latlong_uv({1, 1, 0}).y, 0.75f, 1e-6f);
  EXPECT_NEAR(std::abs(latlong_uv({0, 0, 1}).x - 0.5f), 0.5f, 1e-6f);  // +z is the seam u = 0 = 1
}

TEST(LatLong, RoundTrips) {
  std::mt19937 rng(11);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 d(normal(rng), normal(rng), normal(rng));
    const glm::vec3 back = latlong_direction(latlong_uv(d));
    EXPECT_LT(glm::length(back - glm::normalize(d)), 1e-5f);
  }
  std::uniform_real_distribution<float> inner(0.01f, 0.99f);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 uv(inner(rng), inner(rng));
    EXPECT_LT(glm::length(latlong_uv(latlong_direction(uv)) - uv), 1e-5f);
  }
}

TEST(CubeMap, AxesPickTheirFacesAtTheCenter) {
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    const CubeCoord c = cube_coord(axes[f] * 3.f);
    EXPECT_EQ(int(c.face), f);
    EXPECT_NEAR(c.st.x, 0.5f, 1e-6f);
    EXPECT_NEAR(c.st.y, 0.5f, 1e-6f);
  }
  const CubeCoord zero = cube_coord({0, 0, 0});
  EXPECT_EQ(zero.face, CubeFace::pos_x);
}

TEST(CubeMap, FollowsTheOpenGLSelectionTable) {
  struct Case {
    glm::vec3 d;
    CubeFace face;
    float s, t;
  };
  // s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2 with the table's sc, tc.
  const Case cases[] = {
      {{2, 1, 0.5f}, CubeFace::pos_x, 0.5f * (-0.25f + 1), 0.5f * (-0.5f + 1)},
      {{-2, 1, 0.5f}, CubeFace::neg_x, 0.5f * (0.25f + 1), 0.5f * (-0.5f + 1)},
      {{0.5f, 2, 1}, CubeFace::pos_y, 0.5f * (0.25f + 1), 0.5f * (0.5f + 1)},
      {{0.5f, -2, 1}, CubeFace::neg_y, 0.5f * (0.25f + 1), 0.5f * (-0.5f + 1)},
      {{0.5f, 1, 2}, CubeFace::pos_z, 0.5f * (0.25f + 1), 0.5f * (-0.5f + 1)},
      {{0.5f, 1, -2}, CubeFace::neg_z, 0.5f * (-0.25f + 1), 0.5f * (-0.5f + 1)},
  };
  for (const Case& c : cases) {
    const CubeCoord got = cube_coord(c.d);
    EXPECT_EQ(got.face, c.face);
    EXPECT_NEAR(got.st.x, c.s, 1e-6f);
    EXPECT_NEAR(got.st.y, c.t, 1e-6f);
  }
}

TEST(CubeMap, DirectionAndFaceCoordinatesRoundTrip) {
  std::mt19937 rng(17);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 d(normal(rng), normal(rng), normal(rng));
    const glm::vec3 back = glm::normalize(cube_direction(cube_coord(d)));
    EXPECT_LT(glm::length(back - glm::normalize(d)), 1e-5f);
  }
  std::uniform_real_distribution<float> inner(0.01f, 0.99f);
  for (int i = 0; i < 600; ++i) {
    const CubeCoord c{CubeFace(i % 6), {inner(rng), inner(rng)}};
    const CubeCoord back = cube_coord(cube_direction(c));
    EXPECT_EQ(back.face, c.face);
    EXPECT_LT(glm::length(back.st - c.st), 1e-5f);
  }
}

TEST(CubeMap, FaceRowZeroIsTEqualsZero) {
  // On the side faces t = 0 looks up (tc = -ry): the top row of a face image sees the sky.
  const CubeMap cube = CubeMap::from_function(8, [](glm::vec3 d) { return glm::vec4(d, 1.f); });
  for (CubeFace f : {CubeFace::pos_x, CubeFace::neg_x, CubeFace::pos_z, CubeFace::neg_z}) {
    EXPECT_GT(cube.face(f).level(0)(4, 0).y, 0.5f);
    EXPECT_LT(cube.face(f).level(0)(4, 7).y, -0.5f);
  }
  EXPECT_EQ(cube.size(), 8);
}

TEST(CubeMap, RejectsBadFaces) {
  std::array<ImageRGBA, 6> faces;
  for (ImageRGBA& f : faces) f = ImageRGBA(4, 4);
  faces[3] = ImageRGBA(4, 5);
  EXPECT_THROW(CubeMap{faces}, InvalidInput);
  faces[3] = ImageRGBA(2, 2);
  EXPECT_THROW(CubeMap{faces}, InvalidInput);
  EXPECT_THROW(CubeMap::from_function(0, [](glm::vec3) { return glm::vec4(0.f); }), InvalidInput);
}

// A smooth function of direction for the environment tests.
glm::vec4 sky(glm::vec3 d) {
  return glm::vec4(0.5f + 0.5f * d.x, 0.5f + 0.5f * d.y * d.y, 0.5f + 0.25f * (d.x * d.z + d.z), 1.f);
}

TEST(EnvironmentMap, LatLongAndCubeMapAgreeWithTheFunction) {
  const int w = 256, h = 128;
  ImageRGBA latlong(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      latlong(x, y) = sky(latlong_direction({(float(x) + 0.5f) / float(w), 1.f - (float(y) + 0.5f) / float(h)}));
  const EnvironmentMap env(latlong);
  const CubeMap cube = CubeMap::from_function(64, [&](glm::vec3 d) { return env.lookup(d); });
  std::mt19937 rng(23);
  std::normal_distribution<float> normal;
  double env_sq = 0, cube_sq = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng)));
    const glm::vec4 truth = sky(d), e = env.lookup(d), c = cube.lookup(d);
    expect_near(e, truth, 0.02f, "lat-long");
    expect_near(c, truth, 0.03f, "cube");
    env_sq += glm::dot(e - truth, e - truth);
    cube_sq += glm::dot(c - truth, c - truth);
  }
  EXPECT_LT(std::sqrt(env_sq / n), 2e-3);
  EXPECT_LT(std::sqrt(cube_sq / n), 3e-3);
}

TEST(EnvironmentMap, IsContinuousAcrossTheSeam) {
  const EnvironmentMap env(random_image(32, 16, 29));
  expect_near(env.lookup({1e-4f, 0.1f, 1.f}), env.lookup({-1e-4f, 0.1f, 1.f}), 1e-3f);
}

// ---- 8-bit textures ----

ImageRGBA8 random_rgba8(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  ImageRGBA8 image(width, height);
  for (glm::u8vec4& p : image.pixels()) p = glm::u8vec4(rng() & 255, rng() & 255, rng() & 255, rng() & 255);
  return image;
}

TEST(Texture2D, EightBitImagesAreStoredEightBit) {
  const Texture2D eight(random_rgba8(64, 32, 1)), full(ImageRGBA(64, 32));
  EXPECT_EQ(eight.format(), TexelFormat::rgba8);
  EXPECT_EQ(eight.bytes_per_texel(), 4u);
  EXPECT_EQ(full.format(), TexelFormat::rgba32f);
  EXPECT_EQ(full.bytes_per_texel(), 16u);
  // 64x32 + 32x16 + 16x8 + 8x4 + 4x2 + 2x1 + 1x1 = 2731 texels.
  EXPECT_EQ(eight.levels(), 7);
  EXPECT_EQ(eight.bytes(), 2731u * 4);
  EXPECT_EQ(full.bytes(), 2731u * 16);
  EXPECT_EQ(eight.level_rgba8(6).width(), 1);
  EXPECT_THROW(eight.level_rgba8(7), InvalidInput);
  EXPECT_THROW(full.level_rgba8(0), InvalidInput);
}

// A PNG loaded by load_texture (8-bit texels) samples level 0 exactly as the float texture of read_image's image of
// the same file did: nearest and bilinear, every wrap mode, coordinates far outside [0, 1]; so does an environment
// map.
TEST(Texture2D, EightBitLevelZeroSamplesAreTheFloatTexturesBitForBit) {
  const std::filesystem::path png =
      std::filesystem::temp_directory_path() / ("tessera-texture-" + std::to_string(::getpid()) + ".png");
  write_image(png, random_rgba8(37, 23, 2));
  const ImageRGBA floats = read_image(png);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> coord(-3.f, 3.f);
  for (Wrap wrap : {Wrap::repeat, Wrap::clamp, Wrap::mirror})
    for (Filter filter : {Filter::nearest, Filter::bilinear, Filter::trilinear}) {
      const Sampler sampler{wrap, wrap, filter};
      const Texture2D eight = load_texture(png, sampler), full(floats, sampler);
      ASSERT_EQ(eight.format(), TexelFormat::rgba8);
      for (int i = 0; i < 2000; ++i) {
        const glm::vec2 uv(coord(rng), coord(rng));
        ASSERT_EQ(eight.sample(uv), full.sample(uv)) << uv.x << "," << uv.y;  // lod 0 for trilinear
        ASSERT_EQ(eight.nearest(uv, 0), full.nearest(uv, 0));
        ASSERT_EQ(eight.bilinear(uv, 0), full.bilinear(uv, 0));
      }
    }
  const EnvironmentMap eight = load_environment_map(png), full(floats);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 d(normal(rng), normal(rng), normal(rng));
    ASSERT_EQ(eight.lookup(d), full.lookup(d));
  }
  std::filesystem::remove(png);
}

// The integer taps of a 1D reduction of n samples: indices, integer weights and their sum (the three-tap box of odd
// sizes has weights (m - i, m, i + 1) / n with m = n / 2).
struct IntegerTaps {
  int index[3], weight[3], sum;
};

IntegerTaps integer_taps(int n, int i) {
  const int m = n / 2;
  if (n == 1) return {{0, 0, 0}, {1, 0, 0}, 1};
  if (n % 2 == 0) return {{2 * i, 2 * i + 1, 2 * i}, {1, 1, 0}, 2};
  return {{2 * i, 2 * i + 1, 2 * i + 2}, {m - i, m, i + 1}, n};
}

// Every 8-bit level against an exact computation from the 8-bit level above, in integers: the filtered value is
// num / den, and the level holds it rounded to nearest (halves up; at an exact half, either neighbor, since the
// float filter can land on either side).
TEST(Mipmaps, EightBitLevelsRoundTheExactFilterOfTheLevelAbove) {
  for (const auto& [w, h] :
       {std::pair{16, 8}, std::pair{7, 5}, std::pair{13, 1}, std::pair{1, 6}, std::pair{37, 20}, std::pair{64, 64}}) {
    const std::vector<ImageRGBA8> levels = build_mipmaps(random_rgba8(w, h, unsigned(w * 100 + h)));
    ASSERT_EQ(levels.size(), build_mipmaps(ImageRGBA(w, h)).size());
    for (size_t k = 1; k < levels.size(); ++k) {
      const ImageRGBA8 &above = levels[k - 1], &level = levels[k];
      ASSERT_EQ(level.width(), std::max(1, above.width() / 2));
      ASSERT_EQ(level.height(), std::max(1, above.height() / 2));
      for (int y = 0; y < level.height(); ++y)
        for (int x = 0; x < level.width(); ++x) {
          const IntegerTaps tx = integer_taps(above.width(), x), ty = integer_taps(above.height(), y);
          for (int c = 0; c < 4; ++c) {
            long long num = 0;
            for (int b = 0; b < 3; ++b)
              for (int a = 0; a < 3; ++a)
                num += (long long)ty.weight[b] * tx.weight[a] * above(tx.index[a], ty.index[b])[c];
            const long long den = (long long)tx.sum * ty.sum, rounded = (2 * num + den) / (2 * den);
            const int got = level(x, y)[c];
            if ((2 * num + den) % (2 * den) == 0)
              EXPECT_TRUE(got == rounded || got == rounded - 1) << w << "x" << h << " level " << k;
            else
              EXPECT_EQ(got, rounded) << w << "x" << h << " level " << k << " texel " << x << "," << y;
          }
        }
    }
  }
}

// Rounding at each level: level k of an 8-bit texture lies within k x 0.5/255 of the float texture's level k (each
// rounding adds at most half a step, and the filter, a convex combination, does not grow earlier errors).
TEST(Mipmaps, EightBitLevelsStayWithinHalfAStepPerLevelOfTheFloatPyramid) {
  const ImageRGBA8 bytes = random_rgba8(256, 96, 5);
  const Texture2D eight(bytes), full(to_float(bytes));
  double worst = 0;
  for (int k = 1; k < eight.levels(); ++k) {
    const ImageRGBA a = eight.level(k), b = full.level(k);
    double largest = 0;
    for (size_t i = 0; i < a.pixels().size(); ++i)
      for (int c = 0; c < 4; ++c) largest = std::max(largest, double(std::abs(a.pixels()[i][c] - b.pixels()[i][c])));
    EXPECT_LE(largest, k * 0.5 / 255 + 1e-6) << "level " << k;
    worst = std::max(worst, largest * 255);
  }
  std::printf("largest difference of the 8-bit and float levels: %.3f / 255\n", worst);
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

TEST(TextureLanes, SampleLanesAgreesWithSample) {
  // Every filter and wrap on an 8-bit texture of odd size (MIPmap levels of both parities), at random points well
  // outside [0, 1] and levels of detail below 0, between levels and past the last: within one 8-bit step (the SIMD
  // path's float coordinates), exactly for the per-point path (nearest, mirror).
  ImageRGBA8 image(37, 20);
  Rng rng(3);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      image(x, y) = glm::u8vec4(rng.next_u32() & 255, rng.next_u32() & 255, rng.next_u32() & 255, rng.next_u32() & 255);
  constexpr int kCount = 64;
  float u[kCount], v[kCount], lod[kCount], r[kCount], g[kCount], b[kCount], a[kCount];
  float* const out[4] = {r, g, b, a};
  for (const Filter filter : {Filter::nearest, Filter::bilinear, Filter::trilinear})
    for (const Wrap wrap : {Wrap::repeat, Wrap::clamp, Wrap::mirror}) {
      const Texture2D texture(image, Sampler{wrap, wrap, filter});
      float worst = 0;
      for (int round = 0; round < 50; ++round) {
        for (int k = 0; k < kCount; ++k) {
          u[k] = 6 * rng.uniform() - 3, v[k] = 6 * rng.uniform() - 3, lod[k] = 7 * rng.uniform() - 1.5f;
        }
        texture.sample_lanes(u, v, lod, out, kCount);
        for (int k = 0; k < kCount; ++k) {
          const glm::vec4 want = texture.sample(glm::vec2(u[k], v[k]), lod[k]);
          for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(out[c][k] - want[c]));
        }
      }
      const bool per_point = filter == Filter::nearest || wrap == Wrap::mirror;
      EXPECT_LE(worst, per_point ? 0.0f : 1.0f / 255) << int(filter) << " " << int(wrap);
    }
}

}  // namespace
}  // namespace tessera
