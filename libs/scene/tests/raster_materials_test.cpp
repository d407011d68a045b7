// The two backends against analytic pictures and against each other: orthographic cameras (sizes in pixels that do
// not change with distance), the checkerboard's cells at known pixels, textures at the ray tracer's uv, glass blended
// (not black), mirrors reflecting the background and the other objects, each material's mean color within a
// tolerance of the ray tracer's.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/scene/raster.hpp"
#include "tessera/scene/scene.hpp"
#include "tessera/scene/trace.hpp"

namespace tessera {
namespace {

/// A scene of `objects` and `materials` (JSON) seen by `camera` (JSON) at size x size, ambient 1, no lights: every
/// surface shows C_r (plus its mirror and glass terms).
Scene unlit(const std::string& camera, const std::string& materials, const std::string& objects, int size = 64,
            const std::string& background = "0") {
  return parse_scene(R"({"image": {"size": [)" + std::to_string(size) + ", " + std::to_string(size) +
                         R"(], "background": )" + background + R"(, "depth": 8}, "ambient": 1, "camera": )" + camera +
                         R"(, "materials": )" + materials + R"(, "objects": )" + objects + "}",
                     "test.json", ".");
}

ImageRGB traced(const Scene& scene) {
  RenderSettings s = render_settings(scene);
  s.samples = 1;
  s.progress = false;
  return render(to_ray_scene(scene), s);
}

ImageRGB rasterized(const Scene& scene, RasterShadows method = RasterShadows::map) {
  return rasterize_scene(scene, scene.image.width, scene.image.height, method);
}

/// Both backends' pictures (the rasterizer with either shadow method; shadow volumes need a perspective camera).
std::vector<ImageRGB> both(const Scene& scene) {
  if (scene.camera.orthographic) return {traced(scene), rasterized(scene)};
  return {traced(scene), rasterized(scene), rasterized(scene, RasterShadows::volumes)};
}

/// The pixels where `inside(x, y)`: their count and mean color.
std::pair<int, Vec3f> mean_over(const ImageRGB& img, const std::function<bool(int, int)>& inside) {
  int n = 0;
  Vec3f sum(0.0f);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (inside(x, y)) ++n, sum += img(x, y);
  return {n, n ? sum / float(n) : sum};
}

int count_lit(const ImageRGB& img) {
  return mean_over(img, [&](int x, int y) { return img(x, y).x > 0.5f; }).first;
}

constexpr const char* kWhite = R"({"m": {"diffuse": 1}})";

TEST(SceneCamera, ProjectionKeysAreCheckedAndTheHeightDefaultsToThePerspectiveFraming) {
  const Scene s = unlit(R"({"eye": [0, 0, 10], "fovy": 90, "projection": "orthographic"})", kWhite,
                        R"([{"type": "sphere", "material": "m"}])");
  EXPECT_TRUE(s.camera.orthographic);
  EXPECT_NEAR(s.camera.ortho_height, 2 * 10 * std::tan(kPi / 4), 1e-12);
  const auto fails = [](const std::string& camera, const std::string& what) {
    try {
      unlit(camera, kWhite, R"([{"type": "sphere", "material": "m"}])");
      ADD_FAILURE() << camera;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fails(R"({"projection": "fisheye"})", "camera.projection: expected perspective or orthographic");
  fails(R"({"projection": "orthographic", "ortho_height": -1})", "camera.ortho_height: expected a positive number");
  fails(R"({"ortho_height": 3})", "camera.ortho_height: applies to \"projection\": \"orthographic\" only");
  EXPECT_FALSE(unlit(R"({"projection": "perspective"})", kWhite, R"([{"type": "sphere", "material": "m"}])")
                   .camera.orthographic);
}

TEST(SceneCamera, OrthographicSquareIsExactlyItsSizeInPixels) {
  // ortho_height 4 over 64 rows: 16 pixels per unit. The unit square about the axis covers the pixel centers of
  // columns and rows 24..39 (centers at -2 + (i + 1/2) / 16), none of them on an edge: exactly 16 x 16 pixels, from
  // near and from far.
  for (const double distance : {1.5, 40.0}) {
    const Scene scene = unlit(
        R"({"eye": [0, 0, )" + std::to_string(distance) + R"(], "projection": "orthographic", "ortho_height": 4})",
        kWhite, R"([{"type": "polygon", "material": "m",
                           "vertices": [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]]}])");
    const auto images = both(scene);
    for (size_t k = 0; k < images.size(); ++k) {
      const ImageRGB& img = images[k];
      EXPECT_EQ(count_lit(img), 256) << distance << " backend " << k;
      EXPECT_GT(img(24, 24).x, 0.5f);
      EXPECT_GT(img(39, 39).x, 0.5f);
      EXPECT_LT(img(23, 30).x, 0.5f);
      EXPECT_LT(img(40, 30).x, 0.5f);
    }
  }
}

TEST(SceneCamera, ShadowVolumesNeedAPerspectiveCamera) {
  const Scene scene = unlit(R"({"projection": "orthographic"})", kWhite, R"([{"type": "sphere", "material": "m"}])");
  EXPECT_THROW(rasterized(scene, RasterShadows::volumes), InvalidInput);
}

// Issue 24, class 3: a shadow map per light was allocated whatever its size. Two lights' maps of 512^2 texels are
// estimated at 2 x 512^2 x 6 bytes (4 a texel, 1.5 times the texels for a point light among the casters), 3 MiB,
// and refused in a 2 MiB budget before anything is drawn.
TEST(SceneCamera, ShadowMapsOverTheMemoryBudgetAreRefused) {
  const Scene scene = parse_scene(
      R"({"image": {"size": [16, 16]}, "camera": {}, "materials": {"m": {"diffuse": 1}},
          "objects": [{"type": "sphere", "material": "m"}],
          "lights": [{"type": "point", "position": [0, 3, 3]}, {"type": "point", "position": [3, 3, 0]}]})",
      "test.json", ".");
  MemoryBudget::set_limit(2 << 20);
  std::string message = "no error";
  try {
    rasterize_scene(scene, 16, 16, RasterShadows::map, 512);
  } catch (const MemoryBudgetError& e) {
    message = e.what();
  }
  MemoryBudget::set_limit(4 << 20);
  EXPECT_NO_THROW(rasterize_scene(scene, 16, 16, RasterShadows::map, 512));
  EXPECT_NO_THROW(rasterize_scene(scene, 16, 16, RasterShadows::volumes, 16384));  // no maps
  MemoryBudget::set_limit(0);
  EXPECT_EQ(message,
            "rasterize: 2 shadow maps of 512x512 texels needs about 3.0 MiB, the memory budget is 2.0 MiB "
            "(raise it with --max-memory SIZE)");
}

