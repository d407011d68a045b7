#include "tessera/image/animation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "run_command.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/image/metrics.hpp"
#include "tessera_test/scratch_dir.hpp"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class Animation : public testing::ScratchDirTest {
 protected:
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

using image_test::run;

// The system Python (version-manager shims start slowly), with PIL.
std::string python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }
bool have_pil() { return run(python() + " -c 'import PIL'").has_value(); }
bool have(const std::string& program) { return run("command -v " + program).has_value(); }

// What PIL and the block walk of gif_reference.py read from a GIF: "key" -> numbers, and the decoded frames.
struct GifReference {
  std::map<std::string, std::vector<std::string>> lines;
  std::vector<ImageRGBA> frames;
  std::vector<long> numbers(const std::string& key) const {
    std::vector<long> out;
    for (const std::string& v : lines.at(key)) out.push_back(std::stol(v));
    return out;
  }
};

std::optional<GifReference> read_with_pil(const fs::path& gif, const fs::path& outdir) {
  fs::create_directories(outdir);
  const auto out = run(python() + " " + TESSERA_SOURCE_DIR + "/libs/image/tests/gif_reference.py " + gif.string() +
                       " " + outdir.string());
  if (!out) return std::nullopt;
  GifReference ref;
  std::istringstream lines(*out);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string key, word;
    words >> key;
    while (words >> word) ref.lines[key].push_back(word);
  }
  for (long i = 0; i < ref.numbers("frames")[0]; ++i)
    ref.frames.push_back(read_image(outdir / fmt::format("frame-{}.ppm", i)));
  return ref;
}

// Frame t of moving squares: a red square moving right and a blue one moving down on a dark background; colors
// are k/255, so 8-bit conversion is exact, and each frame has 3 or 4 colors.
ImageRGB squares(int t, int w = 64, int h = 48) {
  ImageRGB image(w, h, glm::vec3(20, 40, 60) / 255.f);
  for (int y = 10; y < 22; ++y)
    for (int x = 4 * t; x < 4 * t + 12 && x < w; ++x) image(x, y) = glm::vec3(230, 30, 30) / 255.f;
  for (int y = 3 * t; y < 3 * t + 10 && y < h; ++y)
    for (int x = 40; x < 50; ++x) image(x, y) = glm::vec3(40, 60, 250) / 255.f;
  return image;
}

// A smooth gradient (thousands of colors) shifting with t.
ImageRGB gradient(int t, int w = 160, int h = 90) {
  ImageRGB image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float u = float(x) / float(w - 1), v = float(y) / float(h - 1);
      image(x, y) = glm::vec3(u, v, 0.5f + 0.5f * std::sin(6.2832f * (u + v + 0.1f * float(t))) * 0.8f);
    }
  return image;
}

// The mean of each pixel's 5 x 5 neighbourhood (clipped at the borders): what the eye averages dithering to.
ImageRGB box_blur(const ImageRGB& image) {
  ImageRGB out(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      glm::vec3 sum(0);
      int n = 0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          if (image.contains(x + dx, y + dy)) sum += image(x + dx, y + dy), ++n;
      out(x, y) = sum / float(n);
    }
  return out;
}

// Mean and max of |a - b| over RGB channels, in 8-bit levels.
std::pair<double, double> level_error(const ImageRGB& source, const ImageRGB& decoded) {
  double sum = 0, worst = 0;
  for (size_t i = 0; i < source.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = 255.0 * std::abs(double(source.pixels()[i][c]) - double(decoded.pixels()[i][c]));
      sum += d;
      worst = std::max(worst, d);
    }
  return {sum / (3.0 * double(source.pixels().size())), worst};
}

