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

}  // namespace
}  // namespace tessera