TEST(SceneCamera, OrthographicSilhouetteDoesNotChangeWithDistance) {
  // A unit sphere at 16 pixels per unit covers pi 16^2 = 804 pixels from any distance (the tessellation's polygon a
  // little less); through the perspective camera it shrinks with distance.
  for (const double distance : {3.0, 30.0}) {
    const std::string eye = R"({"eye": [0, 0, )" + std::to_string(distance) + "]";
    const Scene ortho = unlit(eye + R"(, "projection": "orthographic", "ortho_height": 4})", kWhite,
                              R"([{"type": "sphere", "material": "m"}])");
    for (const ImageRGB& img : both(ortho)) EXPECT_NEAR(count_lit(img), kPi * 256, 0.02 * kPi * 256) << distance;
    const Scene perspective = unlit(eye + "}", kWhite, R"([{"type": "sphere", "material": "m"}])");
    EXPECT_GT(std::abs(count_lit(traced(perspective)) - kPi * 256), 0.2 * kPi * 256) << distance;
  }
}

TEST(SceneMaterials, CheckerboardCellsAreAtTheirPixelsInBothBackends) {
  // The floor y = 0 seen from above, orthographic, 8 pixels per unit: pixel (i, j) shows world x = (i + 1/2) / 8 - 4,
  // z = (j + 1/2) / 8 - 4, whose cell parity floor(x) + floor(z) picks red or green (never on a cell edge).
  const Scene scene = unlit(R"({"eye": [0, 10, 0], "up": [0, 0, -1], "projection": "orthographic", "ortho_height": 8})",
                            R"({"m": {"diffuse": [1, 0, 0], "checker": {"size": 1, "color": [0, 1, 0]}}})",
                            R"([{"type": "plane", "material": "m"}])");
  for (const ImageRGB& img : both(scene))
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i) {
        const double x = (i + 0.5) / 8 - 4, z = (j + 0.5) / 8 - 4;
        const bool odd = (int(std::floor(x)) + int(std::floor(z))) & 1;
        ASSERT_NEAR(img(i, j).x, odd ? 0.0f : 1.0f, 0.01f) << i << "," << j;
        ASSERT_NEAR(img(i, j).y, odd ? 1.0f : 0.0f, 0.01f) << i << "," << j;
      }
}

