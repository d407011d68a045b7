// The runner's outputs and determinism, and the built-in sketches against independent expectations.
#include "tessera/sketch/runner.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tessera/glsl/program_files.hpp"
#include "tessera/image/image_io.hpp"

namespace tessera {
namespace {

std::vector<ImageRGBA8> record(std::string_view name, RunOptions options) {
  const SketchInfo* info = find_sketch(name);
  EXPECT_NE(info, nullptr) << name;
  std::vector<ImageRGBA8> frames;
  const auto sketch = info->make();
  run_sketch(*sketch, options, [&](int, const ImageRGBA8& picture) { frames.push_back(picture); });
  return frames;
}

bool same_bytes(const ImageRGBA8& a, const ImageRGBA8& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.row(0), b.row(0), size_t(a.width()) * size_t(a.height()) * 4) == 0;
}

TEST(Runner, ModeIsAWindowUnlessHeadlessOrAnOutputIsAsked) {
  // docs/sketch.md: --window opens one; without it, a window unless --headless or -o, as Processing's Run.
  EXPECT_EQ(run_mode(false, false, ""), RunMode::window);
  EXPECT_EQ(run_mode(false, true, ""), RunMode::headless);
  EXPECT_EQ(run_mode(false, false, "out.gif"), RunMode::headless);
  EXPECT_EQ(run_mode(true, false, "out.gif"), RunMode::window);
}

TEST(Registry, SortedFindableAndDescribed) {
  const auto all = builtin_sketches();
  ASSERT_GE(all.size(), 2u);
  for (size_t i = 0; i < all.size(); ++i) {
    if (i > 0) {
      EXPECT_LT(all[i - 1].name, all[i].name);
    }
    EXPECT_FALSE(all[i].description.empty());
    EXPECT_EQ(find_sketch(all[i].name), &all[i]);
    EXPECT_NO_THROW(parse_input_script(all[i].demo_input, all[i].name));
  }
  EXPECT_EQ(find_sketch("no_such_sketch"), nullptr);
}

TEST(PinkSquare, IsTheNotesPinkSquareCenteredOnTheMouse) {
  RunOptions o;
  o.frames = 2;
  o.events = parse_input_script("2 mouse_move 100 80\n");
  const auto frames = record("pink_square", o);
  ASSERT_EQ(frames.size(), 2u);
  const ImageRGBA8& f = frames[1];
  ASSERT_EQ(f.width(), 400);
  ASSERT_EQ(f.height(), 400);
  // rect(mouse_x - 25, mouse_y - 25, 50, 50) covers exactly x in [75, 125), y in [55, 105) (half-open fills).
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) {
      const bool inside = x >= 75 && x < 125 && y >= 55 && y < 105;
      const glm::u8vec4 expected = inside ? glm::u8vec4(255, 150, 150, 255) : glm::u8vec4(255, 255, 255, 255);
      ASSERT_EQ(f(x, y), expected) << x << "," << y;
    }
}

TEST(Runner, HeadlessBytesDoNotDependOnThreads) {
  for (const SketchInfo& info : builtin_sketches()) {
    RunOptions o;
    o.frames = 12;
    o.events = parse_input_script(info.demo_input, info.name);
    o.threads = 1;
    const auto one = record(info.name, o);
    o.threads = 2;
    const auto two = record(info.name, o);
    ASSERT_EQ(one.size(), two.size()) << info.name;
    for (size_t i = 0; i < one.size(); ++i) EXPECT_TRUE(same_bytes(one[i], two[i])) << info.name << " frame " << i;
    // And the frames do change (the sketch moves).
    EXPECT_FALSE(same_bytes(one.front(), one.back())) << info.name;
  }
}

TEST(Runner, WritesANumberedSequenceOrTheLastPicture) {
  const auto dir = std::filesystem::path(testing::TempDir()) / "sketch_runner_output";
  std::filesystem::remove_all(dir);
  RunOptions o;
  o.frames = 3;
  o.events = parse_input_script("1 mouse_move 10 10\n2 mouse_move 200 200\n3 mouse_move 390 390\n");
  o.output = dir.string() + "/seq/";
  const auto frames = record("pink_square", o);
  for (int i = 0; i < 3; ++i) {
    const auto path = dir / "seq" / ("frame-000" + std::to_string(i) + ".png");
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    EXPECT_TRUE(same_bytes(to_rgba8(read_image(path)), frames[i])) << path;
  }
  o.output = dir / "last.png";
  record("pink_square", o);
  EXPECT_TRUE(same_bytes(to_rgba8(read_image(dir / "last.png")), frames[2]));
}

TEST(Runner, ThreeDimensionalSketchTurns) {
  RunOptions o;
  o.frames = 30;
  o.size = std::pair{96, 96};
  const auto frames = record("rotating_cube", o);
  ASSERT_EQ(frames.size(), 30u);
  EXPECT_EQ(frames[0].width(), 96);
  // The background's corner is the clear color (0.1, 0.1, 0.15); the center is a face of the cube.
  EXPECT_EQ(frames[5](0, 0), glm::u8vec4(26, 26, 38, 255));
  EXPECT_NE(frames[5](48, 48), frames[5](0, 0));
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// A 3D sketch drawing one quad through a GLSL program loaded from files (Processing's loadShader and shader()).
class ShaderSketch : public Sketch {
 public:
  explicit ShaderSketch(std::filesystem::path dir) : dir_(std::move(dir)) {}
  void setup() override {
    size(16, 16, Renderer::p3d);
    program_ = load_shader((dir_ / "paint.frag").string(), (dir_ / "paint.vert").string());
  }
  void draw() override {
    raster3d::Context& ctx = context();
    ctx.clear(Vec3f(0));
    shader(program_);
    ctx.begin(raster3d::Primitive::quads);
    for (const auto& [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) ctx.vertex(x, y, 0);
    ctx.end();
  }

 private:
  std::filesystem::path dir_;
  std::shared_ptr<glsl::ProgramFiles> program_;
};

void write_shader(const std::filesystem::path& path, const std::string& text, int edit) {
  std::ofstream(path) << text;
  std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now() + std::chrono::seconds(edit));
}

TEST(Runner, ShadersAreReloadedWhenTheirFilesChange) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sketch_shader";
  std::filesystem::create_directories(dir);
  write_shader(dir / "paint.vert", "void main() { gl_Position = gl_Vertex; }", 0);
  write_shader(dir / "paint.frag", "void main() { gl_FragColor = vec4(1.0, 0.0, 0.0, 1.0); }", 1);
  ShaderSketch sketch(dir);
  RunOptions options;
  options.frames = 3;
  std::vector<glm::u8vec4> centers;
  run_sketch(sketch, options, [&](int frame, const ImageRGBA8& picture) {
    centers.push_back(picture(8, 8));
    // After frame 1 the file is edited; after frame 2 it is broken (the last good program keeps drawing).
    if (frame == 1) write_shader(dir / "paint.frag", "void main() { gl_FragColor = vec4(0.0, 1.0, 0.0, 1.0); }", 2);
    if (frame == 2) write_shader(dir / "paint.frag", "void main() { gl_FragColor = 1.0; }", 3);
  });
  ASSERT_EQ(centers.size(), 3u);
  EXPECT_EQ(centers[0], glm::u8vec4(255, 0, 0, 255));
  EXPECT_EQ(centers[1], glm::u8vec4(0, 255, 0, 255));
  EXPECT_EQ(centers[2], glm::u8vec4(0, 255, 0, 255));
}

}  // namespace
}  // namespace tessera
