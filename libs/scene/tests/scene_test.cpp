// The scene loader: every built-in scene loads and renders; transforms compose as the notes' calls; meshes load
// relative to the scene file; bad documents fail with the JSON path and what was expected.
#include "tessera/scene/scene.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tessera/core/error.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/scene/raster.hpp"
#include "tessera/scene/trace.hpp"

namespace tessera {
namespace {

TEST(Scene, EveryBuiltinLoadsAndRenders) {
  const auto names = builtin_scene_names();
  for (const char* required : {"whitted", "cornell", "motion-blur", "mesh"})
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  for (const auto& name : names) {
    const Scene scene = builtin_scene(name);
    EXPECT_FALSE(scene.objects.empty()) << name;
    EXPECT_FALSE(scene.lights.empty()) << name;
    const RayScene rs = to_ray_scene(scene);
    RenderSettings s = render_settings(scene);
    s.width = 40;
    s.height = 30;
    s.samples = 1;
    s.progress = false;
    const ImageRGB img = render(rs, s);
    // Something other than the background is in view.
    int different = 0;
    for (const Vec3f& p : img.pixels()) different += glm::length(p - scene.image.background) > 0.05f ? 1 : 0;
    EXPECT_GT(different, 40 * 30 / 4) << name;
  }
}

TEST(Scene, WhittedHasAMirrorAndAGlassSphereOverACheckerboard) {
  const Scene s = builtin_scene("whitted");
  int spheres = 0;
  for (const auto& o : s.objects) spheres += o.shape && std::holds_alternative<Sphere>(*o.shape) ? 1 : 0;
  EXPECT_EQ(spheres, 2);
  EXPECT_GT(s.materials.at("mirror").reflection.x, 0.5f);
  EXPECT_EQ(s.materials.at("glass").ior, ior::kGlass);
  EXPECT_GT(s.materials.at("checkerboard").checker, 0.0f);
}

std::string with_objects(const std::string& objects, const std::string& extra = "") {
  return R"({"materials": {"m": {"diffuse": 0.5}}, )" + extra + R"("objects": )" + objects + "}";
}

/// The message of the InvalidInput that parsing `json` throws.
std::string error_of(const std::string& json) {
  try {
    parse_scene(json, "test.json", ".");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Scene, DuplicateKeysAreRefusedWithTheirPath) {
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m"},
                                      {"type": "sphere", "radius": 1, "radius": 2, "material": "m"}])")),
            "test.json: objects[1]: duplicate key 'radius' (each key may appear once in an object)");
  EXPECT_EQ(error_of(R"({"objects": [], "objects": []})"),
            "test.json: (top level): duplicate key 'objects' (each key may appear once in an object)");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m", "center": [0, 0, 0]}])",
                                  R"("camera": {"eye": [0, 0, 5], "center": [0, 0, 0], "eye": [1, 1, 1]}, )")),
            "test.json: camera: duplicate key 'eye' (each key may appear once in an object)");
  // The same key in sibling objects and nested arrays is fine.
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m", "center": [0, 0, 0]},
                                      {"type": "sphere", "material": "m", "center": [[1], 0, 0]}])"))
                .find("duplicate"),
            std::string::npos);
}

TEST(Scene, AFolderIsNotAScene) {
  const auto dir = std::filesystem::temp_directory_path() / ("tessera_scene_dir_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  try {
    load_scene(dir);
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory, expected a file"), std::string::npos) << e.what();
  }
  std::filesystem::remove(dir);
}

