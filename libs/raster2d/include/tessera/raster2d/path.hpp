#pragma once
// Filled paths and strokes in device (pixel) coordinates: the canvas's and the SVG front end's common back end.
//
// Coverage follows DESIGN.md: pixel (x, y) covers [x, x+1) x [y, y+1). Without antialiasing a pixel is filled iff its
// center (x + 0.5, y + 0.5) is inside (half-open: centers exactly on a left or top edge are in, on a right or bottom
// edge are out, so abutting shapes never share a pixel). With antialiasing the pixel's coverage is the fraction of its
// square inside the path.
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// Which points a set of closed contours encloses.
enum class FillRule {
  non_zero,  ///< winding number != 0
  even_odd,  ///< odd number of crossings
};

/// Closed polygonal contours (each implicitly closed back to its first point), in device pixel coordinates.
struct Path {
  std::vector<std::vector<Vec2>> contours;
};

/// How stroke segments meet.
enum class LineJoin { miter, round, bevel };
/// How open strokes end.
enum class LineCap { butt, round, square };

/// Stroke parameters (SVG/Processing semantics).
struct StrokeStyle {
  double width = 1;  ///< full line width in pixels
  LineJoin join = LineJoin::miter;
  LineCap cap = LineCap::butt;
  double miter_limit = 4;  ///< miter length / width above which a miter becomes a bevel
};

/// Fills `path` into `target` with `color` (straight, non-premultiplied RGBA, alpha scales coverage), compositing
/// source-over. Scanline algorithm with an edge table and active edge list (the notes); when antialias is set each
/// pixel's coverage is its area fraction inside the path. Throws nothing; contours with < 3 points add nothing.
void fill_path(ImageRGBA& target, const Path& path, FillRule rule, const Vec4f& color, bool antialias);

/// The outline of a stroked polyline as a path to fill with FillRule::non_zero. A closed polyline gets joins all
/// around and no caps.
Path stroke_path(const std::vector<Vec2>& polyline, bool closed, const StrokeStyle& style);

}  // namespace tessera
