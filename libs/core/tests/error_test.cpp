#include "tessera/core/error.hpp"

#include <gtest/gtest.h>

namespace tessera {
namespace {

TEST(Error, CheckPassesSilently) { EXPECT_NO_THROW(TESSERA_CHECK(1 + 1 == 2)); }

TEST(Error, CheckThrowsInternalErrorWithExpression) {
  try {
    TESSERA_CHECK(2 + 2 == 5);
    FAIL() << "no throw";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("2 + 2 == 5"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("error_test.cpp"), std::string::npos);
  }
}

TEST(Error, CheckOpPrintsOperands) {
  const int a = 3, b = 4;
  try {
    TESSERA_CHECK_EQ(a, b);
    FAIL() << "no throw";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("3 vs 4"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(TESSERA_CHECK_LT(a, b));
}

TEST(Error, TypedExceptionsDeriveFromError) {
  EXPECT_THROW(throw InvalidInput("x"), Error);
  EXPECT_THROW(throw IoError("x"), Error);
  EXPECT_THROW(throw TopologyError("x"), std::runtime_error);
  EXPECT_EQ(at_line("a.obj", 12), "a.obj:12");
  EXPECT_EQ(at_byte("a.ply", 40), "a.ply: byte offset 40");
  EXPECT_EQ(located("a.obj:12", "expected 3 numbers"), "a.obj:12: expected 3 numbers");
}

}  // namespace
}  // namespace tessera