TEST(AnimationNames, NumberedFramePath) {
  EXPECT_EQ(numbered_frame_path("frames/frame-####.png", 7), fs::path("frames/frame-0007.png"));
  EXPECT_EQ(numbered_frame_path("frame-##.png", 0), fs::path("frame-00.png"));
  EXPECT_EQ(numbered_frame_path("f#.png", 12345), fs::path("f12345.png"));  // wider numbers are written whole
  EXPECT_EQ(numbered_frame_path("still.png", 3), fs::path("still.png"));
  EXPECT_EQ(numbered_frame_path("dir#1/####-x.jpg", 42), fs::path("dir#1/0042-x.jpg"));  // only the file name
  EXPECT_THROW(numbered_frame_path("a-##-##.png", 1), InvalidInput);
  EXPECT_THROW(numbered_frame_path("a-##.png", -1), InvalidInput);
}

TEST_F(Animation, FormatFromThePath) {
  EXPECT_EQ(animation_format("a.gif"), AnimationFormat::gif);
  EXPECT_EQ(animation_format("A.GIF"), AnimationFormat::gif);
  for (const char* name : {"a.mp4", "a.webm", "a.mkv", "b.MOV"})
    EXPECT_EQ(animation_format(name), AnimationFormat::video);
  EXPECT_EQ(animation_format("out/f-###.png"), AnimationFormat::sequence);
  EXPECT_EQ(animation_format("out/"), AnimationFormat::sequence);
  EXPECT_EQ(animation_format(dir_), AnimationFormat::sequence);
  try {
    animation_format(path("a.avi"));
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr(".gif"));
    EXPECT_THAT(e.what(), HasSubstr("a.avi"));
  }
}

TEST(AnimationDelays, CarryTheRoundingSoTheAverageRateIsExact) {
  std::vector<int> delays;
  for (int i = 0; i < 6; ++i) delays.push_back(AnimationWriter::gif_delay_cs(30, i));
  EXPECT_EQ(delays, (std::vector<int>{3, 3, 4, 3, 3, 4}));
  for (double fps : {30.0, 24.0, 7.0, 29.97, 50.0, 1.0, 0.5}) {
    long long total = 0;
    const int n = 3000;
    for (int i = 0; i < n; ++i) {
      const int d = AnimationWriter::gif_delay_cs(fps, i);
      EXPECT_GE(d, int(std::floor(100 / fps)));
      EXPECT_LE(d, int(std::ceil(100 / fps)));
      total += d;
    }
    EXPECT_EQ(total, (long long)std::floor(n * 100.0 / fps + 1e-7)) << fps;  // n frames last n / fps seconds
  }
  EXPECT_EQ(AnimationWriter::gif_delay_cs(50, 17), 2);
}

TEST_F(Animation, GifOfFlatFramesIsExactAndSharesOnePalette) {
  if (!have_pil()) GTEST_SKIP() << "python3 with PIL (Debian python3-pil) is not available";
  AnimationWriter writer(path("squares.gif"), AnimationOptions{.fps = 30});
  std::vector<ImageRGB> frames;
  for (int t = 0; t < 12; ++t) {
    frames.push_back(squares(t == 11 ? 10 : t));  // the last frame repeats the one before
    writer.add(frames.back());
  }
  EXPECT_EQ(writer.frames(), 12);
  EXPECT_FALSE(fs::exists(path("squares.gif")));  // only the temporary, until finish()
  writer.finish();
  EXPECT_EQ(files(), std::vector<std::string>{"squares.gif"});

  const auto ref = read_with_pil(path("squares.gif"), path("pil"));
  ASSERT_TRUE(ref);
  EXPECT_EQ(ref->numbers("frames"), std::vector<long>{12});
  EXPECT_EQ(ref->numbers("size"), (std::vector<long>{64, 48}));
  EXPECT_EQ(ref->numbers("loop"), std::vector<long>{0});
  EXPECT_EQ(ref->numbers("durations"), (std::vector<long>{30, 30, 40, 30, 30, 40, 30, 30, 40, 30, 30, 40}));
  const std::vector<long> tables = ref->numbers("tables");
  ASSERT_EQ(tables.size(), 13u);
  EXPECT_LE(tables[0], 256);
  for (size_t i = 1; i < tables.size(); ++i) EXPECT_EQ(tables[i], 0) << "frame " << i - 1 << " has a local table";
  for (size_t i = 0; i < frames.size(); ++i)
    EXPECT_EQ(count_differing_pixels(to_rgba8(ref->frames[i]), to_rgba8(frames[i])), 0) << "frame " << i;
  // Each later frame stores only the bounding box of what changed (a 1x1 rectangle when nothing did).
  const std::vector<long> rects = ref->numbers("rects");
  ASSERT_EQ(rects.size(), 4 * frames.size());
  EXPECT_EQ(std::vector<long>(rects.begin(), rects.begin() + 4), (std::vector<long>{0, 0, 64, 48}));
  for (size_t i = 1; i < frames.size(); ++i) {
    long x0 = 64, y0 = 48, x1 = -1, y1 = -1;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x)
        if (frames[i](x, y) != frames[i - 1](x, y))
          x0 = std::min<long>(x0, x), y0 = std::min<long>(y0, y), x1 = std::max<long>(x1, x), y1 = y;
    const std::vector<long> expected =
        x1 < 0 ? std::vector<long>{0, 0, 1, 1} : std::vector<long>{x0, y0, x1 - x0 + 1, y1 - y0 + 1};
    EXPECT_EQ(std::vector<long>(rects.begin() + ptrdiff_t(4 * i), rects.begin() + ptrdiff_t(4 * i + 4)), expected)
        << "frame " << i;
  }
}

