#pragma once
// Helpers shared by the svg module's tests: comparisons with tolerances, the message of an expected InvalidInput, a
// document from a body, and the check that flattened arcs lie on their ellipse.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera::test {

inline void expect_near(const Vec2& a, const Vec2& b, double eps = 1e-12) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
}

inline void expect_matrix_near(const Mat3& a, const Mat3& b, double eps = 1e-12) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], eps) << "column " << c << " row " << r;
}

inline void expect_color(const Vec4f& c, float r, float g, float b, float a = 1) {
  EXPECT_NEAR(c.x, r, 1e-6);
  EXPECT_NEAR(c.y, g, 1e-6);
  EXPECT_NEAR(c.z, b, 1e-6);
  EXPECT_NEAR(c.w, a, 1e-6);
}

// The message of the InvalidInput that f throws (fails the test when it throws nothing or something else).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected InvalidInput";
  return {};
}

// A document "t.svg" whose root <svg> has the attributes `root` and holds `body`.
inline SvgDocument parse(std::string_view body, std::string_view root = R"~(width="100" height="100")~") {
  return parse_svg(fmt::format(R"~(<svg xmlns="http://www.w3.org/2000/svg" {}>{}</svg>)~", root, body), "t.svg");
}

// Every flattened point of an arc lies on its ellipse.
inline void expect_on_ellipse(const std::vector<SvgSubpath>& p, const Vec2& center, double rx, double ry, double phi) {
  const auto lines = flatten_svg_subpaths(p, Mat3(1.0), 1e-4);
  ASSERT_EQ(lines.size(), 1u);
  for (const Vec2& q : lines[0].points) {
    const Vec2 d = q - center;
    const double u = (std::cos(phi) * d.x + std::sin(phi) * d.y) / rx;
    const double v = (-std::sin(phi) * d.x + std::cos(phi) * d.y) / ry;
    EXPECT_NEAR(u * u + v * v, 1.0, 1e-4) << q.x << "," << q.y;
  }
}

}  // namespace tessera::test
