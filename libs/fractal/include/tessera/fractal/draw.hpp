#pragma once
// Pictures of the self-similar fractals: geometry in a window of the plane (y up) drawn with the raster2d back end
// (scanline fill of paths, strokes), and the binary masks that box counting measures.
#include <cstdint>
#include <vector>

#include "tessera/fractal/self_similar.hpp"
#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// Where the geometry lands: `window` of the plane (y up) maps onto the picture inside a margin (y down).
struct PictureFrame {
  int width = 512;                  ///< pixels (> 0)
  int height = 512;                 ///< pixels (> 0)
  double margin = 0;                ///< pixels left free on every side (>= 0)
  Rect window{0.0, 0.0, 1.0, 1.0};  ///< the part of the plane shown, stretched to fill the picture
};

/// Colors and coverage of a fractal picture.
struct DrawStyle {
  Vec3f ink{0.0f, 0.0f, 0.0f};    ///< shapes and curves
  Vec3f paper{1.0f, 1.0f, 1.0f};  ///< background
  double line_width = 1;          ///< curve width in pixels (> 0)
  bool antialias = false;         ///< area coverage; without it a pixel is ink iff its center is (exact for masks)
};

/// A frame whose window holds every point with equal scale in x and y (centered, the picture's aspect kept), inside
/// `margin` pixels. Throws InvalidInput when there are no points or the picture is too small for the margin.
PictureFrame frame_around(const std::vector<Vec2>& points, int width, int height, double margin);

/// The pixel position of plane point p. Throws nothing.
Vec2 to_pixels(const PictureFrame& frame, Vec2 p);

/// Rectangles and triangles as polygons (counterclockwise), ready for draw_polygons().
std::vector<std::vector<Vec2>> as_polygons(const std::vector<Rect>& rects);
std::vector<std::vector<Vec2>> as_polygons(const std::vector<Triangle2>& triangles);

/// Fills polygons (nonzero rule) in ink on paper. Throws InvalidInput for a bad frame.
ImageRGBA draw_polygons(const std::vector<std::vector<Vec2>>& polygons, const PictureFrame& frame,
                        const DrawStyle& style = {});

/// Strokes a polyline (closed: back to its first point) in ink on paper, with round joins.
/// Throws InvalidInput for a bad frame or line width.
ImageRGBA draw_curve(const std::vector<Vec2>& polyline, bool closed, const PictureFrame& frame,
                     const DrawStyle& style = {});

/// Adds more polygons or a curve to an existing picture in `color` (for overlays of several levels).
void add_polygons(ImageRGBA& picture, const std::vector<std::vector<Vec2>>& polygons, const PictureFrame& frame,
                  const Vec3f& color, bool antialias);
void add_curve(ImageRGBA& picture, const std::vector<Vec2>& polyline, bool closed, const PictureFrame& frame,
               const Vec3f& color, double line_width, bool antialias);

/// The binary mask of a picture: 1 where the luminance (Rec. 709 weights) is below `threshold` (dark ink on light
/// paper), else 0; `invert` swaps the two (light on dark). Transparency is paper: a pixel of alpha a is seen over
/// white paper (black with `invert`), so a transparent background (RGBA 0,0,0,0, as canvas render writes) is no ink.
Image<uint8_t> ink_mask(const ImageRGBA& picture, float threshold = 0.5f, bool invert = false);

}  // namespace tessera