TEST_F(Animation, GifOfAGradientIsCloseWithAndWithoutDithering) {
  if (!have_pil()) GTEST_SKIP() << "python3 with PIL (Debian python3-pil) is not available";
  double local_error[2] = {};  // mean error after a 5 x 5 box blur, without and with dithering
  for (bool dither : {false, true}) {
    const fs::path gif = path(dither ? "dithered.gif" : "plain.gif");
    AnimationWriter writer(gif, AnimationOptions{.fps = 24, .dither = dither});
    for (int t = 0; t < 4; ++t) writer.add(gradient(t));
    writer.finish();
    const auto ref = read_with_pil(gif, path(dither ? "pil-d" : "pil-p"));
    ASSERT_TRUE(ref);
    EXPECT_EQ(ref->numbers("durations"), (std::vector<long>{40, 40, 40, 40}));
    // Thousands of colors: every frame gets its own palette, of at most 256 colors.
    EXPECT_EQ(ref->numbers("tables"), (std::vector<long>{256, 0, 256, 256, 256}));
    for (long colors : ref->numbers("colors")) EXPECT_LE(colors, 256);
    for (int t = 0; t < 4; ++t) {
      const ImageRGB source = gradient(t);
      const auto [mean, worst] = level_error(source, to_rgb(ref->frames[size_t(t)]));
      // 256 colors for a sheet of ~14000 spread over the cube leave about 5 levels per channel (PIL's own median
      // cut: 5.2 on this frame); dithering spends a larger error per pixel (damped: undamped specks reach 155
      // levels) on the right local average.
      EXPECT_LT(mean, dither ? 7.5 : 6.0) << "frame " << t;
      EXPECT_LE(worst, dither ? 64.0 : 40.0) << "frame " << t;
      local_error[dither] += level_error(box_blur(source), box_blur(to_rgb(ref->frames[size_t(t)]))).first / 4;
    }
  }
  EXPECT_LT(local_error[1], 0.7 * local_error[0]) << "plain " << local_error[0] << ", dithered " << local_error[1];
}

TEST_F(Animation, GifPaletteModes) {
  if (!have_pil()) GTEST_SKIP() << "python3 with PIL (Debian python3-pil) is not available";
  for (GifPalette mode : {GifPalette::per_frame, GifPalette::shared}) {
    const fs::path gif = path(mode == GifPalette::shared ? "shared.gif" : "per_frame.gif");
    AnimationWriter writer(gif, AnimationOptions{.palette = mode});
    for (int t = 0; t < 3; ++t) writer.add(squares(t));
    writer.finish();
    const auto ref = read_with_pil(gif, path(gif.stem().string()));
    ASSERT_TRUE(ref);
    const std::vector<long> tables = ref->numbers("tables");
    ASSERT_EQ(tables.size(), 4u);
    EXPECT_EQ(tables[1], 0);  // the first frame uses the global table
    for (size_t i = 2; i < 4; ++i) EXPECT_EQ(tables[i] > 0, mode == GifPalette::per_frame);
    for (int t = 0; t < 3; ++t)
      EXPECT_EQ(count_differing_pixels(to_rgba8(ref->frames[size_t(t)]), to_rgba8(squares(t))), 0);
  }
}

