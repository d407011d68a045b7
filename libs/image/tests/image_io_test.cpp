#include "tessera/image/image_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <sstream>

#include "run_command.hpp"
#include "tessera/color/srgb.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/metrics.hpp"
#include "tessera_test/scratch_dir.hpp"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

class ImageIo : public testing::ScratchDirTest {
 protected:
  void write_bytes(const std::string& name, const std::string& bytes) const { write_file_atomic(path(name), bytes); }
};

ImageRGBA8 random_rgba8(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  ImageRGBA8 image(width, height);
  for (glm::u8vec4& p : image.pixels()) p = glm::u8vec4(rng() & 255, rng() & 255, rng() & 255, rng() & 255);
  return image;
}

ImageRGB random_rgb(int width, int height, unsigned seed, float lo, float hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(lo, hi);
  ImageRGB image(width, height);
  for (glm::vec3& p : image.pixels()) p = glm::vec3(value(rng), value(rng), value(rng));
  return image;
}

ImageRGBA8 opaque(ImageRGBA8 image) {
  for (glm::u8vec4& p : image.pixels()) p.w = 255;
  return image;
}

using image_test::run;

// The reference script run by the system Python when there is one (version-manager shims start slowly).
const std::string kPngReference = (fs::exists("/usr/bin/python3") ? "/usr/bin/python3 " : "python3 ") +
                                  std::string(TESSERA_SOURCE_DIR) + "/libs/image/tests/png_reference.py";

uint32_t bits_of(float v) {
  uint32_t b;
  std::memcpy(&b, &v, 4);
  return b;
}

TEST_F(ImageIo, PngRoundTripIsExact) {
  const ImageRGBA8 image = random_rgba8(13, 7, 1);
  write_image(path("a.png"), image);
  EXPECT_EQ(count_differing_pixels(to_rgba8(read_image(path("a.png"))), image), 0);
  // Float RGB through PNG: values k/255 survive exactly, alpha reads 1.
  const ImageRGBA reference = to_float(opaque(image));
  write_image(path("b.png"), to_rgb(reference));
  EXPECT_EQ(max_abs_difference(read_image(path("b.png")), reference), 0.0);
}

TEST_F(ImageIo, PngMatchesAnIndependentDecoder) {
  const ImageRGBA8 image = random_rgba8(17, 9, 2);
  write_image(path("a.png"), image);
  const auto out = run(kPngReference + " decode " + path("a.png").string());
  if (!out) GTEST_SKIP() << "python3 is not available";
  std::istringstream in(*out);
  int w = 0, h = 0, c = 0;
  in >> w >> h >> c;
  ASSERT_EQ(w, 17);
  ASSERT_EQ(h, 9);
  ASSERT_EQ(c, 4);
  for (const glm::u8vec4& p : image.pixels())
    for (int k = 0; k < 4; ++k) {
      int v = -1;
      in >> v;
      ASSERT_EQ(v, p[k]);
    }
}

// Baseline, progressive, gray, unsubsampled and Adobe CMYK JPEGs from PIL decode to PIL's own RGB, sample for sample.
TEST_F(ImageIo, JpegsDecodeAsPilDecodesThem) {
  const auto out = run((fs::exists("/usr/bin/python3") ? "/usr/bin/python3 " : "python3 ") +
                       std::string(TESSERA_SOURCE_DIR) + "/libs/image/tests/jpeg_reference.py " + path("").string());
  if (!out) GTEST_SKIP() << "python3 with PIL is not available";
  std::istringstream in(*out);
  std::string kind;
  int count = 0;
  for (int w = 0, h = 0; in >> kind >> w >> h; ++count) {
    SCOPED_TRACE(kind);
    const FileImage native = read_image_native(path(kind + ".jpg"));
    const auto* image = std::get_if<ImageRGBA8>(&native);
    ASSERT_NE(image, nullptr);
    ASSERT_EQ(image->width(), w);
    ASSERT_EQ(image->height(), h);
    for (const glm::u8vec4& p : image->pixels()) {
      int r = -1, g = -1, b = -1;
      in >> r >> g >> b;
      ASSERT_EQ(glm::ivec4(p), glm::ivec4(r, g, b, 255));
    }
  }
  EXPECT_EQ(count, 5);
}

// Big enough for several deflate bands (256 KiB each) and for every filter type to win some rows: smooth
// gradients (Sub, Up, Average, Paeth), flat areas and noise (None).
ImageRGBA8 banded_test_image(int width, int height) {
  ImageRGBA8 image = random_rgba8(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int band = (y / 37) % 4;
      if (band == 0) image(x, y) = glm::u8vec4(x, y, x + y, 255);
      if (band == 1) image(x, y) = glm::u8vec4(90, 20, 200, 255);
      if (band == 2) image(x, y) = glm::u8vec4(x * 3, 255 - y, (x * y) / 7, 128 + (x & 127));
    }
  return image;
}

