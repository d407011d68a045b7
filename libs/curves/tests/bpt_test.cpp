#include "tessera/curves/bpt.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

using ::testing::HasSubstr;

std::string one_patch(const std::string& header = "3 3") {
  std::string text = "1\n" + header + "\n";
  for (int k = 0; k < 16; ++k) text += std::to_string(k % 4) + " " + std::to_string(k / 4) + " 0.5\n";
  return text;
}

// The message of the InvalidInput that parse_bpt throws for `text`.
std::string parse_error(const std::string& text) {
  try {
    parse_bpt(text, "t.bpt");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(Bpt, ParsesThePointOrder) {
  const auto patches = parse_bpt(one_patch());
  ASSERT_EQ(patches.size(), 1u);
  // Control point k = 4 i + j.
  EXPECT_EQ(patches[0].at(0, 1), Vec3(1, 0, 0.5));
  EXPECT_EQ(patches[0].at(2, 3), Vec3(3, 2, 0.5));
  EXPECT_TRUE(parse_bpt("0\n").empty());
  // Any white space separates tokens.
  std::string crlf;
  for (char ch : one_patch()) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  EXPECT_EQ(parse_bpt(crlf)[0].points, patches[0].points);
}

TEST(Bpt, RoundTripsExactly) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::vector<BezierPatch> patches(5);
  for (auto& p : patches)
    for (Vec3& q : p.points) q = Vec3(u(rng), u(rng) * 1e-9, u(rng) * 1e12);
  const auto back = parse_bpt(format_bpt(patches));
  ASSERT_EQ(back.size(), patches.size());
  for (size_t i = 0; i < patches.size(); ++i) EXPECT_EQ(back[i].points, patches[i].points);

  const auto dir = std::filesystem::temp_directory_path() / ("tessera_bpt_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_bpt(dir / "a.bpt", patches);
  EXPECT_EQ(read_bpt(dir / "a.bpt")[4].points, patches[4].points);
  std::filesystem::remove_all(dir);
}

TEST(Bpt, ErrorsSayWhereAndWhatWasExpected) {
  EXPECT_THAT(parse_error(""), HasSubstr("t.bpt:1: expected the patch count, got end of file"));
  EXPECT_THAT(parse_error("x"), HasSubstr("t.bpt:1: the patch count: expected an integer, got 'x'"));
  EXPECT_THAT(parse_error(one_patch("3 2")), HasSubstr("t.bpt:2: expected the v degree of patch 1 to be 3"));
  std::string bad = one_patch();
  bad.replace(bad.find("2 1 0.5"), 7, "2 1 zz");  // control point 7 is on line 9
  EXPECT_THAT(parse_error(bad), HasSubstr("t.bpt:9: z of control point 7 of patch 1: expected a number, got 'zz'"));
  EXPECT_THAT(parse_error(one_patch() + "extra"), HasSubstr("t.bpt:19: expected end of file after the last patch"));
  std::string truncated = one_patch();
  truncated.resize(truncated.size() - 5);
  EXPECT_THAT(parse_error(truncated),
              HasSubstr("t.bpt:18: expected z of control point 16 of patch 1, got end of file"));
  std::string nan = one_patch();
  nan.replace(nan.find("0.5"), 3, "nan");
  EXPECT_THAT(parse_error(nan), HasSubstr("expected a number, got 'nan'"));
}

TEST(Bpt, HostileCountsAreRejectedBeforeAllocating) {
  EXPECT_THAT(parse_error("-1\n"), HasSubstr("expected a patch count >= 0"));
  EXPECT_THAT(parse_error("2000000000\n3 3\n"), HasSubstr("patch count 2000000000 needs at least"));
  // The total the count needs (count x 100 bytes), not the per-patch minimum.
  EXPECT_THAT(parse_error("3\n3 3\n"), HasSubstr("patch count 3 needs at least 300 bytes (100 per patch), 5 are left"));
  EXPECT_THAT(parse_error("9000000000000000000\n3 3\n"),
              HasSubstr("needs at least more than 18446744073709551615 bytes"));
  // Trailing garbage is quoted with control bytes escaped, never sent raw to the terminal.
  EXPECT_THAT(parse_error(one_patch() + "\x1b[2J"), HasSubstr("got '\\x1b[2J'"));
  EXPECT_THAT(parse_error("99999999999999999999999\n"), HasSubstr("expected an integer"));
  EXPECT_THAT(parse_error("2\n" + one_patch().substr(2)), HasSubstr("patch count 2 needs at least"));
}

TEST(Bpt, MissingFileIsAnIoError) { EXPECT_THROW(read_bpt("/nonexistent/x.bpt"), IoError); }

}  // namespace
}  // namespace tessera
