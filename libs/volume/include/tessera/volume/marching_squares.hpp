#pragma once
// Marching squares (the notes' 2D example): contour lines of a scalar field sampled on a grid.
#include <filesystem>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// A contour line in pixel coordinates of the field (sample (i, j) at point (i, j)).
struct Polyline {
  std::vector<Vec2> points;
  bool closed = false;  ///< the last point connects back to the first
};

/// The iso-lines value == iso of `field`. Inside is value >= iso; cut points are interpolated linearly along cell
/// edges (clamped off the samples as in marching cubes); saddle cells are resolved by the cell's center value (the
/// mean of its corners): inside connects the inside corners. Segments are chained into polylines.
std::vector<Polyline> marching_squares(const DepthImage& field, float iso);

/// Writes contours as an SVG of the field's size times `scale`, over an optional gray rendering of the field (atomic).
void write_contours_svg(const std::filesystem::path& path, const std::vector<Polyline>& contours, int width, int height,
                        double scale = 4.0);

}  // namespace tessera