TEST_F(ImageIo, LargePngsMatchAnIndependentDecoderForAnyThreadCount) {
  const ImageRGBA8 image = banded_test_image(60, 2500);  // 600 KB of RGBA rows: three bands
  std::string first_bytes;
  for (int threads : {1, 2, 3}) {
    ThreadLimit limit(threads);
    write_image(path("rgba.png"), image);
    const std::string bytes = read_file(path("rgba.png"));
    if (first_bytes.empty()) first_bytes = bytes;
    EXPECT_EQ(bytes, first_bytes) << threads << " threads";
  }
  for (const bool alpha : {true, false}) {
    const ImageRGBA8 expected = alpha ? image : opaque(image);
    if (alpha)
      write_image(path("a.png"), image);
    else
      write_image(path("a.png"), to_rgb(to_float(image)));  // the RGB (3-channel) path
    const auto out = run(kPngReference + " decode " + path("a.png").string());
    if (!out) GTEST_SKIP() << "python3 is not available";
    std::istringstream in(*out);
    int w = 0, h = 0, c = 0;
    in >> w >> h >> c;
    ASSERT_EQ(w, image.width());
    ASSERT_EQ(h, image.height());
    ASSERT_EQ(c, alpha ? 4 : 3);
    for (const glm::u8vec4& p : expected.pixels())
      for (int k = 0; k < c; ++k) {
        int v = -1;
        in >> v;
        ASSERT_EQ(v, p[k]);
      }
  }
}

TEST_F(ImageIo, ReadsPngsFromAnIndependentEncoder) {
  if (!run(kPngReference + " encode " + path("a.png").string() + " 11 6")) GTEST_SKIP() << "python3 is not available";
  const ImageRGBA8 got = to_rgba8(read_image(path("a.png")));
  ASSERT_EQ(got.width(), 11);
  ASSERT_EQ(got.height(), 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 11; ++x)  // the pattern of png_reference.py
      ASSERT_EQ(got(x, y), glm::u8vec4((7 * x + 3 * y) % 256, (x * y) % 256, 255 - x, 200 + y)) << x << "," << y;
  ASSERT_TRUE(run(kPngReference + " encode16 " + path("g.png").string() + " 9 4"));
  const ImageRGBA gray = read_image(path("g.png"));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 9; ++x) {
      const float v = float((x * 4099 + y * 257) % 65536) / 65535.f;
      ASSERT_EQ(gray(x, y), glm::vec4(v, v, v, 1.f)) << x << "," << y;
    }
}

TEST_F(ImageIo, PpmAndPngAgree) {
  const ImageRGB image = random_rgb(10, 6, 3, -0.2f, 1.2f);
  write_image(path("a.ppm"), image);
  write_image(path("a.png"), image);
  const ImageRGBA ppm = read_image(path("a.ppm")), png = read_image(path("a.png"));
  EXPECT_EQ(max_abs_difference(ppm, png), 0.0);
  EXPECT_EQ(count_differing_pixels(to_rgba8(ppm), to_rgba8(image)), 0);
  // The P6 header is the plain one, and the first bytes are pixel (0, 0) of the top row.
  const std::string bytes = read_file(path("a.ppm"));
  const std::string header = "P6\n10 6\n255\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  const glm::u8vec4 first = to_rgba8(image)(0, 0);
  EXPECT_EQ((unsigned char)bytes[header.size()], first.x);
  EXPECT_EQ(bytes.size(), header.size() + 10 * 6 * 3);
}

TEST_F(ImageIo, ReadsPlainGrayAndSixteenBitNetpbm) {
  write_bytes("p3.ppm", "P3\n# a comment\n2 1 # trailing comment\n10\n10 0 5\n0 10 1\n");
  const ImageRGBA p3 = read_image(path("p3.ppm"));
  ASSERT_EQ(p3.width(), 2);
  EXPECT_EQ(p3(0, 0), glm::vec4(1.f, 0.f, 0.5f, 1.f));
  EXPECT_EQ(p3(1, 0), glm::vec4(0.f, 1.f, 0.1f, 1.f));
  write_bytes("p5.pgm", std::string("P5 2 2 255\n") + char(0) + char(255) + char(51) + char(102));
  const ImageRGBA p5 = read_image(path("p5.pgm"));
  EXPECT_EQ(p5(1, 0), glm::vec4(1.f, 1.f, 1.f, 1.f));
  EXPECT_EQ(p5(0, 1), glm::vec4(0.2f, 0.2f, 0.2f, 1.f));
  write_bytes("p2.pgm", "P2 1 2 4 1 4");
  EXPECT_EQ(read_image(path("p2.pgm"))(0, 0), glm::vec4(0.25f, 0.25f, 0.25f, 1.f));
  write_bytes("p6.ppm", std::string("P6 1 1 1000\n") + char(0x03) + char(0xe8) + char(0x01) + char(0xf4) + char(0) +
                            char(0));  // big-endian 1000, 500, 0
  EXPECT_EQ(read_image(path("p6.ppm"))(0, 0), glm::vec4(1.f, 0.5f, 0.f, 1.f));
}

