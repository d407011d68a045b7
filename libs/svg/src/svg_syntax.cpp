// The grammars of SVG attribute values: numbers, lengths, lists, opacities, path data (SVG 1.1 section 8.3 and the
// arc implementation notes F.6), transform lists (section 7.6) and colors (CSS Color Level 3 keywords).
#include "svg_syntax.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>

#include "tessera/math/transform.hpp"
#include "tessera/svg/svg.hpp"
#include "xml.hpp"

namespace tessera::svg {

SvgValueError::SvgValueError(size_t offset, const std::string& detail)
    : InvalidInput(fmt::format("character {}: {}", offset + 1, detail)), offset_(offset), detail_(detail) {}

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

// "got 'x'" or "got the end" for messages.
std::string describe(std::string_view text, size_t pos) {
  if (pos >= text.size()) return "got the end of the value";
  const unsigned char c = static_cast<unsigned char>(text[pos]);
  if (c < 0x20 || c >= 0x7f) return fmt::format("got byte 0x{:02x}", c);
  return fmt::format("got '{}'", text[pos]);
}

// A cursor over one attribute value with the SVG number, comma-wsp and flag productions.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  size_t pos() const { return pos_; }
  void advance() { ++pos_; }

  void skip_space() {
    while (!at_end() && xml::is_space(text_[pos_])) ++pos_;
  }
  // wsp* (',' wsp*)?: returns true when a comma was consumed (then something must follow).
  bool skip_comma_space() {
    skip_space();
    if (peek() != ',') return false;
    ++pos_;
    skip_space();
    return true;
  }
  bool at_number() const {
    const char c = peek();
    return is_digit(c) || c == '.' || c == '-' || c == '+';
  }

  // number ::= sign? (digits ('.' digits?)? | '.' digits) (('e'|'E') sign? digits)?
  double number(std::string_view what) {
    const size_t start = pos_;
    size_t i = pos_;
    if (i < text_.size() && (text_[i] == '+' || text_[i] == '-')) ++i;
    size_t digits = 0;
    while (i < text_.size() && is_digit(text_[i])) ++i, ++digits;
    if (i < text_.size() && text_[i] == '.') {
      ++i;
      while (i < text_.size() && is_digit(text_[i])) ++i, ++digits;
    }
    if (digits == 0) fail(fmt::format("expected {}, {}", what, describe(text_, start)));
    if (i < text_.size() && (text_[i] == 'e' || text_[i] == 'E')) {
      size_t j = i + 1;
      if (j < text_.size() && (text_[j] == '+' || text_[j] == '-')) ++j;
      if (j < text_.size() && is_digit(text_[j])) {
        while (j < text_.size() && is_digit(text_[j])) ++j;
        i = j;
      }
    }
    const size_t first = text_[start] == '+' ? start + 1 : start;
    double value = 0;
    const auto [end, ec] = std::from_chars(text_.data() + first, text_.data() + i, value);
    if (ec != std::errc() || end != text_.data() + i || !std::isfinite(value))
      fail(fmt::format("number '{}' is out of range", text_.substr(start, i - start)));
    pos_ = i;
    return value;
  }

  // An arc flag: a single '0' or '1' (no separator needed after it).
  bool flag() {
    const char c = peek();
    if (c != '0' && c != '1') fail(fmt::format("expected an arc flag '0' or '1', {}", describe(text_, pos_)));
    ++pos_;
    return c == '1';
  }