TEST(Scene, ErrorsNameTheJsonPath) {
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m"},
                                      {"type": "sphere", "radius": -1, "material": "m"}])")),
            "test.json: objects[1].radius: expected a positive number");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "nope"}])")),
            "test.json: objects[0].material: no material named 'nope'");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "radius": 1, "colour": 1, "material": "m"}])")),
            "test.json: objects[0].colour: unknown key for a sphere");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "torus", "material": "m"}])")).substr(0, 32),
            "test.json: objects[0].type: expe");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m", "transform": [{"shear": 1}]}])")),
            "test.json: objects[0].transform[0]: expected translate, rotate, scale or matrix");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "box", "min": [0, 0, 0], "max": [1, 0, 1], "material": "m"}])")),
            "test.json: objects[0]: expected min < max in every coordinate");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0]],
                                      "material": "m"}])")),
            "test.json: objects[0].vertices: the vertices enclose no area");
  EXPECT_EQ(error_of(with_objects("[]")), "test.json: objects: expected at least 1 elements");
  EXPECT_EQ(error_of(with_objects("[1]")), "test.json: objects[0]: expected an object");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m"}])", R"("lights": [[]], )")),
            "test.json: lights[0]: expected an object");
  EXPECT_EQ(error_of(R"({"materials": {}})"), "test.json: objects: missing");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m"}])", R"("image": {"size": [0, 10]}, )")),
            "test.json: image.size[0]: expected an integer in [1, 65536]");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m"}])",
                                  R"("lights": [{"type": "point", "position": [0, 1]}], )")),
            "test.json: lights[0].position: expected an array of 3 numbers");
  EXPECT_EQ(error_of(with_objects(R"([{"type": "sphere", "material": "m"}])",
                                  R"("camera": {"eye": [0, 0, 0], "center": [0, 0, 0]}, )")),
            "test.json: camera: eye and center coincide");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"ior": "honey"}}, "objects": []})"),
            "test.json: materials.m.ior: expected a number or one of air, water, glass, ice, diamond, vacuum");
  const std::string syntax = error_of("{\"objects\": [1, 2,]}");
  EXPECT_EQ(syntax.rfind("test.json: byte offset 19: ", 0), 0u) << syntax;
  // A number beyond double's range is an out_of_range error inside the JSON library (found by fuzz/scene_fuzz.cpp: it
  // escaped as a foreign exception); it is located like a syntax error.
  EXPECT_EQ(error_of(R"({"ambient": 1e999})"), "test.json: byte offset 17: number overflow parsing '1e999'");
  // A transform the parser accepts (no zero factor) but the ray tracer cannot invert: the error names the object.
  try {
    to_ray_scene(parse_scene(with_objects(R"([{"type": "sphere", "material": "m"},
        {"type": "sphere", "material": "m", "transform": [{"scale": [1e-30, 1, 1]}]}])"),
                             "test.json", "."));
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "test.json: objects[1]: Instance: the transform is singular (determinant 1e-30)");
  }
}

TEST(Scene, TransformListComposesLikeTheNotesCalls) {
  // M = translate * scale: the scale (written last) acts first, so (1, 0, 0) goes to (2, 0, 0) then (3, 0, 0).
  const Scene s = parse_scene(with_objects(R"([{"type": "sphere", "material": "m",
      "transform": [{"translate": [1, 0, 0]}, {"scale": 2}, {"rotate": {"angle": 90, "axis": [0, 0, 1]}}],
      "velocity": [0, 1, 0]}])"),
                              "t", ".");
  const Vec3 p = transform_point(s.objects[0].transform, {0, 1, 0});  // rotate (0,1,0) -> (-1,0,0), scale, translate
  EXPECT_NEAR(p.x, -1.0, 1e-12);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  EXPECT_EQ(s.objects[0].motion.velocity, Vec3f(0, 1, 0));
  const Scene m = parse_scene(with_objects(R"([{"type": "sphere", "material": "m",
      "transform": [{"matrix": [1, 0, 0, 5,  0, 1, 0, 6,  0, 0, 1, 7,  0, 0, 0, 1]}]}])"),
                              "t", ".");
  EXPECT_EQ(transform_point(m.objects[0].transform, {0, 0, 0}), Vec3(5, 6, 7));  // rows as written
}

TEST(Scene, MeshFilesAreRelativeToTheSceneFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("tessera_scene_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "scene.json") << with_objects(R"([{"type": "mesh", "file": "meshes/tri.obj", "material": "m"}])");
  const Scene s = load_scene(dir / "scene.json");
  ASSERT_TRUE(s.objects[0].mesh);
  EXPECT_EQ(s.objects[0].mesh->triangle_count(), 1u);
  std::ofstream(dir / "bad.json") << with_objects(R"([{"type": "mesh", "file": "meshes/none.obj", "material": "m"}])");
  EXPECT_THROW(load_scene(dir / "bad.json"), IoError);
  EXPECT_THROW(load_scene(dir / "missing.json"), IoError);
  std::filesystem::remove_all(dir);
}

TEST(Scene, TextureMultipliesTheSurfaceColor) {
  // A one-color red texture on a white floor seen from above: the floor shows C_r * texture = red only.
  const auto dir = std::filesystem::temp_directory_path() / ("tessera_scene_texture_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_image(dir / "red.png", ImageRGB(2, 2, Vec3f(1, 0, 0)));
  std::ofstream(dir / "scene.json") << R"({"image": {"size": [8, 8]}, "ambient": 1,
      "camera": {"eye": [0, 5, 0], "center": [0, 0, 0], "up": [0, 0, -1]},
      "materials": {"m": {"diffuse": 0.5, "texture": "red.png"}},
      "objects": [{"type": "plane", "material": "m"}]})";
  const Scene scene = load_scene(dir / "scene.json");
  RenderSettings s = render_settings(scene);
  s.progress = false;
  const ImageRGB img = render(to_ray_scene(scene), s);
  EXPECT_NEAR(img(4, 4).x, 0.5f, 1e-5);
  EXPECT_EQ(img(4, 4).y, 0.0f);
  EXPECT_EQ(img(4, 4).z, 0.0f);
  std::ofstream(dir / "bad.json")
      << R"({"materials": {"m": {"texture": "none.png"}}, "objects": [{"type": "plane", "material": "m"}]})";
  EXPECT_THROW(load_scene(dir / "bad.json"), IoError);
  std::filesystem::remove_all(dir);
}

