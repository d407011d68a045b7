#pragma once
// Pictures of Bezier curves as SVG text: the curve, its control polygon and convex hull, the de Casteljau
// construction at a parameter t and the two halves of the split there (the notes' subdivision figures). The text is
// plain SVG 1.1 that any viewer shows and that raster2d's render_svg turns into pixels.
#include <optional>
#include <string>
#include <vector>

#include "tessera/curves/bezier.hpp"

namespace tessera {

/// What a figure shows. Coordinates are pixels: origin top-left, y down (the canvas convention).
struct CurveFigure {
  int width = 400, height = 400;       ///< the SVG's size (and viewBox)
  std::vector<Bezier2> curves;         ///< drawn in order, e.g. the segments of a chain
  bool show_hull = true;               ///< each curve's convex hull, filled
  bool show_control_polygon = true;    ///< each curve's control polygon and control points
  std::optional<double> construction;  ///< t of the de Casteljau construction drawn on every curve (levels, Q(t))
  bool show_split = false;             ///< with construction: the control polygons of the halves [0, t] and [t, 1]
  int steps = 0;                       ///< > 0: curves drawn as `steps` segments by forward differences;
                                       ///< 0: adaptive flattening within 0.1 px
};

/// The SVG document of the figure. Throws InvalidInput for an empty curve, a size outside 1..65536, a construction t
/// outside [0, 1] or steps < 0.
std::string curve_figure_svg(const CurveFigure& figure);

}  // namespace tessera