TEST_F(ImageIo, PfmRoundTripIsBitExactAndBottomRowFirst) {
  ImageRGB image = random_rgb(5, 3, 4, -1e6f, 1e6f);
  image(0, 0) = glm::vec3(std::numeric_limits<float>::denorm_min(), -0.f, 1e-30f);
  // The extremes of the finite floats (an infinite sample is refused on reading: NonFinitePfmSamplesAreRefused...).
  image(4, 2) = glm::vec3(-std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), 1.f / 3);
  write_image(path("a.pfm"), image);
  const ImageRGBA back = read_image(path("a.pfm"));
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(bits_of(back(x, y)[c]), bits_of(image(x, y)[c])) << x << "," << y;
  const std::string bytes = read_file(path("a.pfm"));
  const std::string header = "PF\n5 3\n-1\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  ASSERT_EQ(bytes.size(), header.size() + 5 * 3 * 3 * 4);
  // The first float stored is the red of the bottom-left pixel, little endian.
  const uint32_t expected = bits_of(image(0, 2).x);
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + header.size());
  EXPECT_EQ(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24, expected);
}

TEST_F(ImageIo, ReadsBigEndianPfm) {
  // Positive scale: big endian. 1 x 2 gray, bottom row (2.0) first then the top row (-0.5).
  write_bytes("be.pfm", std::string("Pf\n1 2\n1.0\n") + std::string("\x40\x00\x00\x00\xbf\x00\x00\x00", 8));
  const DepthImage gray = read_pfm_gray(path("be.pfm"));
  EXPECT_EQ(gray(0, 0), -0.5f);
  EXPECT_EQ(gray(0, 1), 2.f);
  EXPECT_EQ(read_image(path("be.pfm"))(0, 1), glm::vec4(2.f, 2.f, 2.f, 1.f));
}

TEST_F(ImageIo, GrayPfmRoundTrip) {
  DepthImage depth(4, 3);
  for (int i = 0; i < 12; ++i) depth.pixels()[size_t(i)] = 0.1f * float(i) - 0.3f;
  write_pfm(path("d.pfm"), depth);
  EXPECT_EQ(read_file(path("d.pfm")).substr(0, 3), "Pf\n");
  const DepthImage back = read_pfm_gray(path("d.pfm"));
  EXPECT_EQ(max_abs_difference(back, depth), 0.0);
  // A color PFM reads as the mean of its channels.
  ImageRGB rgb(1, 1, glm::vec3(0.f, 0.5f, 1.f));
  write_image(path("c.pfm"), rgb);
  EXPECT_EQ(read_pfm_gray(path("c.pfm"))(0, 0), 0.5f);
  EXPECT_THROW(write_pfm(path("d.png"), depth), InvalidInput);
}

TEST_F(ImageIo, HdrKeepsRgbePrecision) {
  ImageRGB image = random_rgb(9, 5, 5, 0.f, 1.f);
  for (glm::vec3& p : image.pixels()) p = glm::exp2(p * 20.f - 10.f);  // 2^-10 .. 2^10
  write_image(path("a.hdr"), image);
  const ImageRGBA back = read_image(path("a.hdr"));
  ASSERT_EQ(back.width(), 9);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 9; ++x) {
      const glm::vec3 p = image(x, y);
      const float largest = std::max({p.x, p.y, p.z});
      for (int c = 0; c < 3; ++c)  // a shared exponent and 8-bit mantissas: error below largest / 128
        EXPECT_NEAR(back(x, y)[c], p[c], largest / 128.f) << x << "," << y;
      EXPECT_EQ(back(x, y).w, 1.f);
    }
}

TEST_F(ImageIo, JpgIsClose) {
  ImageRGB image(32, 24);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) image(x, y) = glm::vec3(float(x) / 31.f, float(y) / 23.f, 0.5f);
  write_image(path("a.jpg"), image);
  write_image(path("b.JPEG"), image, {.jpeg_quality = 100});
  EXPECT_GT(psnr(to_rgb(read_image(path("a.jpg"))), image), 35.0);
  EXPECT_GT(psnr(to_rgb(read_image(path("b.JPEG"))), image), 40.0);
  EXPECT_THROW(write_image(path("c.jpg"), image, {.jpeg_quality = 0}), InvalidInput);
}

TEST_F(ImageIo, BmpAndTgaRoundTrip) {
  const ImageRGBA8 image = random_rgba8(6, 5, 6);
  write_image(path("a.bmp"), image);
  write_image(path("a.tga"), image);
  EXPECT_EQ(count_differing_pixels(to_rgba8(read_image(path("a.bmp"))), opaque(image)), 0);
  EXPECT_EQ(count_differing_pixels(to_rgba8(read_image(path("a.tga"))), image), 0);  // TGA keeps alpha
}