  // Letters (a function or unit name).
  std::string_view word() {
    const size_t start = pos_;
    while (!at_end() && is_alpha(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  void expect(char c, std::string_view context) {
    if (peek() != c) fail(fmt::format("expected '{}' {}, {}", c, context, describe(text_, pos_)));
    ++pos_;
  }
  void expect_end() {
    skip_space();
    if (!at_end()) fail(fmt::format("unexpected '{}' after the value", printable(text_.substr(pos_))));
  }

  [[noreturn]] void fail(const std::string& what) const { throw SvgValueError(pos_, what); }
  [[noreturn]] void fail_at(size_t pos, const std::string& what) const { throw SvgValueError(pos, what); }

 private:
  std::string_view text_;
  size_t pos_ = 0;
};

}  // namespace

double parse_number(std::string_view text) {
  Scanner s(text);
  s.skip_space();
  const double v = s.number("a number");
  s.expect_end();
  return v;
}

double parse_length(std::string_view text) {
  Scanner s(text);
  s.skip_space();
  const double v = s.number("a length");
  const size_t unit_pos = s.pos();
  std::string_view unit = s.word();
  if (unit.empty() && s.peek() == '%') unit = "%";
  if (!unit.empty() && unit != "px")
    s.fail_at(unit_pos, fmt::format("unit '{}' is not supported (lengths are px or unitless)", unit));
  s.expect_end();
  return v;
}

std::vector<double> parse_number_list(std::string_view text) {
  Scanner s(text);
  std::vector<double> values;
  s.skip_space();
  bool comma = false;
  while (!s.at_end() || comma) {
    values.push_back(s.number("a number"));
    comma = s.skip_comma_space();
  }
  return values;
}

float parse_opacity(std::string_view text) {
  Scanner s(text);
  s.skip_space();
  double v = s.number("an opacity (a number or a percentage)");
  if (s.peek() == '%') {
    s.advance();
    v /= 100;
  }
  s.expect_end();
  return float(std::clamp(v, 0.0, 1.0));
}

void append_arc_cubics(std::vector<SvgSegment>& out, const Vec2& center, double rx, double ry, double phi,
                       double theta1, double dtheta, const Vec2& end) {
  const int pieces = std::max(1, int(std::ceil(std::abs(dtheta) / (kPi / 4) - 1e-9)));
  const double step = dtheta / pieces;
  const double k = 4.0 / 3.0 * std::tan(step / 4);
  const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
  const auto map = [&](const Vec2& unit) {
    return center + Vec2(cos_phi * rx * unit.x - sin_phi * ry * unit.y, sin_phi * rx * unit.x + cos_phi * ry * unit.y);
  };
  for (int i = 0; i < pieces; ++i) {
    const double t0 = theta1 + i * step, t1 = t0 + step;
    const Vec2 p0(std::cos(t0), std::sin(t0)), p3(std::cos(t1), std::sin(t1));
    const Vec2 c1 = p0 + k * Vec2(-p0.y, p0.x), c2 = p3 - k * Vec2(-p3.y, p3.x);
    out.push_back({SvgSegment::Kind::cubic, map(c1), map(c2), i + 1 == pieces ? end : map(p3)});
  }
}

namespace {

// Builds subpaths from path commands, tracking the current point, the subpath start and the control points that S
// and T reflect.
class PathBuilder {
 public:
  // Applies one command letter with its arguments (already read, flags as 0/1).
  void apply(char op, const std::array<double, 7>& a) {
    const bool relative = op >= 'a' && op <= 'z';
    const Vec2 cur = current_;
    const Vec2 origin = relative ? cur : Vec2(0.0);
    const auto pt = [&](int i) { return origin + Vec2(a[size_t(i)], a[size_t(i) + 1]); };
    std::optional<Vec2> cubic_control, quad_control;
    switch (op & ~0x20) {  // upper case
      case 'M':
        subpaths_.push_back({pt(0), {}, false});
        current_ = start_ = pt(0);
        open_ = true;
        break;
      case 'L':
        line_to(pt(0));
        break;
      case 'H':
        line_to({origin.x + a[0], cur.y});
        break;
      case 'V':
        line_to({cur.x, origin.y + a[0]});
        break;
      case 'C':
        cubic_control = pt(2);
        add({SvgSegment::Kind::cubic, pt(0), pt(2), pt(4)});
        break;
      case 'S':
        cubic_control = pt(0);
        add({SvgSegment::Kind::cubic, last_cubic_ ? 2.0 * cur - *last_cubic_ : cur, pt(0), pt(2)});
        break;
      case 'Q':
        quad_control = pt(0);
        add({SvgSegment::Kind::quadratic, pt(0), Vec2(0.0), pt(2)});
        break;
      case 'T':
        quad_control = last_quad_ ? 2.0 * cur - *last_quad_ : cur;
        add({SvgSegment::Kind::quadratic, *quad_control, Vec2(0.0), pt(0)});
        break;
      case 'A':
        arc_to(a[0], a[1], a[2], a[3] != 0, a[4] != 0, pt(5));
        break;
      default:  // 'Z'
        if (open_) subpaths_.back().closed = true;
        current_ = start_;
        open_ = false;
        break;
    }
    last_cubic_ = cubic_control;
    last_quad_ = quad_control;
  }

  std::vector<SvgSubpath> take() { return std::move(subpaths_); }

 private:
  // The open subpath's segments; a segment after Z (without M) starts a new subpath at the closed one's start.
  std::vector<SvgSegment>& segments() {
    if (!open_) {
      subpaths_.push_back({current_, {}, false});
      start_ = current_;
      open_ = true;
    }
    return subpaths_.back().segments;
  }
  void add(const SvgSegment& segment) {
    segments().push_back(segment);
    current_ = segment.end;
  }
  void line_to(const Vec2& p) { add({SvgSegment::Kind::line, Vec2(0.0), Vec2(0.0), p}); }

  // SVG 1.1 F.6.5: endpoint to center parameterization, with F.6.6's correction of out-of-range radii.
  void arc_to(double rx, double ry, double phi_degrees, bool large_arc, bool sweep, const Vec2& end) {
    const Vec2 p1 = current_;
    if (p1 == end) return;  // F.6.2: identical endpoints omit the arc
    rx = std::abs(rx);
    ry = std::abs(ry);
    if (rx == 0 || ry == 0) return line_to(end);  // F.6.2: a zero radius makes it a line
    const double phi = radians(std::fmod(phi_degrees, 360.0));
    const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
    const Vec2 half = 0.5 * (p1 - end);
    const Vec2 p1r(cos_phi * half.x + sin_phi * half.y, -sin_phi * half.x + cos_phi * half.y);  // (x1', y1')
    const double lambda = (p1r.x / rx) * (p1r.x / rx) + (p1r.y / ry) * (p1r.y / ry);
    if (lambda > 1) {
      rx *= std::sqrt(lambda);
      ry *= std::sqrt(lambda);
    }
    // (rx^2 ry^2 - rx^2 y1'^2 - ry^2 x1'^2) / (rx^2 y1'^2 + ry^2 x1'^2) = (1 - lambda) / lambda, free of overflow.
    const double coef = (large_arc != sweep ? 1.0 : -1.0) * std::sqrt(std::max(0.0, (1 - lambda) / lambda));
    const Vec2 cr(coef * rx * p1r.y / ry, -coef * ry * p1r.x / rx);  // (cx', cy')
    const Vec2 center(cos_phi * cr.x - sin_phi * cr.y + 0.5 * (p1.x + end.x),
                      sin_phi * cr.x + cos_phi * cr.y + 0.5 * (p1.y + end.y));
    const Vec2 u((p1r.x - cr.x) / rx, (p1r.y - cr.y) / ry), v((-p1r.x - cr.x) / rx, (-p1r.y - cr.y) / ry);
    const double theta1 = std::atan2(u.y, u.x);
    double dtheta = std::atan2(u.x * v.y - u.y * v.x, glm::dot(u, v));
    if (!sweep && dtheta > 0) dtheta -= 2 * kPi;
    if (sweep && dtheta < 0) dtheta += 2 * kPi;
    // Finite numbers whose arc is not (radii or endpoints near 1e308, whose differences and products overflow; an
    // angle of 1e308 degrees): nothing of it is drawable, and a NaN piece count would be undefined behaviour.
    if (!std::isfinite(dtheta) || !std::isfinite(theta1) || !std::isfinite(center.x) || !std::isfinite(center.y) ||
        !std::isfinite(rx) || !std::isfinite(ry))
      return line_to(end);
    append_arc_cubics(segments(), center, rx, ry, phi, theta1, dtheta, end);
    current_ = end;
  }

  std::vector<SvgSubpath> subpaths_;
  Vec2 current_{0.0}, start_{0.0};
  bool open_ = false;
  std::optional<Vec2> last_cubic_, last_quad_;
};

// Number of arguments of a path command, -1 for a letter that is not one.
int path_arity(char c) {
  switch (c & ~0x20) {
    case 'Z':
      return 0;
    case 'H':
    case 'V':
      return 1;
    case 'M':
    case 'L':
    case 'T':
      return 2;
    case 'S':
    case 'Q':
      return 4;
    case 'C':
      return 6;
    case 'A':
      return 7;
    default:
      return -1;
  }
}

}  // namespace

}  // namespace tessera::svg

namespace tessera {

std::vector<SvgSubpath> parse_svg_path_data(std::string_view d) {
  svg::Scanner s(d);
  svg::PathBuilder builder;
  char command = 0;
  s.skip_space();
  while (!s.at_end()) {
    const char c = s.peek();
    const int arity = svg::is_alpha(c) ? svg::path_arity(c) : -1;
    if (command == 0 && c != 'M' && c != 'm')
      s.fail(fmt::format("path data must start with a moveto ('M' or 'm'), {}", svg::describe(d, s.pos())));
    if (arity < 0)
      s.fail(fmt::format("expected a path command (M L H V C S Q T A Z or lower case), {}", svg::describe(d, s.pos())));
    s.advance();
    command = c;
    char op = c;
    if (arity == 0) {
      builder.apply(op, {});
      s.skip_space();
      continue;
    }
    const std::string what = fmt::format("a number for '{}' ({} per segment)", c, arity);
    for (;;) {
      s.skip_space();
      std::array<double, 7> args{};
      bool comma = false;
      for (int k = 0; k < arity; ++k) {
        const bool is_flag = (op == 'A' || op == 'a') && (k == 3 || k == 4);
        args[size_t(k)] = is_flag ? (s.flag() ? 1 : 0) : s.number(what);
        comma = s.skip_comma_space();
      }
      builder.apply(op, args);
      if (!comma && !s.at_number()) break;                      // the next command letter (or the end)
      if (op == 'M' || op == 'm') op = char(op + ('L' - 'M'));  // implicit lineto after a moveto's first pair
    }
  }
  return builder.take();
}

Mat3 parse_svg_transform(std::string_view text) {
  svg::Scanner s(text);
  Mat3 result(1.0);
  s.skip_space();
  while (!s.at_end()) {
    const size_t name_pos = s.pos();
    const std::string_view name = s.word();
    if (name.empty())
      s.fail(fmt::format("expected a transform function (matrix, translate, scale, rotate, skewX, skewY), {}",
                         svg::describe(text, name_pos)));
    s.skip_space();
    s.expect('(', fmt::format("after '{}'", name));
    std::vector<double> a;
    s.skip_space();
    bool comma = false;
    while (s.peek() != ')' || comma) {
      a.push_back(s.number(fmt::format("a number in {}(...)", name)));
      comma = s.skip_comma_space();
    }
    s.advance();  // ')'
    const auto arity_error = [&](const char* counts) {
      s.fail_at(name_pos, fmt::format("{}() takes {} numbers, got {}", name, counts, a.size()));
    };
    Mat3 t(1.0);
    if (name == "matrix") {
      if (a.size() != 6) arity_error("6");
      t[0] = Vec3(a[0], a[1], 0);  // columns: [a c e; b d f; 0 0 1]
      t[1] = Vec3(a[2], a[3], 0);
      t[2] = Vec3(a[4], a[5], 1);
    } else if (name == "translate") {
      if (a.size() != 1 && a.size() != 2) arity_error("1 or 2");
      t = translate2d(a[0], a.size() == 2 ? a[1] : 0.0);
    } else if (name == "scale") {
      if (a.size() != 1 && a.size() != 2) arity_error("1 or 2");
      t = scale2d(a[0], a.size() == 2 ? a[1] : a[0]);
    } else if (name == "rotate") {
      if (a.size() != 1 && a.size() != 3) arity_error("1 or 3");
      t = a.size() == 3 ? rotate2d_about(radians(a[0]), a[1], a[2]) : rotate2d(radians(a[0]));
    } else if (name == "skewX") {
      if (a.size() != 1) arity_error("1");
      t = shear2d(std::tan(radians(a[0])), 0);
    } else if (name == "skewY") {
      if (a.size() != 1) arity_error("1");
      t = shear2d(0, std::tan(radians(a[0])));
    } else {
      s.fail_at(name_pos, fmt::format("unknown transform function '{}' (expected matrix, translate, scale, rotate, "
                                      "skewX or skewY)",
                                      name));
    }
    result = result * t;
    s.skip_comma_space();
  }
  return result;
}

}  // namespace tessera

namespace tessera::svg {
namespace {

// The CSS Color Level 3 keywords (SVG 1.1 section 4.4), sorted by name for binary search.
struct NamedColor {
  std::string_view name;
  uint32_t rgb;
};
constexpr NamedColor kNamedColors[] = {
    {"aliceblue", 0xf0f8ff},
    {"antiquewhite", 0xfaebd7},
    {"aqua", 0x00ffff},
    {"aquamarine", 0x7fffd4},
    {"azure", 0xf0ffff},
    {"beige", 0xf5f5dc},
    {"bisque", 0xffe4c4},
    {"black", 0x000000},
    {"blanchedalmond", 0xffebcd},
    {"blue", 0x0000ff},
    {"blueviolet", 0x8a2be2},
    {"brown", 0xa52a2a},
    {"burlywood", 0xdeb887},
    {"cadetblue", 0x5f9ea0},
    {"chartreuse", 0x7fff00},
    {"chocolate", 0xd2691e},
    {"coral", 0xff7f50},
    {"cornflowerblue", 0x6495ed},
    {"cornsilk", 0xfff8dc},
    {"crimson", 0xdc143c},
    {"cyan", 0x00ffff},
    {"darkblue", 0x00008b},
    {"darkcyan", 0x008b8b},
    {"darkgoldenrod", 0xb8860b},
    {"darkgray", 0xa9a9a9},
    {"darkgreen", 0x006400},
    {"darkgrey", 0xa9a9a9},
    {"darkkhaki", 0xbdb76b},
    {"darkmagenta", 0x8b008b},
    {"darkolivegreen", 0x556b2f},
    {"darkorange", 0xff8c00},
    {"darkorchid", 0x9932cc},
    {"darkred", 0x8b0000},
    {"darksalmon", 0xe9967a},
    {"darkseagreen", 0x8fbc8f},
    {"darkslateblue", 0x483d8b},
    {"darkslategray", 0x2f4f4f},
    {"darkslategrey", 0x2f4f4f},
    {"darkturquoise", 0x00ced1},
    {"darkviolet", 0x9400d3},
    {"deeppink", 0xff1493},
    {"deepskyblue", 0x00bfff},
    {"dimgray", 0x696969},
    {"dimgrey", 0x696969},
    {"dodgerblue", 0x1e90ff},
    {"firebrick", 0xb22222},
    {"floralwhite", 0xfffaf0},
    {"forestgreen", 0x228b22},
    {"fuchsia", 0xff00ff},
    {"gainsboro", 0xdcdcdc},
    {"ghostwhite", 0xf8f8ff},
    {"gold", 0xffd700},
    {"goldenrod", 0xdaa520},
    {"gray", 0x808080},
    {"green", 0x008000},
    {"greenyellow", 0xadff2f},
    {"grey", 0x808080},
    {"honeydew", 0xf0fff0},
    {"hotpink", 0xff69b4},
    {"indianred", 0xcd5c5c},
    {"indigo", 0x4b0082},
    {"ivory", 0xfffff0},
    {"khaki", 0xf0e68c},
    {"lavender", 0xe6e6fa},
    {"lavenderblush", 0xfff0f5},
    {"lawngreen", 0x7cfc00},
    {"lemonchiffon", 0xfffacd},
    {"lightblue", 0xadd8e6},
    {"lightcoral", 0xf08080},
    {"lightcyan", 0xe0ffff},
    {"lightgoldenrodyellow", 0xfafad2},
    {"lightgray", 0xd3d3d3},
    {"lightgreen", 0x90ee90},
    {"lightgrey", 0xd3d3d3},
    {"lightpink", 0xffb6c1},
    {"lightsalmon", 0xffa07a},
    {"lightseagreen", 0x20b2aa},
    {"lightskyblue", 0x87cefa},
    {"lightslategray", 0x778899},
    {"lightslategrey", 0x778899},
    {"lightsteelblue", 0xb0c4de},
    {"lightyellow", 0xffffe0},
    {"lime", 0x00ff00},
    {"limegreen", 0x32cd32},
    {"linen", 0xfaf0e6},
    {"magenta", 0xff00ff},
    {"maroon", 0x800000},
    {"mediumaquamarine", 0x66cdaa},
    {"mediumblue", 0x0000cd},
    {"mediumorchid", 0xba55d3},
    {"mediumpurple", 0x9370db},
    {"mediumseagreen", 0x3cb371},
    {"mediumslateblue", 0x7b68ee},
    {"mediumspringgreen", 0x00fa9a},
    {"mediumturquoise", 0x48d1cc},
    {"mediumvioletred", 0xc71585},
    {"midnightblue", 0x191970},
    {"mintcream", 0xf5fffa},
    {"mistyrose", 0xffe4e1},
    {"moccasin", 0xffe4b5},
    {"navajowhite", 0xffdead},
    {"navy", 0x000080},
    {"oldlace", 0xfdf5e6},
    {"olive", 0x808000},
    {"olivedrab", 0x6b8e23},
    {"orange", 0xffa500},
    {"orangered", 0xff4500},
    {"orchid", 0xda70d6},
    {"palegoldenrod", 0xeee8aa},
    {"palegreen", 0x98fb98},
    {"paleturquoise", 0xafeeee},
    {"palevioletred", 0xdb7093},
    {"papayawhip", 0xffefd5},
    {"peachpuff", 0xffdab9},
    {"peru", 0xcd853f},
    {"pink", 0xffc0cb},
    {"plum", 0xdda0dd},
    {"powderblue", 0xb0e0e6},
    {"purple", 0x800080},
    {"red", 0xff0000},
    {"rosybrown", 0xbc8f8f},
    {"royalblue", 0x4169e1},
    {"saddlebrown", 0x8b4513},
    {"salmon", 0xfa8072},
    {"sandybrown", 0xf4a460},
    {"seagreen", 0x2e8b57},
    {"seashell", 0xfff5ee},
    {"sienna", 0xa0522d},
    {"silver", 0xc0c0c0},
    {"skyblue", 0x87ceeb},
    {"slateblue", 0x6a5acd},
    {"slategray", 0x708090},
    {"slategrey", 0x708090},
    {"snow", 0xfffafa},
    {"springgreen", 0x00ff7f},
    {"steelblue", 0x4682b4},
    {"tan", 0xd2b48c},
    {"teal", 0x008080},
    {"thistle", 0xd8bfd8},
    {"tomato", 0xff6347},
    {"turquoise", 0x40e0d0},
    {"violet", 0xee82ee},
    {"wheat", 0xf5deb3},
    {"white", 0xffffff},
    {"whitesmoke", 0xf5f5f5},
    {"yellow", 0xffff00},
    {"yellowgreen", 0x9acd32},
};

Vec4f from_rgb24(uint32_t rgb) {
  return {float((rgb >> 16) & 0xff) / 255.0f, float((rgb >> 8) & 0xff) / 255.0f, float(rgb & 0xff) / 255.0f, 1.0f};
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

}  // namespace tessera::svg

namespace tessera {

Vec4f parse_svg_color(std::string_view text) {
  svg::Scanner s(text);
  s.skip_space();
  const size_t start = s.pos();
  if (s.peek() == '#') {
    s.advance();
    uint32_t rgb = 0;
    int digits = 0;
    while (!s.at_end() && svg::hex_digit(s.peek()) >= 0) {
      rgb = (rgb << 4) | uint32_t(svg::hex_digit(s.peek()));
      s.advance();
      ++digits;
    }
    if (digits != 3 && digits != 6)
      s.fail_at(start, fmt::format("expected a color #rgb or #rrggbb, got '{}'", printable(trim(text))));
    s.expect_end();
    if (digits == 3)  // #abc is #aabbcc
      rgb = ((rgb & 0xf00) << 12) | ((rgb & 0xf00) << 8) | ((rgb & 0xf0) << 8) | ((rgb & 0xf0) << 4) |
            ((rgb & 0xf) << 4) | (rgb & 0xf);
    return svg::from_rgb24(rgb);
  }
  std::string name(s.word());
  std::transform(name.begin(), name.end(), name.begin(), [](char c) { return char(std::tolower(c)); });
  s.skip_space();
  if ((name == "rgb" || name == "rgba") && s.peek() == '(') {
    s.advance();
    const size_t count = name.size();  // 3 channels for rgb, 4 for rgba
    Vec4f color(0, 0, 0, 1);
    for (size_t i = 0; i < count; ++i) {
      if (i > 0) s.expect(',', fmt::format("between the {}() components", name));
      s.skip_space();
      double v = s.number(fmt::format("a component of {}()", name));
      const bool percent = s.peek() == '%';
      if (percent) s.advance();
      v = percent ? v / 100 : (i < 3 ? v / 255 : v);  // alpha is a number in [0, 1] or a percentage
      color[int(i)] = float(std::clamp(v, 0.0, 1.0));
      s.skip_space();
    }
    s.expect(')', fmt::format("to close {}()", name));
    s.expect_end();
    return color;
  }
  const auto it = std::lower_bound(std::begin(svg::kNamedColors), std::end(svg::kNamedColors), name,
                                   [](const svg::NamedColor& c, const std::string& n) { return c.name < n; });
  if (name.empty() || it == std::end(svg::kNamedColors) || it->name != name)
    s.fail_at(start, fmt::format("unknown color '{}' (expected #rgb, #rrggbb, rgb(r, g, b), rgba(r, g, b, a) or a "
                                 "CSS color keyword)",
                                 printable(trim(text))));
  s.expect_end();
  return svg::from_rgb24(it->rgb);
}

}  // namespace tessera