TEST_F(Animation, GifLoopCount) {
  if (!have_pil()) GTEST_SKIP() << "python3 with PIL (Debian python3-pil) is not available";
  for (int loop : {3, -1}) {
    const fs::path gif = path(fmt::format("loop{}.gif", loop));
    AnimationWriter writer(gif, AnimationOptions{.fps = 10, .loop = loop});
    writer.add(squares(0));
    writer.add(squares(1));
    writer.finish();
    const auto ref = read_with_pil(gif, path(fmt::format("pil{}", loop)));
    ASSERT_TRUE(ref);
    EXPECT_EQ(ref->lines.at("loop"), std::vector<std::string>{loop < 0 ? "none" : "3"});
    EXPECT_EQ(ref->numbers("durations"), (std::vector<long>{100, 100}));
  }
}

TEST_F(Animation, SrgbEncodesAsWriteImageDoes) {
  if (!have_pil()) GTEST_SKIP() << "python3 with PIL (Debian python3-pil) is not available";
  ImageRGB frame(8, 8, glm::vec3(0.5f, 0.2f, 0.0f));
  AnimationWriter writer(path("s.gif"), AnimationOptions{.srgb = true});
  writer.add(frame);
  writer.finish();
  const auto ref = read_with_pil(path("s.gif"), path("pil"));
  ASSERT_TRUE(ref);
  // IEC 61966-2-1: linear 0.5 -> 188, 0.2 -> 124 (docs/image.md).
  EXPECT_EQ(to_rgba8(ref->frames[0])(3, 3), glm::u8vec4(188, 124, 0, 255));
}

TEST_F(Animation, EightBitFramesAreWrittenAsTheyAre) {
  if (!have_pil()) GTEST_SKIP() << "python3 with PIL (Debian python3-pil) is not available";
  AnimationWriter writer(path("e.gif"), AnimationOptions{.srgb = true});  // srgb applies to float frames only
  const ImageRGBA8 frame = to_rgba8(squares(2));
  writer.add(frame);
  writer.add(squares(3));  // float and 8-bit frames mix
  writer.finish();
  const auto ref = read_with_pil(path("e.gif"), path("pil"));
  ASSERT_TRUE(ref);
  EXPECT_EQ(count_differing_pixels(to_rgba8(ref->frames[0]), frame), 0);
  EXPECT_EQ(count_differing_pixels(to_rgba8(ref->frames[1]), to_rgba8(squares(3), true)), 0);

  AnimationWriter sequence(path("seq/f-#.png"));
  sequence.add(frame);
  sequence.finish();
  EXPECT_EQ(count_differing_pixels(to_rgba8(read_image(path("seq/f-0.png"))), frame), 0);
}