TEST(SceneMaterials, PerspectiveCheckerboardMatchesTheRayTracer) {
  // Seen in perspective toward the horizon, the rasterizer's cells are the ray tracer's but along their edges.
  const Scene scene = unlit(R"({"eye": [0.3, 2, 6], "center": [0, 0, 0], "fovy": 50})",
                            R"({"m": {"diffuse": [1, 0, 0], "checker": {"size": 0.7, "color": [0, 1, 0]}}})",
                            R"([{"type": "plane", "material": "m"}])", 96);
  const ImageRGB ray = traced(scene), raster = rasterized(scene);
  int floor = 0, differ = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      if (ray(x, y) == Vec3f(0.0f)) continue;  // the sky
      ++floor;
      differ += glm::length(ray(x, y) - raster(x, y)) > 0.1f;
    }
  EXPECT_GT(floor, 96 * 96 / 3);
  EXPECT_LT(differ, floor / 20);  // the far rows' cells are a pixel or two wide: their edges are most of them
}

TEST(SceneMaterials, TexturesUseTheRayTracersCoordinatesOnEveryShape) {
  // A texture of distinct texels (nearest filtering) on a sphere, a box, a disk, a cylinder and a mesh without uvs
  // (the triangles' barycentrics): the rasterized pixels show the ray tracer's texels but along texel edges.
  Scene scene = unlit(R"({"eye": [1, 2, 9], "center": [0, 0, 0], "fovy": 45})", kWhite,
                      R"([{"type": "sphere", "center": [-1.5, 1, 0], "radius": 1, "material": "m"},
                          {"type": "box", "min": [0.5, 0.2, -0.5], "max": [2, 1.7, 0.5], "material": "m"},
                          {"type": "disk", "center": [0, -1, 0], "normal": [0, 1, 1], "radius": 1, "material": "m"},
                          {"type": "cylinder", "radius": 0.6, "y0": -2.5, "y1": -1.5, "material": "m",
                           "transform": [{"translate": [-2, 0, 0]}]},
                          {"type": "mesh", "primitive": "octahedron", "smooth": false, "material": "m",
                           "transform": [{"translate": [2, -1.5, 0]}]}])",
                      128);
  ImageRGBA texels(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) texels(x, y) = glm::vec4(float(x % 3) / 2, float((x + y) % 4) / 3, float(y) / 3, 1);
  Sampler nearest;
  nearest.filter = Filter::nearest;
  scene.materials["m"].texture = std::make_shared<Texture2D>(texels, nearest);
  const ImageRGB ray = traced(scene), raster = rasterized(scene);
  int object = 0, differ = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const bool a = ray(x, y) != Vec3f(0.0f), b = raster(x, y) != Vec3f(0.0f);
      if (!a || !b) continue;  // silhouettes differ by a pixel here and there
      ++object;
      differ += glm::length(ray(x, y) - raster(x, y)) > 0.1f;
    }
  EXPECT_GT(object, 128 * 128 / 8);
  EXPECT_LT(differ, object / 15);
  // The mean color over the objects agrees closely.
  const auto mean = [&](const ImageRGB& img) {
    return mean_over(img, [&](int x, int y) { return ray(x, y) != Vec3f(0.0f) && raster(x, y) != Vec3f(0.0f); }).second;
  };
  EXPECT_LT(glm::length(mean(ray) - mean(raster)), 0.03f);
}

