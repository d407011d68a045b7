#include <algorithm>

#include "tessera/raster2d/blend.hpp"
#include "tessera/raster2d/path.hpp"
#include "tessera/raster2d/scanline.hpp"

namespace tessera {

void fill_path(ImageRGBA& target, const Path& path, FillRule rule, const Vec4f& color, bool antialias) {
  if (!(color.w > 0.0f)) return;  // source-over with zero alpha changes nothing
  const Vec4f opaque(color.x, color.y, color.z, 1.0f);
  scan_path(path, rule, target.width(), target.height(), antialias, [&](int y, int x0, int x1, const float* coverage) {
    Vec4f* row = target.row(y);
    if (coverage) {
      for (int x = x0; x < x1; ++x) row[x] = blend_over(row[x], color, coverage[x - x0]);
    } else if (color.w >= 1.0f) {
      std::fill(row + x0, row + x1, opaque);
    } else {
      for (int x = x0; x < x1; ++x) row[x] = blend_over(row[x], color);
    }
  });
}

}  // namespace tessera