TEST(Scene, UnknownBuiltinListsTheNames) {
  try {
    load_scene_or_builtin("no-such-scene");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("whitted"), std::string::npos) << e.what();
  }
}

TEST(Scene, TessellatedShapesHaveTheirAreas) {
  // Surface areas of the tessellations approach the analytic ones: sphere 4 pi r^2, box, capped cylinder
  // 2 pi r h + 2 pi r^2, cone pi r (r + slant), disk pi r^2 (polygons inscribed in circles are a little smaller).
  const auto area = [](const Shape& s) { return surface_area(to_poly_mesh(tessellate(s, 96))); };
  EXPECT_NEAR(area(Sphere{{1, 2, 3}, 2}), 4 * kPi * 4, 0.01 * 4 * kPi * 4);
  EXPECT_NEAR(area(Box{{0, 0, 0}, {1, 2, 3}}), 2 * (2 + 6 + 3), 1e-9);
  EXPECT_NEAR(area(Cylinder{0.5f, -1, 2, true}), 2 * kPi * 0.5 * 3 + 2 * kPi * 0.25, 0.01 * 10.9);
  EXPECT_NEAR(area(Cone{{0, 0, 0}, 1, 2, true}), kPi * (1 + std::sqrt(5.0)), 0.01 * 10.2);
  EXPECT_NEAR(area(Disk{{0, 0, 0}, {0, 0, 1}, 2}), kPi * 4, 0.01 * kPi * 4);
  EXPECT_NEAR(area(Ellipsoid{{0, 0, 0}, {1, 1, 1}}), 4 * kPi, 0.01 * 4 * kPi);
  // The cone's apex is where the notes put it, and its base cap at apex + height.
  const TriMesh cone = tessellate(Cone{{0, 1, 0}, 1, 2, true}, 16);
  double lo = 1e9, hi = -1e9;
  for (const auto& p : cone.positions) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
  EXPECT_NEAR(lo, 1.0, 1e-9);
  EXPECT_NEAR(hi, 3.0, 1e-9);
}

TEST(Scene, RasterizerAndRayTracerSeeTheSameSilhouettes) {
  // Two independent renderers (raster3d's z-buffer of tessellated shapes, the ray tracer's exact intersections) agree
  // on which pixels show the background in the shapes scene, except along the outlines.
  Scene scene = builtin_scene("shapes");
  const int w = 200, h = 90;
  const ImageRGB raster = rasterize_scene(scene, w, h);
  RenderSettings s = render_settings(scene);
  s.width = w;
  s.height = h;
  s.samples = 1;
  s.progress = false;
  const ImageRGB traced = render(to_ray_scene(scene), s);
  const auto is_background = [&](const Vec3f& c) { return glm::length(c - scene.image.background) < 0.02f; };
  int differ = 0, background = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      background += is_background(traced(x, y)) ? 1 : 0;
      differ += is_background(raster(x, y)) != is_background(traced(x, y)) ? 1 : 0;
    }
  EXPECT_GT(background, w * h / 10);  // the sky is in view
  EXPECT_LT(differ, w * h / 100);
}

/// Pixels where `shadowed` differs between the rasterized and the ray-traced pictures away from the ray-traced
/// shadows' outlines (first), and the ray-traced picture's shadowed pixels (second).
template <class Shadowed>
std::pair<int, int> shadow_differences(const ImageRGB& raster, const ImageRGB& traced, Shadowed shadowed) {
  const int w = traced.width(), h = traced.height();
  int differ = 0, in_shadow = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool a = shadowed(raster(x, y)), b = shadowed(traced(x, y));
      in_shadow += b;
      if (a == b) continue;
      // A difference must lie on an outline: a neighbour of the ray-traced picture disagrees with this pixel.
      bool outline = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = std::clamp(x + dx, 0, w - 1), ny = std::clamp(y + dy, 0, h - 1);
          outline |= shadowed(traced(nx, ny)) != b;
        }
      differ += outline ? 0 : 1;
    }
  return {differ, in_shadow};
}