/// The mean color over the pixels well inside a sphere of 16-pixel radius at the center of a 64 x 64 picture, for
/// the ray tracer and both rasterizer methods.
std::vector<Vec3f> sphere_means(const Scene& scene) {
  std::vector<Vec3f> means;
  for (const ImageRGB& img : both(scene))
    means.push_back(mean_over(img, [](int x, int y) { return std::hypot(x + 0.5 - 32, y + 0.5 - 32) < 14; }).second);
  return means;
}

const char* kOrthoSphereCamera = R"({"eye": [0, 0, 10], "projection": "orthographic", "ortho_height": 4})";

TEST(SceneMaterials, GlassIsBlendedNotBlack) {
  // A glass sphere (two surfaces, 90% transmission each) before a gray sky: the ray tracer sees the sky through both,
  // 0.9 x 0.9 x 0.5; the rasterizer blends the back and the front surfaces over it, the same. With Fresnel's term the
  // rim reflects more and transmits less, in both.
  for (const char* fresnel : {"false", "true"}) {
    const Scene scene =
        unlit(kOrthoSphereCamera,
              std::string(R"({"m": {"diffuse": 0, "ambient": 0, "transmission": 0.9, "fresnel": )") + fresnel + "}}",
              R"([{"type": "sphere", "material": "m"}])", 64, "0.5");
    const auto means = sphere_means(scene);
    EXPECT_NEAR(means[0].x, 0.81 * 0.5, 0.05) << fresnel;
    for (const Vec3f& m : means) {
      EXPECT_GT(m.x, 0.3f) << fresnel;
      EXPECT_NEAR(m.x, means[0].x, 0.03) << fresnel;
    }
  }
}

TEST(SceneMaterials, GlassShowsWhatLiesBehindIt) {
  // A glass pane (no refraction through a thin slab) before a red wall: the wall shows through at 0.9 of its color.
  const Scene scene = unlit(
      kOrthoSphereCamera,
      R"({"glass": {"diffuse": 0, "ambient": 0, "transmission": 0.9}, "red": {"diffuse": [1, 0, 0]}})",
      R"([{"type": "polygon", "material": "red", "vertices": [[-3, -3, -1], [3, -3, -1], [3, 3, -1], [-3, 3, -1]]},
          {"type": "polygon", "material": "glass", "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}])");
  const auto images = both(scene);
  for (size_t k = 0; k < images.size(); ++k) {
    EXPECT_NEAR(images[k](32, 32).x, 0.9f, 0.01f) << "backend " << k;
    EXPECT_NEAR(images[k](2, 2).x, 1.0f, 0.01f) << "backend " << k;
  }
}

TEST(SceneMaterials, MirrorsReflectTheBackground) {
  // A mirror sphere alone under a blue sky reflects only the sky: 0.8 of it, plus its own dim diffuse color.
  const Scene scene = unlit(kOrthoSphereCamera, R"({"m": {"diffuse": 0.05, "reflection": 0.8}})",
                            R"([{"type": "sphere", "material": "m"}])", 64, "[0.2, 0.4, 0.8]");
  const auto means = sphere_means(scene);
  const Vec3f expected = Vec3f(0.05f) + 0.8f * Vec3f(0.2f, 0.4f, 0.8f);
  for (const Vec3f& m : means) EXPECT_LT(glm::length(m - expected), 0.02f) << m.x << " " << m.y << " " << m.z;
}

TEST(SceneMaterials, MirrorsReflectTheOtherObjects) {
  // A red wall behind the viewer: the mirror sphere's middle reflects it (the ray tracer's reflected rays; the
  // rasterizer's cube map drawn from the sphere's center), the rim the sky beyond the sphere.
  const Scene scene = unlit(R"({"eye": [0, 0, 10], "projection": "orthographic", "ortho_height": 4})",
                            R"({"m": {"diffuse": 0, "reflection": 0.8}, "red": {"diffuse": [1, 0, 0]}})",
                            R"([{"type": "sphere", "material": "m"},
                                {"type": "polygon", "material": "red",
                                 "vertices": [[-40, -40, 20], [-40, 40, 20], [40, 40, 20], [40, -40, 20]]}])",
                            64, "[0, 0, 1]");
  const auto images = both(scene);
  for (size_t k = 0; k < images.size(); ++k) {
    const Vec3f middle =
        mean_over(images[k], [](int x, int y) { return std::hypot(x + 0.5 - 32, y + 0.5 - 32) < 4; }).second;
    EXPECT_LT(glm::length(middle - Vec3f(0.8f, 0, 0)), 0.03f) << "backend " << k;
    EXPECT_LT(glm::length(images[k](32, 18) - Vec3f(0, 0, 0.8f)), 0.03f) << "backend " << k;  // near the rim
  }
}