TEST_F(Animation, AbandonedGifLeavesNoFile) {
  try {
    AnimationWriter writer(path("a.gif"));
    writer.add(squares(0));
    writer.add(squares(1));
    throw std::runtime_error("the sketch failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(files().empty());
}

TEST_F(Animation, FrameBuffersOverTheMemoryBudgetAreRefused) {
  struct Restore {
    ~Restore() { MemoryBudget::set_limit(0); }
  } restore;
  // GIF: the 8-bit RGBA copy, packed RGB, the indices, the previous frame and the changed rectangle, 14 bytes a
  // pixel: 64 x 48 x 14 = 43008 bytes.
  MemoryBudget::set_limit(43007);
  {
    AnimationWriter writer(path("a.gif"));
    try {
      writer.add(squares(0));
      FAIL() << "no throw";
    } catch (const MemoryBudgetError& e) {
      EXPECT_THAT(e.what(), HasSubstr("64x48"));
    }
  }
  EXPECT_TRUE(files().empty());
  MemoryBudget::set_limit(43008);
  AnimationWriter writer(path("a.gif"));
  writer.add(squares(0));
  writer.finish();
  EXPECT_EQ(files(), std::vector<std::string>{"a.gif"});
}

TEST_F(Animation, MisuseIsInvalidInput) {
  AnimationWriter writer(path("a.gif"));
  EXPECT_THROW(writer.finish(), InvalidInput);  // no frames
  EXPECT_THROW(writer.add(ImageRGB()), InvalidInput);
  writer.add(squares(0));
  try {
    writer.add(squares(0, 65, 48));
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr("65x48"));
    EXPECT_THAT(e.what(), HasSubstr("64x48"));
  }
  writer.add(squares(1));
  writer.finish();
  EXPECT_THROW(writer.add(squares(2)), InvalidInput);
  EXPECT_THROW(writer.finish(), InvalidInput);
  EXPECT_EQ(files(), std::vector<std::string>{"a.gif"});

  EXPECT_THROW(AnimationWriter(path("b.gif"), AnimationOptions{.fps = 60}), InvalidInput);
  EXPECT_THROW(AnimationWriter(path("b.gif"), AnimationOptions{.fps = 0}), InvalidInput);
  EXPECT_THROW(AnimationWriter(path("b.gif"), AnimationOptions{.fps = 0.001}), InvalidInput);  // 1000 s a frame
  EXPECT_THROW(AnimationWriter(path("b.gif"), AnimationOptions{.fps = NAN}), InvalidInput);
  EXPECT_THROW(AnimationWriter(path("b.gif"), AnimationOptions{.loop = -2}), InvalidInput);
  EXPECT_THROW(AnimationWriter(path("b.avi")), InvalidInput);
  EXPECT_THROW(AnimationWriter(path("missing/b.gif")), IoError);
  EXPECT_EQ(files(), std::vector<std::string>{"a.gif"});
}

TEST_F(Animation, NumberedSequence) {
  AnimationWriter writer(path("seq/frame-###.png"));
  for (int t = 0; t < 3; ++t) writer.add(squares(t));
  writer.finish();
  EXPECT_EQ(writer.frame_path(2), path("seq/frame-002.png"));
  for (int t = 0; t < 3; ++t)
    EXPECT_EQ(max_abs_difference(read_image(path(fmt::format("seq/frame-{:03}.png", t))), to_rgba(squares(t))), 0.0);
  EXPECT_EQ(std::distance(fs::directory_iterator(path("seq")), fs::directory_iterator()), 3);

  // A folder: frame-0000.png, ...; RGBA frames keep their alpha.
  AnimationWriter folder(path("out").string() + "/");
  ImageRGBA rgba(5, 4, glm::vec4(1, 0, 0, 128 / 255.f));
  folder.add(rgba);
  folder.add(rgba);
  folder.finish();
  EXPECT_EQ(to_rgba8(read_image(path("out/frame-0001.png")))(2, 2), glm::u8vec4(255, 0, 0, 128));
  EXPECT_TRUE(fs::exists(path("out/frame-0000.png")));
}

// Sets PATH for the scope of a test.
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& value) : saved_(std::getenv("PATH") ? std::getenv("PATH") : "") {
    ::setenv("PATH", value.c_str(), 1);
  }
  ~ScopedPath() { ::setenv("PATH", saved_.c_str(), 1); }

 private:
  std::string saved_;
};

TEST_F(Animation, VideoWithoutFfmpegSaysSo) {
  fs::create_directories(path("empty-bin"));
  ScopedPath no_ffmpeg(path("empty-bin").string());
  try {
    AnimationWriter writer(path("a.mp4"));
    FAIL() << "no throw";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ffmpeg"));
    EXPECT_THAT(e.what(), HasSubstr("a.mp4"));
  }
  EXPECT_EQ(files(), std::vector<std::string>{"empty-bin"});
}

