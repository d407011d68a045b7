#pragma once
// The scanline rasterizer behind fill_path: turns a Path into horizontal spans of pixel coverage.
//
// Aliased mode is the notes' polygon rasterization: an edge table sorted by first scanline, an active edge list whose
// x intersections advance by dx/dy per scanline, spans filled between sorted intersections under the even-odd or
// nonzero rule. A pixel is in when its center (x + 0.5, y + 0.5) is: half-open, an intersection at x_s starts a span
// at the first center >= x_s and one at x_e ends it before the first center >= x_e; an edge spanning y0 <= y < y1
// meets the scanlines whose centers lie in [y0, y1). Abutting shapes that share an edge never share a pixel.
//
// Antialiased mode computes each pixel's exact area coverage: every edge deposits its signed area and cover into an
// accumulation row per cell (the method of font rasterizers such as libart, FreeType's "gray" and font-rs); a running
// sum along the row gives the winding-weighted coverage, folded by the fill rule (nonzero: min(|c|, 1); even-odd:
// distance of |c| to the nearest even integer). It is exact wherever contours do not cross inside a pixel.
//
// Rows are processed in fixed bands of kScanBandHeight rows in parallel (oneTBB); every band's result depends only on
// the band, so the output is identical for any thread count.
#include <functional>

#include "tessera/raster2d/path.hpp"

namespace tessera {

/// Rows per parallel band of the scanline rasterizer (fixed, so results do not depend on the thread count).
inline constexpr int kScanBandHeight = 32;

/// Receives the pixels [x0, x1) of row y (0 <= x0 < x1 <= width). `coverage` is null when every pixel of the span is
/// fully covered, else it points at x1 - x0 coverages in (0, 1]. Called concurrently for different rows, never twice
/// at once for the same row; the spans of one row arrive left to right and never overlap.
using SpanSink = std::function<void(int y, int x0, int x1, const float* coverage)>;

/// Rasterizes `path` (device pixel coordinates) clipped to [0, width) x [0, height) and hands its spans to `sink`.
/// Contours with fewer than 3 points and non-finite points are ignored. Throws nothing itself (rethrows the sink's
/// exceptions). Method: see the header comment (the notes' scanline fill; area coverage when antialias).
void scan_path(const Path& path, FillRule rule, int width, int height, bool antialias, const SpanSink& sink);

}  // namespace tessera
