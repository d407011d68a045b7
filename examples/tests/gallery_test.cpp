// The gallery's pictures against their sources: 01's zoom shows the real pixels it claims to magnify; 15's painter
// and z-buffer panels show what a ray cast of their scene says; 28's Venn diagram is the notes' average, written
// linear or sRGB-encoded; 61's figure
// has the cube edges drawn and the corner markers visible where an independent projection (GLM's lookAt and
// perspective) puts them. And the shared data lookup: --data, then the environment, then the documented folders.
#include "gallery.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <optional>

#include "tessera/image/image_io.hpp"
#include "tessera/volume/mc_table.hpp"

namespace tessera::examples {
namespace {

namespace fs = std::filesystem;

// A fresh scratch folder for one test.
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("tessera-gallery-test-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

ImageRGBA8 read8(const fs::path& path) { return to_rgba8(read_image(path)); }

TEST(Gallery, PinkPixelZoomShowsTheRealPixels) {
  const fs::path dir = scratch("01");
  run_examples(dir, {{"01"}, {}, {}});
  const ImageRGBA8 picture = read8(dir / "01_pink_pixel.png"), zoom = read8(dir / "01_pink_pixel_zoom.png");
  // The caption's claim: pixels 190..209 on both axes, each a 20 x 20 cell.
  ASSERT_GE(zoom.width(), 400);
  ASSERT_GE(zoom.height(), 400);
  int white = 0, pink = 0, other = 0;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) {
      const glm::u8vec4 source = picture(190 + i, 190 + j);
      for (const glm::ivec2 d : {glm::ivec2(10, 10), glm::ivec2(3, 3), glm::ivec2(17, 16)})
        EXPECT_EQ(zoom(i * 20 + d.x, j * 20 + d.y), source) << "cell " << i << "," << j;
      const bool is_white = source == glm::u8vec4(255), is_pink = source == glm::u8vec4(255, 150, 150, 255);
      white += is_white, pink += is_pink, other += !is_white && !is_pink;
    }
  // The region really holds the white background, the pink pixel and the circle's outline.
  EXPECT_EQ(pink, 1);
  EXPECT_GT(white, 100);
  EXPECT_GT(other, 20);
}

TEST(Gallery, MarchingCubesCasesShowCubeEdgesAndCornerMarkers) {
  const fs::path dir = scratch("61");
  run_examples(dir, {{"61"}, {}, {}});
  const ImageRGBA8 sheet = read8(dir / "61_marching_cubes_cases.png");
  const int tile = 200;
  ASSERT_EQ(sheet.width(), 5 * tile);
  ASSERT_EQ(sheet.height(), 3 * tile);
  // The figure's camera (61_marching_cubes_cases.cpp): eye (2.6, 1.9, 3.2), looking at the cell's center, y up,
  // 32 degrees vertical field of view; projected here with GLM.
  const glm::dmat4 vp = glm::perspective(glm::radians(32.0), 1.0, 0.1, 100.0) *
                        glm::lookAt(glm::dvec3(2.6, 1.9, 3.2), glm::dvec3(0.5), glm::dvec3(0, 1, 0));
  const auto pixel = [&](const glm::dvec3& p) {
    const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
    return glm::dvec2((c.x / c.w + 1) * 0.5 * tile, (1 - c.y / c.w) * 0.5 * tile);
  };
  // The darkest pixel within one pixel of (x, y): the largest channel of it.
  const auto darkest = [&](int x0, int y0, const glm::dvec2& p) {
    int dark = 255;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const glm::u8vec4 c = sheet(x0 + int(p.x) + dx, y0 + int(p.y) + dy);
        dark = std::min(dark, std::max({int(c.x), int(c.y), int(c.z)}));
      }
    return dark;
  };
  for (size_t k = 0; k < mc::base_cases().size(); ++k) {
    const int cube_case = mc::base_cases()[k], x0 = int(k % 5) * tile, y0 = int(k / 5) * tile;
    for (const auto& [a, b] : mc::edges()) {
      const glm::dvec3 p(mc::corners()[size_t(a)]), q(mc::corners()[size_t(b)]);
      if (p == glm::dvec3(0) || q == glm::dvec3(0)) continue;  // the hidden corner's edges are dashed
      for (const double t : {0.25, 0.4, 0.75})
        EXPECT_LT(darkest(x0, y0, pixel(glm::mix(p, q, t))), 60) << "case " << k << " edge " << a << "-" << b;
    }
    for (int i = 0; i < 8; ++i) {
      const glm::dvec2 p = pixel(glm::dvec3(mc::corners()[size_t(i)]));
      const glm::u8vec4 c = sheet(x0 + int(p.x), y0 + int(p.y));
      if ((cube_case >> i) & 1)
        EXPECT_GT(int(c.z), int(c.x) + 100) << "case " << k << ": inside corner " << i << " is not a blue dot";
      else
        EXPECT_GT(std::min({c.x, c.y, c.z}), 220)
            << "case " << k << ": outside corner " << i << " is not an open circle";
    }
  }
}

TEST(Gallery, PainterPanelsShowWhatTheCaptionSays) {
  // 15_painter.png's first two panels against a ray cast of the same scene, done here: a sphere of radius 0.8 and
  // the slab's plane, turned by rotate_y(0.35) rotate_x(-0.2), seen from (0, 0, 4.5) with a 34-degree field of view
  // on 300 x 300 pixels (15_painter.cpp). The z-buffer panel shows whichever is nearer. The painter draws each triangle
  // whole, far to near by its average depth: a sphere triangle nearer than both of the slab's two big triangles'
  // centroids (each at a third of a corner's depth, negated) comes after them, so the sphere covers the slab there
  // even where the slab is in front: the caption's claim.
  const fs::path dir = scratch("15");
  run_examples(dir, {{"15"}, {}, {}});
  const ImageRGBA8 sheet = read8(dir / "15_painter.png");
  const int size = 300;
  ASSERT_EQ(sheet.width(), 4 * size);
  const glm::dmat4 turn = glm::rotate(glm::rotate(glm::dmat4(1.0), 0.35, {0, 1, 0}), -0.2, {1, 0, 0});
  const glm::dmat4 slab = turn * glm::scale(glm::rotate(glm::rotate(glm::dmat4(1.0), 0.25, {0, 0, 1}), 0.45, {1, 0, 0}),
                                            glm::dvec3(1.4, 1, 0.8));
  double nearest_centroid = -1e9;  // the largest z (nearest the eye) a slab triangle's centroid can have
  for (const double x : {-1.0, 1.0})
    for (const double z : {-1.0, 1.0})
      nearest_centroid = std::max(nearest_centroid, -(slab * glm::dvec4(x, 0, z, 1)).z / 3);
  const glm::dvec3 eye(0, 0, 4.5);
  const double tan_half = std::tan(glm::radians(17.0));
  int slab_front = 0, sphere_front = 0, painter_covers_slab = 0;
  for (int py = 20; py < size - 20; py += 4)
    for (int px = 20; px < size - 20; px += 4) {
      const glm::dvec3 d = glm::normalize(
          glm::dvec3(((px + 0.5) / (size / 2) - 1) * tan_half, (1 - (py + 0.5) / (size / 2)) * tan_half, -1));
      // The sphere (centered at the origin, so the turn does not move it).
      const double b = glm::dot(eye, d), disc = b * b - (glm::dot(eye, eye) - 0.64);
      if (std::abs(disc) < 0.03) continue;  // along the faceted silhouette
      const bool sphere_hit = disc > 0;
      const double t_sphere = sphere_hit ? -b - std::sqrt(disc) : 1e9;
      // The slab: the plane y = 0 of its own frame, |x|, |z| <= 1 there.
      const glm::dmat4 to_slab = glm::inverse(slab);
      const glm::dvec3 o = glm::dvec3(to_slab * glm::dvec4(eye, 1)), v = glm::dvec3(to_slab * glm::dvec4(d, 0));
      const double t_plane = -o.y / v.y;
      const glm::dvec3 q = o + t_plane * v;
      const double edge = std::max(std::abs(q.x), std::abs(q.z));
      if (t_plane > 0 && edge > 0.95 && edge < 1.05) continue;  // along the slab's edges
      const bool slab_hit = t_plane > 0 && edge < 1;
      const glm::u8vec4 zbuffer = sheet(size + px, py), painter = sheet(px, py);
      const auto blue = [](const glm::u8vec4& c) { return c.z > c.x + 40; };
      const auto orange = [](const glm::u8vec4& c) { return c.x > c.z + 40; };
      if (slab_hit && t_plane < std::min(t_sphere, 1e8) - 0.05) {
        ++slab_front;
        EXPECT_TRUE(blue(zbuffer)) << "z-buffer panel at " << px << "," << py << ": the slab is in front";
        if (sphere_hit && (eye + t_sphere * d).z > nearest_centroid + 0.15) {
          ++painter_covers_slab;
          EXPECT_TRUE(orange(painter)) << "painter panel at " << px << "," << py << ": the sphere is drawn last";
        }
      } else if (sphere_hit && (!slab_hit || t_sphere < t_plane - 0.05)) {
        ++sphere_front;
        EXPECT_TRUE(orange(zbuffer)) << "z-buffer panel at " << px << "," << py << ": the sphere is in front";
      }
    }
  EXPECT_GT(slab_front, 100);
  EXPECT_GT(sphere_front, 100);
  EXPECT_GT(painter_covers_slab, 20);
  std::ifstream index(dir / "index.html");
  const std::string html((std::istreambuf_iterator<char>(index)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("the sphere covers the slab even where the slab is in front"), std::string::npos);
}

TEST(Gallery, VennPictureAndItsSrgbEncoding) {
  // 28's two-texture picture, left panel: where only leftCoord = uv - (0.2, 0) falls in the orange disc (0.95, 0.45,
  // 0.1) and rightCoord reads the white background, the pixel is their average; written linear by default and with
  // the sRGB curve (IEC 61966-2-1) when the gallery runs with --srgb.
  const Vec3f half = 0.5f * (Vec3f(0.95f, 0.45f, 0.1f) + Vec3f(1.0f));
  const auto srgb = [](float c) { return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f; };
  for (const bool encode : {false, true}) {
    const fs::path dir = scratch(encode ? "28-srgb" : "28");
    run_examples(dir, {{"28"}, {}, {.srgb = encode}});
    const ImageRGBA8 picture = read8(dir / "28_two_texture_shader.png");
    const glm::u8vec4 lens = picture(120, 120), one = picture(180, 120), none = picture(120, 20);
    for (int k = 0; k < 3; ++k) {
      const float linear = half[k];
      EXPECT_NEAR(one[k], 255 * (encode ? srgb(linear) : linear), 1.5) << "channel " << k << " srgb " << encode;
    }
    EXPECT_EQ(none, glm::u8vec4(255));
    EXPECT_NEAR(lens.x, 255 * (encode ? srgb(0.95f) : 0.95f), 1.5);
  }
}

// Sets or unsets an environment variable for one test, restoring it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? setenv(name, value, 1) : unsetenv(name);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// Runs in `dir` for one test.
class ScopedCwd {
 public:
  explicit ScopedCwd(const fs::path& dir) : old_(fs::current_path()) { fs::current_path(dir); }
  ~ScopedCwd() { fs::current_path(old_); }

 private:
  fs::path old_;
};

TEST(Gallery, DataOptionThenEnvironmentThenDocumentedFolders) {
  const fs::path root = scratch("data-lookup");
  fs::create_directories(root / "work/shared/data");
  fs::create_directories(root / "work/main");
  ScopedEnv short_name("TESSERA_DATA", "/from/tessera_data"), long_name("TESSERA_SHARED_DATA", "/from/shared_data");
  EXPECT_EQ(locate_shared_data("/from/option").dir, "/from/option");
  EXPECT_EQ(locate_shared_data("/from/option").source, "--data");
  EXPECT_EQ(locate_shared_data().dir, "/from/tessera_data");
  {
    ScopedEnv unset_short("TESSERA_DATA", nullptr);
    EXPECT_EQ(locate_shared_data().dir, "/from/shared_data");
    ScopedEnv unset_long("TESSERA_SHARED_DATA", nullptr);
    {
      const ScopedCwd cwd(root / "work");
      EXPECT_EQ(fs::canonical(locate_shared_data().dir), fs::canonical(root / "work/shared/data"));
      EXPECT_EQ(locate_shared_data().source, "./shared/data");
    }
    {
      const ScopedCwd cwd(root / "work/main");
      EXPECT_EQ(fs::canonical(locate_shared_data().dir), fs::canonical(root / "work/shared/data"));
      EXPECT_EQ(locate_shared_data().source, "../shared/data");
    }
  }
  // The folders tried without the option or a variable, in order: the current folder's, its parent's, then above
  // the executable, then the build's.
  const std::vector<DataFolder> folders = default_data_folders();
  ASSERT_GE(folders.size(), 3u);
  EXPECT_EQ(folders[0].dir, "shared/data");
  EXPECT_EQ(folders[1].dir, "../shared/data");
  EXPECT_EQ(folders[2].dir.parent_path().parent_path(), fs::read_symlink("/proc/self/exe").parent_path());
}

TEST(Gallery, MissingDataFileWarnsAndCountsAStandIn) {
  const fs::path root = scratch("stand-in");
  fs::create_directories(root / "data/meshes");
  std::ofstream(root / "data/meshes/present.obj") << "v 0 0 0\n";
  Gallery gallery(root / "out", {root / "data", "--data"});
  EXPECT_EQ(gallery.data_file("meshes/present.obj", "nothing"), root / "data/meshes/present.obj");
  EXPECT_EQ(gallery.stand_ins(), 0u);
  testing::internal::CaptureStderr();
  EXPECT_FALSE(gallery.data_file("meshes/bunny/bun_zipper_res2.ply", "a torus"));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(gallery.stand_ins(), 1u);
  EXPECT_NE(err.find("warning"), std::string::npos) << err;
  EXPECT_NE(err.find("meshes/bunny/bun_zipper_res2.ply"), std::string::npos) << err;
  EXPECT_NE(err.find((root / "data").string()), std::string::npos) << err;
  EXPECT_NE(err.find("a torus"), std::string::npos) << err;
  EXPECT_EQ(stand_in_caption("a torus", "the bunny", "BVH."),
            "STAND-IN (shared data not found; drawn instead of the bunny: a torus): BVH.");
}

// The comparison against the reviewed references (docs/gallery) on one of them: the picture itself and a copy
// re-encoded pass; a 1-level rounding difference on every pixel passes; what a regression does fails: a shape moved
// by one pixel, one object's color changed by a few levels, a 2-level shift of every pixel's color, a different size.
TEST(Gallery, ReferenceComparisonCatchesOnePixelMovesAndColorChanges) {
  const ImageRGBA8 reference = read8("docs/gallery/05_body.png");  // dark outlines and flat fills on a light ground
  EXPECT_TRUE(compare_picture(reference, reference).passed);

  ImageRGBA8 rounded = reference;
  for (glm::u8vec4& p : rounded.pixels()) p.x = uint8_t(p.x < 255 ? p.x + 1 : p.x - 1);
  EXPECT_TRUE(compare_picture(rounded, reference).passed) << compare_picture(rounded, reference).message;

  ImageRGBA8 moved(reference.width(), reference.height(), reference(0, 0));
  for (int y = 0; y < reference.height(); ++y)
    for (int x = 1; x < reference.width(); ++x) moved(x, y) = reference(x - 1, y);
  const Comparison move = compare_picture(moved, reference);
  EXPECT_FALSE(move.passed) << move.message;

  // Recolor the pixels of the picture's most common non-background color by 6 levels (one fill).
  ImageRGBA8 recolored = reference;
  const glm::u8vec4 background = reference(0, 0);
  glm::u8vec4 fill = background;
  for (const glm::u8vec4& p : reference.pixels())
    if (p != background) {
      fill = p;
      break;
    }
  long long changed = 0;
  for (glm::u8vec4& p : recolored.pixels())
    if (p == fill) p.y = uint8_t(p.y >= 6 ? p.y - 6 : p.y + 6), ++changed;
  ASSERT_GT(changed, 0);
  const Comparison color = compare_picture(recolored, reference);
  EXPECT_FALSE(color.passed) << changed << " pixels: " << color.message;

  ImageRGBA8 shifted = reference;
  for (glm::u8vec4& p : shifted.pixels())
    for (int c = 0; c < 3; ++c) p[c] = uint8_t(p[c] >= 2 ? p[c] - 2 : p[c] + 2);
  const Comparison shift = compare_picture(shifted, reference);
  EXPECT_FALSE(shift.passed) << shift.message;

  const Comparison size = compare_picture(ImageRGBA8(reference.width() - 1, reference.height()), reference);
  EXPECT_FALSE(size.passed);
  EXPECT_NE(size.message.find("size"), std::string::npos) << size.message;
}

TEST(Gallery, StandInPicturesAreRecognizedByTheirCaption) {
  EXPECT_TRUE(is_stand_in({"x.png", stand_in_caption("a torus", "the bunny", "BVH.")}));
  EXPECT_FALSE(is_stand_in({"x.png", "BVH of the bunny."}));
}

}  // namespace
}  // namespace tessera::examples
