#pragma once
// Private to the SVG front end: the grammars of attribute values (numbers, lengths, number lists, opacities; path
// data, transforms and colors are public in svg.hpp). Errors are SvgValueError, an InvalidInput that also carries the
// byte offset inside the value, so the document parser can point at file:line:column.
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera::svg {

/// A malformed attribute value: `offset` is the byte offset inside the value, `detail` what was expected there (any
/// input it quotes went through printable()).
class SvgValueError : public InvalidInput {
 public:
  SvgValueError(size_t offset, const std::string& detail);
  size_t offset() const { return offset_; }
  const std::string& detail() const { return detail_; }

 private:
  size_t offset_;
  std::string detail_;
};

/// A value that is exactly one number (SVG number grammar; white space around it allowed).
double parse_number(std::string_view text);

/// A length: a number, optionally followed by "px". Any other unit throws, naming it.
double parse_length(std::string_view text);

/// Numbers separated by white space and/or a comma, as in `points` and `viewBox` (compact forms allowed).
std::vector<double> parse_number_list(std::string_view text);

/// An opacity: a number or a percentage, clamped to [0, 1].
float parse_opacity(std::string_view text);

/// Appends cubic Beziers approximating the elliptical arc center + R(phi) diag(rx, ry) (cos t, sin t) for t from
/// theta1 over dtheta (radians), in pieces of at most 45 degrees (radial error below 5e-6 of the radius, tangent
/// length 4/3 tan(delta/4)); the last piece ends exactly at `end`, which should be the arc's end point.
void append_arc_cubics(std::vector<SvgSegment>& out, const Vec2& center, double rx, double ry, double phi,
                       double theta1, double dtheta, const Vec2& end);

}  // namespace tessera::svg
