// The runtime's frame-exact behaviour, headless: frame_count, millis, no_loop/redraw, scripted mouse and key events
// reaching the callbacks and the variables on the right frame (Processing's semantics, PApplet.handleDraw and
// handleMouseEvent), random seeds, save_frame, 3D double buffering.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster3d/gt.hpp"
#include "tessera/sketch/runner.hpp"

namespace tessera {
namespace {

/// Logs what each callback saw: "name@frame_count", and per draw() the variables.
struct Recorder : Sketch {
  struct Seen {
    int frame, mouse_x, mouse_y, pmouse_x, pmouse_y;
    bool pressed;
    MouseButton button;
    int key, key_code;
    bool key_pressed;
    int64_t millis;
  };
  std::vector<std::string> log;
  std::vector<Seen> draws;
  int setup_frame = -1;
  double fps = 60;

  void setup() override {
    size(40, 30);
    frame_rate(fps);
    setup_frame = frame_count;
  }
  void draw() override {
    draws.push_back({frame_count, mouse_x, mouse_y, pmouse_x, pmouse_y, mouse_is_pressed, mouse_button, key, key_code,
                     key_is_pressed, millis()});
  }
  void note(const std::string& what) {
    log.push_back(what + "@" + std::to_string(frame_count) + " " + std::to_string(mouse_x) + "," +
                  std::to_string(mouse_y) + " p" + std::to_string(pmouse_x) + "," + std::to_string(pmouse_y));
  }
  void mouse_pressed() override { note("pressed"); }
  void mouse_released() override { note("released"); }
  void mouse_moved() override { note("moved"); }
  void mouse_dragged() override { note("dragged"); }
  void mouse_wheel(double delta) override { note("wheel" + std::to_string(int(delta))); }
  void key_pressed() override { note(std::string("key_pressed ") + char(key)); }
  void key_released() override { note(std::string("key_released ") + char(key)); }
  void window_resized() override { note("resized " + std::to_string(window_width)); }
};

RunOptions frames(int n, std::string_view script = {}) {
  RunOptions o;
  o.frames = n;
  if (!script.empty()) o.events = parse_input_script(script);
  return o;
}

TEST(Sketch, FrameCountIsZeroInSetupAndCountsDraws) {
  Recorder s;
  const RunResult r = run_sketch(s, frames(5));
  EXPECT_EQ(s.setup_frame, 0);
  ASSERT_EQ(s.draws.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(s.draws[i].frame, i + 1);
  EXPECT_EQ(r.frames, 5);
  EXPECT_EQ(r.draws, 5);
  EXPECT_EQ(r.width, 40);
  EXPECT_EQ(r.height, 30);
}

TEST(Sketch, HeadlessMillisIsTheFramesTime) {
  Recorder s;
  s.fps = 25;  // 40 ms a frame
  run_sketch(s, frames(4));
  ASSERT_EQ(s.draws.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(s.draws[i].millis, 40 * i);
  // --fps replaces the sketch's frame_rate(): 50 fps, 20 ms a frame.
  Recorder t;
  t.fps = 25;
  RunOptions o = frames(3);
  o.fps = 50;
  run_sketch(t, o);
  EXPECT_EQ(t.draws[2].millis, 40);
}

/// Changes its frame rate in frame 2 (from then on 10 fps, 100 ms a frame).
struct Slows : Recorder {
  void draw() override {
    Recorder::draw();
    if (frame_count == 2) frame_rate(10);
  }
};

TEST(Sketch, FrameRateChangesTimeUnlessTheRunnerFixesIt) {
  Slows s;
  s.fps = 50;
  run_sketch(s, frames(4));
  EXPECT_EQ(s.draws[1].millis, 20);
  EXPECT_EQ(s.draws[2].millis, 120);  // frame 2 lasts 100 ms at the new rate
  EXPECT_EQ(s.draws[3].millis, 220);
  Slows t;
  RunOptions o = frames(4);
  o.fps = 50;
  run_sketch(t, o);
  EXPECT_EQ(t.draws[3].millis, 60);  // --fps 50 holds
}

TEST(Sketch, SecondsGiveRoundSecondsTimesFpsFrames) {
  Recorder s;
  s.fps = 30;
  RunOptions o;
  o.seconds = 0.5;
  EXPECT_EQ(run_sketch(s, o).frames, 15);
}

TEST(Sketch, ScriptedMouseEventsReachCallbacksAndVariablesOnTheirFrame) {
  Recorder s;
  run_sketch(s, frames(5,
                       "2 mouse_move 10 20\n"
                       "3 mouse_press left\n"
                       "3 mouse_move 30 40\n"
                       "4 mouse_release left\n"
                       "5 mouse_move 5 6\n"
                       "5 mouse_wheel 2\n"));
  // Events of frame N come before its draw(): frame_count is still N - 1. In a callback pmouse is the previous
  // event's position (Processing's emouseX).
  const std::vector<std::string> expected = {"moved@1 10,20 p0,0",     "pressed@2 10,20 p10,20",
                                             "dragged@2 30,40 p10,20", "released@3 30,40 p10,20",
                                             "moved@4 5,6 p30,40",     "wheel2@4 5,6 p30,40"};
  EXPECT_EQ(s.log, expected);
  ASSERT_EQ(s.draws.size(), 5u);
  // In draw() pmouse is the position at the previous frame's draw (Processing's dmouseX).
  EXPECT_EQ(s.draws[0].mouse_x, 0);
  EXPECT_EQ(s.draws[1].mouse_x, 10);
  EXPECT_EQ(s.draws[1].pmouse_x, 0);
  EXPECT_EQ(s.draws[2].mouse_x, 30);
  EXPECT_EQ(s.draws[2].mouse_y, 40);
  EXPECT_EQ(s.draws[2].pmouse_x, 10);
  EXPECT_EQ(s.draws[2].pmouse_y, 20);
  EXPECT_FALSE(s.draws[1].pressed);
  EXPECT_TRUE(s.draws[2].pressed);
  EXPECT_EQ(s.draws[2].button, MouseButton::left);
  EXPECT_FALSE(s.draws[3].pressed);
  EXPECT_EQ(s.draws[4].pmouse_x, 30);
}

TEST(Sketch, ScriptedKeysReachCallbacksAndVariablesOnTheirFrame) {
  Recorder s;
  run_sketch(s, frames(5, "2 key_press a\n3 key_release a\n4 key_press up\n"));
  const std::vector<std::string> expected = {"key_pressed a@1 0,0 p0,0", "key_released a@2 0,0 p0,0",
                                             std::string("key_pressed ") + char(Key::coded) + "@3 0,0 p0,0"};
  EXPECT_EQ(s.log, expected);
  EXPECT_FALSE(s.draws[0].key_pressed);
  EXPECT_TRUE(s.draws[1].key_pressed);
  EXPECT_EQ(s.draws[1].key, 'a');
  EXPECT_EQ(s.draws[1].key_code, 'A');
  EXPECT_FALSE(s.draws[2].key_pressed);
  EXPECT_TRUE(s.draws[3].key_pressed);
  EXPECT_EQ(s.draws[3].key, Key::coded);
  EXPECT_EQ(s.draws[3].key_code, Key::up);
}

TEST(Sketch, FocusLossForgetsHeldKeysAndButtons) {
  Recorder s;
  run_sketch(s, frames(3, "2 key_press a\n2 mouse_press left\n3 focus_lost\n3 window_resize 640 480\n"));
  EXPECT_TRUE(s.draws[1].key_pressed);
  EXPECT_TRUE(s.draws[1].pressed);
  EXPECT_FALSE(s.draws[2].key_pressed);
  EXPECT_FALSE(s.draws[2].pressed);
  EXPECT_FALSE(s.focused);
  EXPECT_EQ(s.log.back(), "resized 640@2 0,0 p0,0");
  EXPECT_EQ(s.width, 40);  // the sketch keeps its size
}

/// no_loop() in setup(): draw() runs once, then once per redraw() (asked for by a key).
struct Still : Recorder {
  void setup() override {
    Recorder::setup();
    no_loop();
  }
  void key_pressed() override { redraw(); }
};

TEST(Sketch, NoLoopDrawsOnceThenOncePerRedraw) {
  Still s;
  const RunResult r = run_sketch(s, frames(10, "4 key_press r\n6 key_press r\n"));
  ASSERT_EQ(s.draws.size(), 3u);
  EXPECT_EQ(s.draws[0].frame, 1);
  EXPECT_EQ(s.draws[1].frame, 2);  // frame_count counts draws
  EXPECT_EQ(s.draws[2].frame, 3);
  EXPECT_EQ(s.draws[1].millis, 1000 * 3 / 60);  // drawn at the run's frame 4
  // Headless, the run ends after frame 6: the sketch no longer loops and no scripted event is left.
  EXPECT_EQ(r.frames, 6);
  EXPECT_EQ(r.draws, 3);
}

/// loop() again after no_loop(): every frame draws.
struct Pausing : Recorder {
  void key_pressed() override { key == 'p' ? no_loop() : loop(); }
};

TEST(Sketch, LoopResumesDrawing) {
  Pausing s;
  run_sketch(s, frames(8, "3 key_press p\n6 key_press g\n"));
  // Frames 1 and 2 draw; 3, 4, 5 do not; 6, 7, 8 do.
  EXPECT_EQ(s.draws.size(), 5u);
  EXPECT_EQ(s.draws.back().millis, 1000 * 7 / 60);
}

struct Exits : Recorder {
  void draw() override {
    Recorder::draw();
    if (frame_count == 3) exit();
  }
};

TEST(Sketch, ExitEndsTheRunAfterTheFrame) {
  Exits s;
  EXPECT_EQ(run_sketch(s, frames(10)).frames, 3);
}

struct Randoms : Sketch {
  std::vector<double> values;
  void setup() override {
    for (int i = 0; i < 4; ++i) values.push_back(random(10, 20));
  }
};

TEST(Sketch, RandomFollowsTheSeed) {
  Randoms a, b, c;
  RunOptions o = frames(1);
  o.seed = 7;
  run_sketch(a, o);
  run_sketch(b, o);
  o.seed = 8;
  run_sketch(c, o);
  EXPECT_EQ(a.values, b.values);
  EXPECT_NE(a.values, c.values);
  for (double v : a.values) {
    EXPECT_GE(v, 10);
    EXPECT_LT(v, 20);
  }
}

/// Paints the frame number's gray and saves frame 3.
struct Saver : Sketch {
  std::filesystem::path pattern;
  void setup() override { size(8, 6); }
  void draw() override {
    background(gray255(frame_count * 40));
    if (frame_count == 3) save_frame(pattern.string());
  }
};

TEST(Sketch, SaveFrameNumbersTheFileAndWritesThePicture) {
  const auto dir = std::filesystem::path(testing::TempDir()) / "sketch_save_frame";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  Saver s;
  s.pattern = dir / "frame-####.png";
  run_sketch(s, frames(4));
  const ImageRGBA8 saved = to_rgba8(read_image(dir / "frame-0003.png"));
  ASSERT_EQ(saved.width(), 8);
  EXPECT_EQ(saved(0, 0), glm::u8vec4(120, 120, 120, 255));
  EXPECT_FALSE(std::filesystem::exists(dir / "frame-0004.png"));
}

TEST(Sketch, SizeOverrideAndErrors) {
  Recorder s;
  RunOptions o = frames(1);
  o.size = std::pair{64, 48};
  const RunResult r = run_sketch(s, o);
  EXPECT_EQ(r.width, 64);
  EXPECT_EQ(s.width, 64);
  EXPECT_EQ(s.height, 48);
  EXPECT_THROW(s.context(), InvalidInput);  // a 2D sketch has no 3D context
  Recorder fresh;
  EXPECT_THROW(fresh.size(0, 10), InvalidInput);
  EXPECT_THROW(fresh.size(10, 16385), InvalidInput);
  EXPECT_THROW(fresh.frame_rate(0), InvalidInput);
}

/// 3D: each frame clears to a color of its own; the frame shown is the one just drawn (the swap presents it).
struct Buffers3d : Sketch {
  void setup() override { size(16, 12, Renderer::p3d); }
  void draw() override { gt::gtClear(float(frame_count) / 8, 0, 0); }
};

TEST(Sketch, ThreeDimensionalFramesAreDoubleBuffered) {
  Buffers3d s;
  std::vector<int> reds;
  run_sketch(s, frames(3), [&](int, const ImageRGBA8& picture) { reds.push_back(picture(5, 5).x); });
  // 1/8, 2/8, 3/8 in 8 bits (round(255 v): 31.875, 63.75, 95.625).
  EXPECT_EQ(reds, (std::vector<int>{32, 64, 96}));
  EXPECT_THROW(s.canvas(), InvalidInput);
  EXPECT_EQ(&gt::gtCurrent(), &s.context());
}

/// Processing's noise() (seeded by --seed, reseeded by noise_seed), color_mode(HSB) and text() through the canvas.
struct NoiseAndText : Sketch {
  float seeded = 0, reseeded = 0;
  void setup() override {
    size(60, 20);
    seeded = noise(0.5, 1.5, 2.5);
    noise_seed(9);
    reseeded = noise(3.25);
  }
  void draw() override {
    color_mode(ColorMode::hsb, 360, 100, 100);
    background(120, 100, 100);  // hue 120: pure green
    fill(0, 100, 100);          // hue 0: pure red
    text("Hi", 2, 12);
  }
};

TEST(Sketch, NoiseColorModeAndTextReachTheLibrary) {
  NoiseAndText s;
  RunOptions o = frames(1);
  o.seed = 3;
  ImageRGBA8 picture;
  run_sketch(s, o, [&](int, const ImageRGBA8& p) { picture = p; });
  EXPECT_EQ(s.seeded, ProcessingNoise(3).noise(0.5f, 1.5f, 2.5f));
  EXPECT_EQ(s.reseeded, ProcessingNoise(9).noise(3.25f));
  EXPECT_EQ(picture(59, 19), glm::u8vec4(0, 255, 0, 255));
  int red = 0;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 60; ++x) red += picture(x, y) == glm::u8vec4(255, 0, 0, 255);
  EXPECT_GT(red, 10);  // the letters' pixels
}

/// A 3D sketch of a size the budget refuses: the 13 bytes a pixel of its framebuffer, checked before allocating.
struct Huge3d : Sketch {
  void setup() override { size(1000, 1000, Renderer::p3d); }
};

TEST(Sketch, ThreeDimensionalSizesOverTheMemoryBudgetAreRefused) {
  MemoryBudget::set_limit(13'000'000 - 1);
  Huge3d s;
  EXPECT_THROW(run_sketch(s, frames(1)), MemoryBudgetError);
  MemoryBudget::set_limit(13'000'000);
  EXPECT_NO_THROW(run_sketch(s, frames(1)));
  MemoryBudget::set_limit(0);
}

TEST(Sketch, OptionsAreChecked) {
  Recorder s;
  RunOptions o;
  o.frames = 0;
  EXPECT_THROW(run_sketch(s, o), InvalidInput);
  o.frames = 2;
  o.seconds = 1;
  EXPECT_THROW(run_sketch(s, o), InvalidInput);
  o = {};
  o.fps = 0;
  EXPECT_THROW(run_sketch(s, o), InvalidInput);
}

}  // namespace
}  // namespace tessera