TEST_F(ImageIo, SrgbOptionEncodesAndNothingDecodesOnRead) {
  const ImageRGB image(1, 1, glm::vec3(0.5f, 0.f, 1.f));
  write_image(path("linear.png"), image);
  write_image(path("srgb.png"), image, {.srgb = true});
  EXPECT_EQ(to_rgba8(read_image(path("linear.png")))(0, 0), glm::u8vec4(128, 0, 255, 255));
  const int encoded = int(std::lround(srgb_encode(0.5f) * 255.f));  // 188
  EXPECT_EQ(to_rgba8(read_image(path("srgb.png")))(0, 0), glm::u8vec4(encoded, 0, 255, 255));
}

TEST_F(ImageIo, SrgbWriteFollowsTheFormula) {
  // IEC 61966-2-1 written out here, in double, independently of tessera/color/srgb.hpp: 12.92 v up to 0.0031308, else
  // 1.055 v^(1/2.4) - 0.055; then 255 x and round half up. 4097 levels through a PNG and back, both branches and the
  // knee; a level whose exact value lies within 1e-3 of a rounding half step may go either way in float.
  const auto formula = [](double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; };
  ImageRGB ramp(4097, 1);
  for (int i = 0; i <= 4096; ++i) ramp(i, 0) = glm::vec3(float(i / 4096.0), float(i / 4096.0 * 0.01), 0.0031308f);
  write_image(path("ramp.png"), ramp, {.srgb = true});
  const ImageRGBA8 back = to_rgba8(read_image(path("ramp.png")));
  int checked = 0;
  for (int i = 0; i <= 4096; ++i)
    for (int c = 0; c < 3; ++c) {
      const double exact = 255 * formula(double(ramp(i, 0)[c]));
      if (std::abs(exact - std::floor(exact) - 0.5) < 1e-3) continue;
      EXPECT_EQ(int(back(i, 0)[c]), int(std::floor(exact + 0.5))) << "level " << i << " channel " << c;
      ++checked;
    }
  EXPECT_GT(checked, 12000);
  // The worked values: middle gray 0.5 -> 188 (0.7354), the knee 0.0031308 -> 10 (0.04045), 0.001 -> 3, 0.2 -> 124.
  EXPECT_EQ(back(2048, 0).x, 188);
  EXPECT_EQ(back(0, 0).z, 10);
  EXPECT_EQ(back(410, 0).y, 3);  // 0.1001 x 0.01 = 0.001001: 12.92 x 0.001001 x 255 = 3.30
  EXPECT_EQ(back(0, 0).x, 0);
  EXPECT_EQ(back(4096, 0).x, 255);
  const ImageRGB fifth(1, 1, glm::vec3(0.2f));
  write_image(path("fifth.png"), fifth, {.srgb = true});
  EXPECT_EQ(to_rgba8(read_image(path("fifth.png")))(0, 0).x, 124);  // 1.055 x 0.2^(1/2.4) - 0.055 = 0.4845
}

TEST(ImageConversions, ClampRoundAndKeepAlphaLinear) {
  ImageRGBA image(4, 1);
  image(0, 0) = glm::vec4(-1.f, 2.f, std::nanf(""), 0.5f);
  image(1, 0) = glm::vec4(0.5f / 255.f - 1e-4f, 0.5f / 255.f + 1e-4f, 1.f, 1.f);
  image(2, 0) = glm::vec4(0.25f, 0.5f, 0.75f, 0.25f);
  image(3, 0) = glm::vec4(0.25f, 0.5f, 0.75f, 0.25f);
  const ImageRGBA8 bytes = to_rgba8(image);
  EXPECT_EQ(bytes(0, 0), glm::u8vec4(0, 255, 0, 128));
  EXPECT_EQ(bytes(1, 0), glm::u8vec4(0, 1, 255, 255));
  EXPECT_EQ(bytes(2, 0), glm::u8vec4(64, 128, 191, 64));
  EXPECT_EQ(to_rgba8(image, true)(3, 0).w, 64);  // alpha is never sRGB-encoded
  EXPECT_EQ(to_rgba8(to_rgb(image))(0, 0).w, 255);
}

TEST(ImageConversions, EightBitSurvivesFloatRoundTrips) {
  ImageRGBA8 all(256, 1);
  for (int v = 0; v < 256; ++v) all(v, 0) = glm::u8vec4(v, 255 - v, v, v);
  EXPECT_EQ(count_differing_pixels(to_rgba8(to_float(all)), all), 0);
  EXPECT_EQ(count_differing_pixels(to_rgba8(to_float(all, true), true), all), 0);
  EXPECT_EQ(to_float(all, true)(255, 0), glm::vec4(1.f, 0.f, 1.f, 1.f));
  EXPECT_EQ(to_rgba(to_rgb(to_float(all)))(7, 0).w, 1.f);
}

// ---- errors ----

TEST_F(ImageIo, MissingFileIsAnIoErrorNamingIt) {
  try {
    read_image(path("missing.png"));
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.png"));
  }
}

TEST_F(ImageIo, UnknownExtensionListsTheSupportedOnes) {
  write_bytes("a.gif", "GIF89a");
  try {
    read_image(path("a.gif"));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("a.gif"), HasSubstr(".png"), HasSubstr(".pfm"), HasSubstr(".hdr")));
  }
  try {
    write_image(path("b.gif"), ImageRGB(1, 1));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("b.gif"), HasSubstr(".jpg"), HasSubstr("writing")));
  }
  EXPECT_FALSE(fs::exists(path("b.gif")));
  EXPECT_THROW(write_image(path("noext"), ImageRGB(1, 1)), InvalidInput);
}

