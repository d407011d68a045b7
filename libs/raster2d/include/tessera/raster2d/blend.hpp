#pragma once
// Source-over compositing of straight (non-premultiplied) RGBA colors: what every raster2d write ends in.
#include "tessera/math/types.hpp"

namespace tessera {

/// Composites `src` (straight RGBA in [0, 1]) over `dst` (straight RGBA) with the source alpha scaled by `coverage`
/// (in [0, 1]): a = src.w * coverage, out.a = a + dst.a (1 - a), out.rgb = (src.rgb a + dst.rgb dst.a (1 - a)) / out.a
/// (Porter-Duff "over"). Returns dst unchanged when a <= 0 and src (alpha 1) when a >= 1.
inline Vec4f blend_over(const Vec4f& dst, const Vec4f& src, float coverage = 1.0f) {
  const float a = src.w * coverage;
  if (a <= 0.0f) return dst;
  if (a >= 1.0f) return Vec4f(src.x, src.y, src.z, 1.0f);
  const float keep = dst.w * (1.0f - a);
  const float out_a = a + keep;
  const Vec3f rgb = (Vec3f(src) * a + Vec3f(dst) * keep) / out_a;
  return Vec4f(rgb, out_a);
}

}  // namespace tessera