TEST(SceneMaterials, MirrorFloorsReflectTheObjectsAboveThem) {
  // A red sphere over a half-mirror floor: the ray tracer's reflected rays and the rasterizer's cube map drawn from the
  // eye's mirror image show the sphere's reflection on the same floor pixels, but along its outline.
  const Scene scene = unlit(R"({"eye": [0, 1.5, 6], "center": [0, 0.5, 0], "fovy": 40})",
                            R"({"floor": {"diffuse": 0.2, "reflection": 0.5}, "red": {"diffuse": [1, 0, 0]}})",
                            R"([{"type": "plane", "material": "floor"},
                                {"type": "sphere", "center": [0, 1, 0], "radius": 0.8, "material": "red"}])",
                            96, "[0, 0, 1]");
  const ImageRGB ray = traced(scene), raster = rasterized(scene);
  // The floor pixels that show the red reflection, (0.2, 0.2, 0.2) + 0.5 (1, 0, 0): not the sky's reflection
  // (0.2, 0.2, 0.7), nor the sphere's own red (1, 0, 0).
  const auto reflected = [](const Vec3f& c) { return c.x > 0.5f && c.x < 0.8f && c.z > 0.1f && c.z < 0.4f; };
  int both_red = 0, differ = 0;
  for (int y = 48; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      both_red += reflected(ray(x, y)) && reflected(raster(x, y));
      differ += reflected(ray(x, y)) != reflected(raster(x, y));
    }
  EXPECT_GT(both_red, 150);
  EXPECT_LT(differ, both_red / 5);
}

TEST(SceneMaterials, VisibleAreaLightsGlowInBothBackends) {
  // A rect light of color (1, 0.5, 0) facing the camera, 2 x 1 units at 16 pixels per unit: 32 x 16 pixels of its
  // color (columns 16..47, rows 24..39), and a hidden one nowhere.
  for (const char* visible : {"true", "false"}) {
    const Scene scene = parse_scene(std::string(R"({"image": {"size": [64, 64]}, "ambient": 0,
            "camera": {"eye": [0, 0, 10], "projection": "orthographic", "ortho_height": 4},
            "lights": [{"type": "rect", "corner": [-1, -0.5, 0], "edge_u": [0, 1, 0], "edge_v": [2, 0, 0],
                        "color": [1, 0.5, 0], "visible": )") +
                                        visible + R"(}],
            "materials": {"m": {"diffuse": 0}},
            "objects": [{"type": "sphere", "center": [0, 0, -50], "radius": 0.1, "material": "m"}]})",
                                    "lights.json", ".");
    const auto images = both(scene);
    for (size_t k = 0; k < images.size(); ++k) {
      const auto [count, mean] = mean_over(images[k], [&](int x, int y) { return images[k](x, y).x > 0.5f; });
      EXPECT_EQ(count, std::string(visible) == "true" ? 32 * 16 : 0) << "backend " << k;
      if (count) EXPECT_LT(glm::length(mean - Vec3f(1, 0.5f, 0)), 0.01f) << "backend " << k;
    }
  }
}