// Expects read_image(name) to throw InvalidInput whose message holds the file name and every `parts`.
void expect_invalid(const fs::path& file, std::initializer_list<const char*> parts) {
  try {
    read_image(file);
    ADD_FAILURE() << "expected InvalidInput for " << file;
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.filename().string()));
    for (const char* part : parts) EXPECT_THAT(e.what(), HasSubstr(part));
  }
}

TEST_F(ImageIo, TruncatedPfmNamesTheByteOffset) {
  write_bytes("t.pfm", "PF\n2 2\n-1\n" + std::string(20, '\0'));  // needs 48 bytes of data
  expect_invalid(path("t.pfm"), {"byte offset 30", "truncated", "48 bytes"});
  write_bytes("h.pfm", "PF\n2 2\n");
  expect_invalid(path("h.pfm"), {"byte offset 7", "scale"});
  write_bytes("z.pfm", "PF\n2 2\n0\n");
  expect_invalid(path("z.pfm"), {"nonzero"});
  write_bytes("m.pfm", "P7\n2 2\n-1\n");
  expect_invalid(path("m.pfm"), {"PF or Pf"});
  write_bytes("w.pfm", "PF\n-2 2\n-1\n");
  expect_invalid(path("w.pfm"), {"width"});
  write_bytes("x.pfm", "PF\n2 two\n-1\n");
  expect_invalid(path("x.pfm"), {"height"});
}