// A fake ffmpeg on PATH: a shell script with the given body.
void fake_ffmpeg(const fs::path& folder, const std::string& body) {
  fs::create_directories(folder);
  write_file_atomic(folder / "ffmpeg", "#!/bin/sh\n" + body + "\n");
  ::chmod((folder / "ffmpeg").c_str(), 0755);
}

TEST_F(Animation, FailingFfmpegIsAnIoErrorWithItsMessage) {
  fake_ffmpeg(path("bin"), "cat > /dev/null; echo 'Unknown encoder: fake failure' >&2; exit 1");
  ScopedPath fake(path("bin").string() + ":/usr/bin:/bin");
  try {
    AnimationWriter writer(path("a.mp4"));
    writer.add(squares(0));
    writer.finish();
    FAIL() << "no throw";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ffmpeg failed with exit status 1"));
    EXPECT_THAT(e.what(), HasSubstr("Unknown encoder: fake failure"));
  }
  EXPECT_EQ(files(), std::vector<std::string>{"bin"});

  // An ffmpeg that exits without reading: the frames meet a closed pipe (EPIPE, not a SIGPIPE that would end this
  // test program).
  fake_ffmpeg(path("bin2"), "echo 'gone' >&2; exit 3");
  ScopedPath gone(path("bin2").string() + ":/usr/bin:/bin");
  try {
    AnimationWriter writer(path("b.mp4"));
    for (int t = 0; t < 20; ++t) writer.add(gradient(t, 400, 300));
    writer.finish();
    FAIL() << "no throw";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("exit status 3"));
    EXPECT_THAT(e.what(), HasSubstr("gone"));
  }
  EXPECT_EQ(files(), (std::vector<std::string>{"bin", "bin2"}));
}

// ffprobe's answer for the first video stream: "width,height,r_frame_rate,nb_read_frames".
std::optional<std::string> probe(const fs::path& video) {
  return run(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=width,height,r_frame_rate,nb_read_frames,codec_name,pix_fmt -of csv=p=0 " +
      video.string());
}

TEST_F(Animation, VideoThroughFfmpeg) {
  if (!have("ffmpeg") || !have("ffprobe")) GTEST_SKIP() << "ffmpeg/ffprobe are not installed (Debian ffmpeg)";
  for (const char* name : {"a.mp4", "a.webm"}) {
    AnimationWriter writer(path(name), AnimationOptions{.fps = 25});
    // Odd size: H.264 and VP9 in yuv420p get a repeated last column and row.
    for (int t = 0; t < 20; ++t) writer.add(squares(t % 10, 65, 49));
    writer.finish();
    const auto info = probe(path(name));
    ASSERT_TRUE(info) << name;
    EXPECT_EQ(*info, std::string(name) == "a.mp4" ? "h264,66,50,yuv420p,25/1,20\n" : "vp9,66,50,yuv420p,25/1,20\n");
  }
  // A flat color survives the encoder within a few levels (ffmpeg decodes the first frame to PPM).
  AnimationWriter writer(path("flat.mp4"), AnimationOptions{.fps = 30});
  for (int t = 0; t < 3; ++t) writer.add(ImageRGB(32, 32, glm::vec3(200, 100, 50) / 255.f));
  writer.finish();
  ASSERT_TRUE(run("ffmpeg -v error -i " + path("flat.mp4").string() + " -frames:v 1 -y " + path("flat.ppm").string()));
  const glm::u8vec4 p = to_rgba8(read_image(path("flat.ppm")))(16, 16);
  EXPECT_NEAR(p.x, 200, 4);
  EXPECT_NEAR(p.y, 100, 4);
  EXPECT_NEAR(p.z, 50, 4);
}

TEST_F(Animation, AbandonedVideoLeavesNoFile) {
  if (!have("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed (Debian ffmpeg)";
  try {
    AnimationWriter writer(path("a.mp4"));
    for (int t = 0; t < 5; ++t) writer.add(squares(t));
    throw std::runtime_error("the sketch failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(files().empty());
}

}  // namespace
}  // namespace tessera
