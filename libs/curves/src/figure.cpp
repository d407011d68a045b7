#include "tessera/curves/figure.hpp"

#include <fmt/format.h>

#include "tessera/core/error.hpp"
#include "tessera/curves/convex.hpp"

namespace tessera {
namespace {

// The palette: hull fill, control polygon, construction levels, split halves, curve.
constexpr const char* kHull = "#dfe8f5";
constexpr const char* kControl = "#6d7b8d";
constexpr const char* kLevels[] = {"#2a9d8f", "#e9c46a", "#f4a261", "#e76f51"};
constexpr const char* kHalves[] = {"#d62828", "#1d6fd6"};
constexpr const char* kCurve = "#111111";

std::string points_attr(const std::vector<Vec2>& points) {
  std::string s;
  for (const Vec2& p : points) s += fmt::format("{}{:.3f},{:.3f}", s.empty() ? "" : " ", p.x, p.y);
  return s;
}

std::string polyline(const std::vector<Vec2>& points, const char* color, double width) {
  return fmt::format(
      "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" "
      "stroke-linejoin=\"round\" stroke-linecap=\"round\"/>\n",
      points_attr(points), color, width);
}

std::string dots(const std::vector<Vec2>& points, const char* color, double radius) {
  std::string s;
  for (const Vec2& p : points)
    s += fmt::format("<circle cx=\"{:.3f}\" cy=\"{:.3f}\" r=\"{}\" fill=\"{}\"/>\n", p.x, p.y, radius, color);
  return s;
}

std::vector<Vec2> curve_polyline(const Bezier2& curve, int steps) {
  if (steps > 0) return evaluate_forward_differences(curve, steps);
  std::vector<Vec2> points{curve.front()};
  flatten(curve, 0.1, points);
  return points;
}

}  // namespace

std::string curve_figure_svg(const CurveFigure& figure) {
  if (figure.width < 1 || figure.height < 1 || figure.width > 65536 || figure.height > 65536)
    throw InvalidInput(fmt::format("curve figure: size {}x{} (need 1..65536)", figure.width, figure.height));
  if (figure.construction && !(*figure.construction >= 0 && *figure.construction <= 1))
    throw InvalidInput(fmt::format("curve figure: construction t = {} is outside [0, 1]", *figure.construction));
  if (figure.steps < 0) throw InvalidInput(fmt::format("curve figure: steps = {} is negative", figure.steps));
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">\n"
      "<rect x=\"0\" y=\"0\" width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n",
      figure.width, figure.height);
  for (const Bezier2& curve : figure.curves) {
    if (curve.points.empty()) throw InvalidInput("curve figure: a curve has no control points");
    if (figure.show_hull) {
      const std::vector<Vec2> hull = convex_hull(curve.points);
      if (hull.size() >= 3) svg += fmt::format("<polygon points=\"{}\" fill=\"{}\"/>\n", points_attr(hull), kHull);
    }
  }
  for (const Bezier2& curve : figure.curves) {
    if (figure.show_control_polygon) svg += polyline(curve.points, kControl, 1.5);
    if (figure.construction) {
      const auto levels = de_casteljau_levels(curve, *figure.construction);
      for (size_t k = 1; k + 1 < levels.size(); ++k) {
        const char* color = kLevels[(k - 1) % std::size(kLevels)];
        svg += polyline(levels[k], color, 1.5) + dots(levels[k], color, 3.0);
      }
      if (figure.show_split) {
        const auto [left, right] = split(curve, *figure.construction);
        svg += polyline(left.points, kHalves[0], 2.0) + dots(left.points, kHalves[0], 3.5);
        svg += polyline(right.points, kHalves[1], 2.0) + dots(right.points, kHalves[1], 3.5);
      }
    }
    svg += polyline(curve_polyline(curve, figure.steps), kCurve, 2.5);
    if (figure.show_control_polygon) svg += dots(curve.points, kControl, 4.0);
    if (figure.construction) svg += dots({evaluate_de_casteljau(curve, *figure.construction)}, kLevels[3], 5.0);
  }
  return svg + "</svg>\n";
}

}  // namespace tessera