/// A sphere and a box over a floor under `lights` (JSON), ambient 0.1, no reflections.
Scene shadow_scene(const std::string& lights) {
  const std::string json = R"({"image": {"size": [160, 120], "background": [0, 0, 0]}, "ambient": 0.1,
      "camera": {"eye": [0, 6, 7], "center": [0, 0, 0], "up": [0, 1, 0], "fovy": 45},
      "lights": )" + lights +
                           R"(,
      "materials": {"floor": {"diffuse": 0.8}, "m": {"diffuse": 0.6}},
      "objects": [{"type": "plane", "material": "floor"},
                  {"type": "sphere", "center": [-1, 1, 0], "radius": 1, "material": "m"},
                  {"type": "box", "min": [1, 0, -1.5], "max": [2, 1.5, -0.5], "material": "m"}]})";
  return parse_scene(json, "shadows.json", ".");
}

ImageRGB trace_once(const Scene& scene) {
  RenderSettings settings = render_settings(scene);
  settings.samples = 1;
  settings.progress = false;
  return render(to_ray_scene(scene), settings);
}

TEST(Scene, RasterizedShadowsAreTheRayTracersHardShadows) {
  // One point light: the ray tracer's shadow rays and the rasterizer's shadow map, or its shadow volumes, must darken
  // the same floor pixels, except along the shadows' outlines.
  const Scene scene = shadow_scene(R"([{"type": "point", "position": [3, 7, 2], "color": 1}])");
  const ImageRGB traced = trace_once(scene);
  const int w = traced.width(), h = traced.height();
  for (const RasterShadows method : {RasterShadows::map, RasterShadows::volumes}) {
    const ImageRGB raster = rasterize_scene(scene, w, h, method);
    // The floor's shadowed pixels: ambient only, 0.8 * 0.1 (both renderers' floor is exactly that there).
    const auto [differ, in_shadow] = shadow_differences(raster, traced, [](const Vec3f& c) { return c.x < 0.12f; });
    EXPECT_GT(in_shadow, w * h / 30);  // the shadows are in view
    EXPECT_LT(differ, w * h / 500) << int(method);
  }
}

TEST(Scene, TheShadowMapSizeIsTheCallers) {
  // Coarser maps still give the ray tracer's shadows away from their outlines, and the outlines widen as the texels
  // grow (a red light's one view, a green light's six faces); a size the maps cannot have is an error, not looked at
  // with shadow volumes.
  const Scene scene = shadow_scene(R"([{"type": "point", "position": [3, 7, 2], "color": [1, 0, 0]},
                                       {"type": "point", "position": [0, 3, 0.5], "color": [0, 1, 0]}])");
  const ImageRGB traced = trace_once(scene);
  const int w = traced.width(), h = traced.height();
  const auto differences = [&](int size) {
    const ImageRGB raster = rasterize_scene(scene, w, h, RasterShadows::map, size);
    int differ = 0;
    for (int channel = 0; channel < 2; ++channel)
      differ += shadow_differences(raster, traced, [channel](const Vec3f& c) { return c[channel] < 0.12f; }).first;
    return differ;
  };
  const int fine = differences(2048), mid = differences(256), coarse = differences(16);
  EXPECT_LT(mid, w * h / 100);
  EXPECT_LE(fine, mid);
  EXPECT_GT(coarse, 2 * mid);
  for (const int bad : {0, -3, 16385})
    EXPECT_THROW(rasterize_scene(scene, w, h, RasterShadows::map, bad), InvalidInput) << bad;
  EXPECT_NO_THROW(rasterize_scene(scene, w, h, RasterShadows::volumes, 0));
}

TEST(Scene, RasterizedShadowsShadowEveryLight) {
  // A red light high above and a green one low between the casters (inside their bounding sphere: the shadow map
  // looks all around it, six faces): with either method each light's shadows, seen in its own channel, are the ray
  // tracer's.
  const Scene scene = shadow_scene(R"([{"type": "point", "position": [3, 7, 2], "color": [1, 0, 0]},
                                       {"type": "point", "position": [0, 3, 0.5], "color": [0, 1, 0]}])");
  const ImageRGB traced = trace_once(scene);
  const int w = traced.width(), h = traced.height();
  for (const RasterShadows method : {RasterShadows::map, RasterShadows::volumes}) {
    const ImageRGB raster = rasterize_scene(scene, w, h, method);
    for (int channel = 0; channel < 2; ++channel) {
      const auto shadowed = [channel](const Vec3f& c) { return c[channel] < 0.12f; };
      const auto [differ, in_shadow] = shadow_differences(raster, traced, shadowed);
      EXPECT_GT(in_shadow, w * h / 30) << int(method) << " " << channel;
      EXPECT_LT(differ, w * h / 500) << int(method) << " " << channel;
    }
  }
}

}  // namespace
}  // namespace tessera