// Issue 24, class 2: NaN and infinite PFM samples were decoded and reached pictures, textures and statistics. They
// are refused with the pixel (top row 0) and the byte offset of the sample: 10 header bytes, then the bottom row.
TEST_F(ImageIo, NonFinitePfmSamplesAreRefusedWithPixelAndOffset) {
  const auto le = [](float v) {
    uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    return std::string{char(bits), char(bits >> 8), char(bits >> 16), char(bits >> 24)};
  };
  const auto message = [](const std::function<void()>& read) {
    try {
      read();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // 2 x 2 RGB: the bottom row's second pixel (1, 1) has a NaN green, the 5th float, at byte 10 + 16 = 26.
  std::string rgb = "PF\n2 2\n-1\n";
  for (int i = 0; i < 12; ++i) rgb += le(i == 4 ? NAN : 0.25f);
  const std::string nan_message = message([&] { decode_image(rgb, "n.pfm"); });
  EXPECT_NE(nan_message.find("byte offset 26: pixel (1, 1) channel g is nan: PFM samples must be finite"),
            std::string::npos)
      << nan_message;
  // 1 x 2 gray, big endian (positive scale): the top row (y = 0) is the second float, byte 11 + 4 = 15.
  const std::string gray = "Pf\n1 2\n1.0\n" + std::string("\x3f\x80\x00\x00\xff\x80\x00\x00", 8);
  write_bytes("g.pfm", gray);
  const std::string inf_message = message([&] { read_pfm_gray(path("g.pfm")); });
  EXPECT_NE(inf_message.find("byte offset 15: pixel (0, 0) is -inf"), std::string::npos) << inf_message;
  EXPECT_NE(message([&] { read_image(path("g.pfm")); }).find("byte offset 15"), std::string::npos);
  // Radiance HDR cannot hold one: its largest RGBE sample, mantissa 255 and exponent 255, is 255 x 2^(255 - 136).
  const std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n" + std::string(4, char(255));
  const ImageRGBA largest = decode_image(hdr, "max.hdr");
  EXPECT_EQ(largest(0, 0).x, float(std::ldexp(255.0, 119)));
  EXPECT_TRUE(std::isfinite(largest(0, 0).x));
}

// The writers refuse them too: a result that is not finite is an error and leaves no file (PFM and HDR would store
// NaN, infinity or garbage).
TEST_F(ImageIo, NonFiniteValuesAreNeverWritten) {
  ImageRGB rgb(3, 2, glm::vec3(0.5f));
  rgb(2, 1).z = NAN;
  for (const char* name : {"n.pfm", "n.hdr"}) {
    try {
      write_image(path(name), rgb);
      ADD_FAILURE() << name << " was written";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("pixel (2, 1) channel b is nan"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path(name)));
  }
  DepthImage depth(2, 2, 1.f);
  depth(0, 1) = INFINITY;
  EXPECT_THROW(write_pfm(path("d.pfm"), depth), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(path("d.pfm")));
}

TEST_F(ImageIo, HostileSizesAreRejectedBeforeAllocating) {
  write_bytes("big.pfm", "PF\n100000 100000\n-1\n1234");
  expect_invalid(path("big.pfm"), {"100000x100000"});
  write_bytes("wide.pfm", "PF\n200000000 1\n-1\n1234");
  expect_invalid(path("wide.pfm"), {"truncated"});
  write_bytes("big.ppm", "P6 16000 16000 255\nabc");
  expect_invalid(path("big.ppm"), {"truncated"});
  write_bytes("ascii.ppm", "P3 16000 16000 255\n1 2 3");
  expect_invalid(path("ascii.ppm"), {"truncated"});
  write_bytes("huge.ppm", "P6 99999999999999999999 1 255\n");
  expect_invalid(path("huge.ppm"), {"width"});
  // A PNG whose header claims 100000 x 100000 pixels (stb does not check CRCs); refused from the header alone.
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0dIHDR", 8) + std::string("\0\x01\x86\xa0\0\x01\x86\xa0\x08\x06\0\0\0", 13) +
         std::string(4, '\0');
  write_bytes("big.png", png);
  expect_invalid(path("big.png"), {"cannot decode"});
}

// A PNG chunk cannot declare more bytes than the file holds (stb_image would first grow a buffer to the declared
// length, 700 MB for a 100-byte file in fuzz_image_formats), and no deflate stream may inflate past the memory budget.
TEST_F(ImageIo, PngChunksAndDeflateStreamsCannotOutgrowTheFileOrTheBudget) {
  const auto chunk = [](std::string_view type, const std::string& data) {
    const auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
    return be32(uint32_t(data.size())) + std::string(type) + data + std::string(4, '\0');  // stb skips CRCs
  };
  const std::string signature = "\x89PNG\r\n\x1a\n";
  const std::string header = chunk("IHDR", std::string("\0\0\0\x01\0\0\0\x01\x08\0\0\0\0", 13));  // 1x1 gray
  std::string liar = signature + header + chunk("IDAT", "x");
  liar[8 + 25 + 0] = '\x2C';  // the IDAT chunk's length: 0x2C000001 bytes
  write_bytes("liar.png", liar);
  expect_invalid(path("liar.png"), {"PNG chunk 'IDAT' at byte 33 declares 738197505 bytes", "ends 13 bytes later"});

  const std::string zeros(size_t(80) << 20, '\0');  // 80 MiB of zero rows for a 1x1 image
  uLongf size = compressBound(uLong(zeros.size()));
  std::string deflated(size, '\0');
  ASSERT_EQ(compress2(reinterpret_cast<Bytef*>(deflated.data()), &size, reinterpret_cast<const Bytef*>(zeros.data()),
                      uLong(zeros.size()), 9),
            Z_OK);
  deflated.resize(size);
  write_bytes("bomb.png", signature + header + chunk("IDAT", deflated) + chunk("IEND", ""));
  MemoryBudget::set_limit(uint64_t(32) << 20);
  expect_invalid(path("bomb.png"), {"larger than the memory budget of 32.0 MiB"});
  MemoryBudget::set_limit(0);
}

TEST_F(ImageIo, MalformedNetpbmSaysWhatIsWrong) {
  write_bytes("v.ppm", "P3 1 1 10\n1 11 2\n");
  expect_invalid(path("v.ppm"), {"byte offset 12", "outside [0, 10]"});
  write_bytes("s.ppm", "P3 2 1 10\n1 1 1 1 1\n");
  expect_invalid(path("s.ppm"), {"truncated", "sample"});
  write_bytes("m.ppm", "P6 1 1 70000\n");
  expect_invalid(path("m.ppm"), {"maxval"});
  write_bytes("b.ppm", std::string("P6 1 1 100\n") + char(101) + char(0) + char(0));
  expect_invalid(path("b.ppm"), {"exceeds maxval"});
  write_bytes("q.ppm", "Q6 1 1 255\n");
  expect_invalid(path("q.ppm"), {"magic number"});
}

// A binary Netpbm file under another extension reached stb_image, which recognizes the content; Debian's stb reads
// 16-bit samples in the wrong byte order and converts their channels as if 8-bit, into half the buffer it returns
// (fuzz_image_formats found the heap overflow). Tessera's own reader takes them: the samples are the file's.
TEST_F(ImageIo, SixteenBitNetpbmThroughStbKeepsItsSamples) {
  const char samples[] = "\x12\x34\x56\x78\x9a\xbc\xff\xff\x00\x00\x80\x00";  // big-endian, as Netpbm stores them
  write_bytes("wide.png", std::string("P6 2 1 65535\n") + std::string(samples, 12));
  const ImageRGBA image = read_image(path("wide.png"));
  ASSERT_EQ(image.width(), 2);
  EXPECT_EQ(image(0, 0), glm::vec4(0x1234 / 65535.f, 0x5678 / 65535.f, 0x9abc / 65535.f, 1.f));
  EXPECT_EQ(image(1, 0), glm::vec4(1.f, 0.f, 0x8000 / 65535.f, 1.f));
  write_bytes("wide_gray.png", std::string("P5 1 1 65535\n") + std::string("\x40\x00", 2));
  EXPECT_EQ(read_image(path("wide_gray.png"))(0, 0), glm::vec4(glm::vec3(0x4000 / 65535.f), 1.f));
}

TEST_F(ImageIo, CorruptStbFilesNameTheFile) {
  write_bytes("garbage.png", "this is not a png at all");
  expect_invalid(path("garbage.png"), {"cannot decode"});
  const ImageRGBA8 image = random_rgba8(16, 16, 7);
  write_image(path("good.png"), image);
  const std::string bytes = read_file(path("good.png"));
  write_bytes("cut.png", bytes.substr(0, bytes.size() / 2));
  expect_invalid(path("cut.png"), {"PNG chunk 'IDAT' at byte 33 declares"});
  write_bytes("empty.jpg", "");
  expect_invalid(path("empty.jpg"), {"cannot decode"});
}

// JPEG files are decoded by libjpeg-turbo, which refuses damaged tables: Debian's stb_image decoded a JPEG whose
// quantization tables were lost from an uninitialized struct (two reads of one file differed; found by
// fuzz_image_formats), and wrote past its Huffman tables on a DHT segment of more than 256 codes.
TEST_F(ImageIo, JpegsWithDamagedTablesAreRefused) {
  write_image(path("good.jpg"), random_rgba8(24, 16, 3));
  const std::string good = read_file(path("good.jpg"));
  const size_t scan = good.find("\xFF\xDA");
  ASSERT_NE(scan, std::string::npos);
  std::string no_tables = good;  // each DQT marker's 0xFF damaged: the segments become junk between markers
  for (size_t i = no_tables.find("\xFF\xDB"); i < scan; i = no_tables.find("\xFF\xDB", i)) no_tables[i] = '\xFE';
  write_bytes("no_tables.jpg", no_tables);
  expect_invalid(path("no_tables.jpg"), {"no_tables.jpg", "Quantization table 0x00 was not defined"});
  std::string huge_dht = good;  // the first DHT's 16 code counts become 255 each: 4080 codes, where 256 is the most
  const size_t dht = huge_dht.find("\xFF\xC4");
  ASSERT_LT(dht, scan);
  for (size_t i = 0; i < 16; ++i) huge_dht[dht + 5 + i] = '\xFF';
  write_bytes("huge_dht.jpg", huge_dht);
  expect_invalid(path("huge_dht.jpg"), {"huge_dht.jpg", "Bogus Huffman table definition"});
  write_bytes("cut.jpg", good.substr(0, scan + (good.size() - scan) / 2));  // half the entropy-coded data
  expect_invalid(path("cut.jpg"), {"cut.jpg", "at byte", "Premature end of JPEG file"});
}

TEST_F(ImageIo, FailedWritesLeaveNoFile) {
  const ImageRGB image(2, 2, glm::vec3(0.5f));
  EXPECT_THROW(write_image(path("no/such/dir/a.png"), image), IoError);
  EXPECT_THROW(write_image(path("empty.png"), ImageRGB()), InvalidInput);
  EXPECT_FALSE(fs::exists(path("empty.png")));
  fs::create_directory(path("taken.pfm"));  // renaming over a folder fails after the data was written
  EXPECT_THROW(write_image(path("taken.pfm"), image), IoError);
  EXPECT_TRUE(fs::is_directory(path("taken.pfm")));
  EXPECT_EQ(file_count(), 1u);  // no temporary left behind
}

TEST_F(ImageIo, WritingReplacesAnExistingFileWhole) {
  write_image(path("a.png"), ImageRGB(64, 64, glm::vec3(0.25f)));
  write_image(path("a.png"), ImageRGB(2, 1, glm::vec3(1.f)));
  const ImageRGBA back = read_image(path("a.png"));
  EXPECT_EQ(back.width(), 2);
  EXPECT_EQ(back(1, 0), glm::vec4(1.f));
  EXPECT_EQ(file_count(), 1u);
}

// read_image_native: 8-bit files give their bytes (a PNG from an independent encoder, and Tessera's PNG, TGA, BMP,
// JPG and PPM/PGM of maxval 255), and read_image's floats are exactly those bytes / 255; everything else is
// read_image's float image.
TEST_F(ImageIo, NativeReadsKeepEightBitFilesEightBit) {
  // v / 255 as read_image documents it, for each byte of `bytes`.
  const auto expect_floats_are_bytes_over_255 = [](const ImageRGBA& floats, const ImageRGBA8& bytes) {
    ASSERT_EQ(floats.pixels().size(), bytes.pixels().size());
    for (size_t i = 0; i < bytes.pixels().size(); ++i)
      for (int c = 0; c < 4; ++c) ASSERT_EQ(floats.pixels()[i][c], float(bytes.pixels()[i][c]) / 255.f) << i;
  };
  if (run(kPngReference + " encode " + path("ref.png").string() + " 11 6")) {
    const FileImage native = read_image_native(path("ref.png"));
    ASSERT_TRUE(std::holds_alternative<ImageRGBA8>(native));
    const ImageRGBA8& got = std::get<ImageRGBA8>(native);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 11; ++x)  // the pattern of png_reference.py
        ASSERT_EQ(got(x, y), glm::u8vec4((7 * x + 3 * y) % 256, (x * y) % 256, 255 - x, 200 + y)) << x << "," << y;
    expect_floats_are_bytes_over_255(read_image(path("ref.png")), got);
    ASSERT_TRUE(run(kPngReference + " encode16 " + path("g16.png").string() + " 9 4"));
    const FileImage wide = read_image_native(path("g16.png"));  // 16-bit: float, read_image's values
    ASSERT_TRUE(std::holds_alternative<ImageRGBA>(wide));
    EXPECT_EQ(max_abs_difference(std::get<ImageRGBA>(wide), read_image(path("g16.png"))), 0.0);
  }
  const ImageRGBA8 image = random_rgba8(13, 7, 21);
  for (const char* name : {"a.png", "a.tga", "a.bmp", "a.jpg", "a.ppm"}) {
    write_image(path(name), image);
    const FileImage native = read_image_native(path(name));
    ASSERT_TRUE(std::holds_alternative<ImageRGBA8>(native)) << name;
    const ImageRGBA8& got = std::get<ImageRGBA8>(native);
    if (std::string(name) == "a.png" || std::string(name) == "a.tga") {
      EXPECT_EQ(count_differing_pixels(got, image), 0) << name;
    }
    if (std::string(name) == "a.bmp" || std::string(name) == "a.ppm") {
      EXPECT_EQ(count_differing_pixels(got, opaque(image)), 0) << name;
    }
    expect_floats_are_bytes_over_255(read_image(path(name)), got);
  }
  write_bytes("p5.pgm", std::string("P5 2 1 255\n") + char(51) + char(255));
  const FileImage gray = read_image_native(path("p5.pgm"));
  ASSERT_TRUE(std::holds_alternative<ImageRGBA8>(gray));
  EXPECT_EQ(std::get<ImageRGBA8>(gray)(0, 0), glm::u8vec4(51, 51, 51, 255));
  EXPECT_EQ(std::get<ImageRGBA8>(gray)(1, 0), glm::u8vec4(255));
  // maxval 10, 16-bit PPM, PFM and HDR: float, exactly read_image's image.
  write_bytes("p3.ppm", "P3 2 1 10 10 0 5 0 10 1\n");
  write_bytes("p6.ppm",
              std::string("P6 1 1 1000\n") + char(0x03) + char(0xe8) + char(0x01) + char(0xf4) + char(0) + char(0));
  write_image(path("a.pfm"), random_rgb(5, 3, 4, -10.f, 10.f));
  write_image(path("a.hdr"), random_rgb(5, 3, 5, 0.f, 10.f));
  for (const char* name : {"p3.ppm", "p6.ppm", "a.pfm", "a.hdr"}) {
    const FileImage native = read_image_native(path(name));
    ASSERT_TRUE(std::holds_alternative<ImageRGBA>(native)) << name;
    EXPECT_EQ(max_abs_difference(std::get<ImageRGBA>(native), read_image(path(name))), 0.0) << name;
  }
}

// The budget of a native 8-bit read counts the decoder's 4 samples and the 4-byte pixel, 8 bytes per pixel, where
// read_image counts 4 + 16 = 20; a P6 PPM of maxval 255: 3 floats and the 4-byte pixel, 16 (read_image: 28).
TEST_F(ImageIo, NativeEightBitReadsBudgetFourBytesPerPixel) {
  struct Restore {
    ~Restore() { MemoryBudget::set_limit(0); }
  } restore;
  write_image(path("a.png"), ImageRGB(100, 100, glm::vec3(0.5f)));
  write_image(path("a.ppm"), ImageRGB(100, 100, glm::vec3(0.5f)));
  const auto refusal = [](const auto& read, const fs::path& file) -> std::string {
    try {
      read(file);
    } catch (const MemoryBudgetError& e) {
      return e.what();
    }
    return "no refusal";
  };
  const auto native = [](const fs::path& file) { return read_image_native(file); };
  const auto floats = [](const fs::path& file) { return read_image(file); };
  MemoryBudget::set_limit(100 * 100 * 8);  // exactly the native PNG's estimate
  EXPECT_TRUE(std::holds_alternative<ImageRGBA8>(read_image_native(path("a.png"))));
  EXPECT_THAT(refusal(floats, path("a.png")),
              HasSubstr("decoding 100x100 pixels needs about " + format_bytes(100 * 100 * 20)));
  EXPECT_THAT(refusal(native, path("a.ppm")), HasSubstr("needs about " + format_bytes(100 * 100 * 16)));
  MemoryBudget::set_limit(100 * 100 * 8 - 1);
  EXPECT_THAT(refusal(native, path("a.png")), HasSubstr("needs about " + format_bytes(100 * 100 * 8)));
  MemoryBudget::set_limit(100 * 100 * 16);
  EXPECT_TRUE(std::holds_alternative<ImageRGBA8>(read_image_native(path("a.ppm"))));
  EXPECT_THAT(refusal(floats, path("a.ppm")), HasSubstr("needs about " + format_bytes(100 * 100 * 28)));
}

}  // namespace
}  // namespace tessera
