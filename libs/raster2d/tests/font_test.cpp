#include "tessera/raster2d/font.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <set>
#include <utility>

namespace tessera {
namespace {

int ink(char c) {
  int n = 0;
  for (const uint8_t row : font::glyph(c)) n += std::popcount(row);
  return n;
}

// The glyph as the picture it is drawn from, for readable expectations.
std::vector<std::string> picture(char c) {
  std::vector<std::string> rows;
  for (const uint8_t row : font::glyph(c)) {
    std::string s;
    for (int col = 0; col < font::kGlyphWidth; ++col) s += (row >> (font::kGlyphWidth - 1 - col) & 1) ? '#' : '.';
    rows.push_back(s);
  }
  return rows;
}

TEST(Font, KnownGlyphs) {
  EXPECT_EQ(ink(' '), 0);
  EXPECT_EQ(ink('.'), 4);   // a 2 x 2 dot
  EXPECT_EQ(ink('I'), 11);  // two serifs of 3 and a stem of 5
  EXPECT_EQ(ink('H'), 17);  // two stems of 7 and a bar of 3
  EXPECT_EQ(picture('I'),
            (std::vector<std::string>{".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###.", "....."}));
  EXPECT_EQ(picture('L'),
            (std::vector<std::string>{"#....", "#....", "#....", "#....", "#....", "#....", "#####", "....."}));
  // Capitals and digits stand on the baseline; g, j, p, q, y reach the descender row; '_' lies in it.
  for (const char c : std::string("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789")) {
    EXPECT_NE(font::glyph(c)[0], 0) << c;
    EXPECT_NE(font::glyph(c)[6], 0) << c;
    EXPECT_EQ(font::glyph(c)[7], 0) << c;
  }
  for (const char c : std::string("gjpqy_")) EXPECT_NE(font::glyph(c)[7], 0) << c;
  // Every printable character but the space has ink, and no two printable characters look the same.
  std::set<font::Glyph> seen;
  for (int c = 33; c <= 126; ++c) {
    EXPECT_GT(ink(char(c)), 0) << c;
    EXPECT_TRUE(seen.insert(font::glyph(char(c))).second) << char(c);
  }
  // Anything else is the hollow box: 5 + 5 + 2 x 5 pixels.
  for (const char c : {'\t', '\0', char(127), char(0xC3)}) {
    EXPECT_EQ(font::glyph(c), font::glyph('\x01'));
    EXPECT_EQ(ink(c), 20);
  }
}

TEST(Font, RunsCoverTheGlyphsAtTheirCells) {
  // "I." left-aligned: the I's runs in cell 0, the dot's in cell 1 (x + 6), rows -7 .. -1 above the baseline.
  const std::vector<font::TextRun> runs = font::text_runs("I.");
  const std::set<std::tuple<int, int, int>> got = [&] {
    std::set<std::tuple<int, int, int>> s;
    for (const auto& r : runs) s.insert({r.x0, r.x1, r.y});
    return s;
  }();
  const std::set<std::tuple<int, int, int>> want{{1, 4, -7}, {2, 3, -6}, {2, 3, -5}, {2, 3, -4}, {2, 3, -3},
                                                 {2, 3, -2}, {1, 4, -1}, {7, 9, -2}, {7, 9, -1}};
  EXPECT_EQ(got, want);
}

TEST(Font, AlignmentAndLines) {
  EXPECT_EQ(font::text_width(""), 0);
  EXPECT_EQ(font::text_width("abc"), 18);
  EXPECT_EQ(font::text_width("ab\nlonger\r\nc"), 36);  // the widest line; '\r' takes no room
  EXPECT_EQ(font::line_count(""), 1);
  EXPECT_EQ(font::line_count("a\nb\n"), 3);
  // Centered, each line moves left by half its own width; right-aligned by all of it; line i is 10 units lower.
  const auto first_x = [](std::string_view text, TextAlignX align, int line) {
    int x = 1 << 20;
    for (const auto& r : font::text_runs(text, align))
      if (r.y >= line * font::kLineHeight - font::kAscent && r.y < line * font::kLineHeight + font::kDescent)
        x = std::min(x, r.x0);
    return x;
  };
  EXPECT_EQ(first_x("LL\nL", TextAlignX::left, 0), 0);
  EXPECT_EQ(first_x("LL\nL", TextAlignX::left, 1), 0);
  EXPECT_EQ(first_x("LL\nL", TextAlignX::center, 0), -6);
  EXPECT_EQ(first_x("LL\nL", TextAlignX::center, 1), -3);
  EXPECT_EQ(first_x("LL\nL", TextAlignX::right, 0), -12);
  EXPECT_EQ(first_x("LL\nL", TextAlignX::right, 1), -6);
  EXPECT_EQ(font::text_runs("A\r\nB", TextAlignX::left).size(), font::text_runs("A\nB", TextAlignX::left).size());
}

}  // namespace
}  // namespace tessera