TEST(SceneMaterials, WhittedGlassIsNotBlack) {
  // Gallery 78's scene: the glass sphere's pixels were black in the rasterized picture; now they show the floor and
  // the sky through the glass, as bright on average as the ray tracer's within a fifth.
  const Scene scene = builtin_scene("whitted");
  const int w = 160, h = 120;
  RenderSettings s = render_settings(scene);
  s.width = w, s.height = h, s.samples = 1, s.progress = false;
  const ImageRGB ray = render(to_ray_scene(scene), s);
  // The glass sphere (center (-0.7, 1, 1), radius 0.9) projected: the pixels within 60% of its projected radius.
  Camera camera = scene.camera.camera(double(w) / h, 0.1, 100);
  const Mat4 clip = camera.projection() * camera.view();
  const auto pixel = [&](const Vec3& p) {
    const glm::dvec4 c = clip * glm::dvec4(p, 1.0);
    return Vec2((c.x / c.w + 1) / 2 * w, (1 - c.y / c.w) / 2 * h);
  };
  const Vec2 center = pixel({-0.7, 1, 1}), rim = pixel({-0.7, 1.9, 1});
  const double radius = 0.6 * glm::length(rim - center);
  const auto inside = [&](int x, int y) { return glm::length(Vec2(x + 0.5, y + 0.5) - center) < radius; };
  const Vec3f traced_mean = mean_over(ray, inside).second;
  for (const RasterShadows method : {RasterShadows::map, RasterShadows::volumes}) {
    const Vec3f raster_mean = mean_over(rasterize_scene(scene, w, h, method), inside).second;
    const float a = raster_mean.x + raster_mean.y + raster_mean.z, b = traced_mean.x + traced_mean.y + traced_mean.z;
    EXPECT_GT(a, 0.6f);
    EXPECT_NEAR(a, b, 0.2f * b);
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

/// Writes the files of a material shader into the test's folder: a uniform color over ftransform().
std::filesystem::path shader_folder() {
  // A folder of the test's own: ctest runs the tests of this file at once.
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) /
      (std::string("scene_shader_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "flat.vert") << "void main() { gl_Position = ftransform(); }\n";
  std::ofstream(dir / "flat.frag") << "uniform vec3 paint;\nvoid main() { gl_FragColor = vec4(paint, 1.0); }\n";
  std::ofstream(dir / "broken.frag") << "void main() {\n  gl_FragColor = 1.0;\n}\n";
  return dir;
}

Scene shader_scene(const std::string& shader) {
  return parse_scene(R"({"image": {"size": [48, 48]}, "ambient": 1,
      "camera": {"eye": [0, 0, 10], "projection": "orthographic", "ortho_height": 4},
      "materials": {"m": {"diffuse": 1, "shader": )" +
                         shader + R"(}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})",
                     "test.json", shader_folder());
}

TEST(SceneShaders, MaterialProgramPaintsItsObjectInTheRasterizer) {
  const Scene scene =
      shader_scene(R"({"vertex": "flat.vert", "fragment": "flat.frag", "uniforms": {"paint": [1, 0.5, 0]}})");
  const ImageRGB raster = rasterized(scene);
  // The ray tracer shades the material's own terms (white): the same silhouette, another color.
  const ImageRGB trace = traced(scene);
  const auto [painted, mean] = mean_over(raster, [&](int x, int y) { return raster(x, y).x > 0.5f; });
  EXPECT_NEAR(mean.x, 1.0f, 0.01f);
  EXPECT_NEAR(mean.y, 0.5f, 0.01f);
  EXPECT_NEAR(mean.z, 0.0f, 0.01f);
  const int silhouette = count_lit(trace);
  EXPECT_NEAR(painted, silhouette, 0.03 * silhouette);
  EXPECT_NEAR(painted, 3.14159 * 144, 0.05 * 3.14159 * 144);  // radius 12 pixels
}

TEST(SceneShaders, BadShadersNameTheirPlace) {
  const auto message = [](const std::string& shader) {
    try {
      shader_scene(shader);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(R"({"vertex": "flat.vert", "fragment": "broken.frag"})").find("broken.frag:2:"), std::string::npos);
  EXPECT_NE(message(R"({"vertex": "flat.vert", "fragment": "missing.frag"})").find("materials.m.shader.fragment"),
            std::string::npos);
  EXPECT_NE(message(R"({"vertex": "flat.vert", "fragment": "flat.frag", "uniforms": {"paint": [1, 0]}})")
                .find("materials.m.shader.uniforms.paint"),
            std::string::npos);
  EXPECT_NE(message(R"({"vertex": "flat.vert", "fragment": "flat.frag", "colour": 1})").find("unknown key"),
            std::string::npos);
}

}  // namespace
}  // namespace tessera
