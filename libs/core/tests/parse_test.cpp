#include "tessera/core/parse.hpp"

#include <gtest/gtest.h>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

TEST(Parse, Numbers) {
  EXPECT_DOUBLE_EQ(parse_double(" 1.5 ", "x"), 1.5);
  EXPECT_DOUBLE_EQ(parse_double("+2e3", "x"), 2000);
  EXPECT_EQ(parse_int("-42", "n"), -42);
  EXPECT_THROW(parse_double("1.5abc", "x"), InvalidInput);
  EXPECT_THROW(parse_double("nan", "x"), InvalidInput);
  EXPECT_THROW(parse_double("inf", "x"), InvalidInput);
  EXPECT_THROW(parse_double("", "x"), InvalidInput);
  EXPECT_THROW(parse_int("1.0", "n"), InvalidInput);
}

TEST(Parse, ListsAndSizes) {
  EXPECT_EQ(parse_doubles("1,2,3", 3, "v"), (std::vector<double>{1, 2, 3}));
  EXPECT_THROW(parse_doubles("1,2", 3, "v"), InvalidInput);
  EXPECT_THROW(parse_doubles("1,,3", 3, "v"), InvalidInput);
  const auto s = parse_size("640x480", "size");
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 480);
  EXPECT_THROW(parse_size("-5x10", "size"), InvalidInput);
  EXPECT_THROW(parse_size("0x10", "size"), InvalidInput);
  EXPECT_THROW(parse_size("640", "size"), InvalidInput);
  try {
    parse_size("12xq", "--size");
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--size"), std::string::npos);
  }
}

TEST(Parse, PrintableEscapesControlBytesAndTruncates) {
  EXPECT_EQ(printable("plain text"), "plain text");
  EXPECT_EQ(printable("\x1b[31mred\x1b[0m"), "\\x1b[31mred\\x1b[0m");
  EXPECT_EQ(printable("a\nb\tc\r\\"), "a\\nb\\tc\\r\\\\");
  EXPECT_EQ(printable(std::string_view("\0\x7f\xff", 3)), "\\x00\\x7f\\xff");
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x82\xac"), "caf\xc3\xa9 \xe2\x82\xac");  // valid UTF-8 stays readable
  EXPECT_EQ(printable("\xc2\x9b"), "\\xc2\\x9b");                                // a C1 control (CSI) does not
  EXPECT_EQ(printable("\xc3"), "\\xc3");                                         // nor a cut sequence
  // Forms RFC 3629 forbids are escaped byte by byte: an overlong ESC (E0 80 9B, which a lenient terminal decodes as
  // ESC), a surrogate (U+D800) and a code point past U+10FFFF; the smallest valid 3- and 4-byte forms stay.
  EXPECT_EQ(printable("\xe0\x80\x9b[2J"), "\\xe0\\x80\\x9b[2J");
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");
  EXPECT_EQ(printable("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");
  EXPECT_EQ(printable("\xf0\x8f\xbf\xbf"), "\\xf0\\x8f\\xbf\\xbf");
  EXPECT_EQ(printable("\xe0\xa0\x80 \xf0\x90\x80\x80"), "\xe0\xa0\x80 \xf0\x90\x80\x80");
  const std::string line(10'000'000, '7');
  EXPECT_EQ(printable(line, 5), "77777... (10000000 bytes)");
  EXPECT_LT(printable(line).size(), 100u);
}

TEST(Parse, ErrorsQuoteInputPrintably) {
  try {
    parse_doubles(std::string(1'000'000, '1') + "\x1b]0;pwned\x07", 3, "--values");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_LT(what.size(), 200u) << what;
    EXPECT_EQ(what.find('\x1b'), std::string::npos);
  }
  try {
    parse_double("1\x1b[2J", "--near");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "--near: expected a number, got '1\\x1b[2J'");
  }
}

TEST(Parse, SizeBeyondWhatAnImageHoldsNamesTheLimit) {
  EXPECT_EQ(parse_size("65536x32768", "--size").height, 32768);  // exactly 2^31 pixels
  try {
    parse_size("65536x65536", "--size");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(),
                 "--size: 65536x65536 is 4294967296 pixels, more than the 2147483648 (2^31) an image can hold");
  }
}

}  // namespace
}  // namespace tessera
