// The lane shaders' texture lookup (lanes.hpp): a level of detail per quad, then Texture2D::sample_lanes.
#include "tessera/raster3d/lanes.hpp"

#include "tessera/image/texture.hpp"

namespace tessera::raster3d::lanes {

vec4 texture(const Texture2D& t, const vec2& uv) {
  alignas(32) float u[kWidth], v[kWidth], lod[kWidth];
  uv.x.store(u);
  uv.y.store(v);
  for (int q = 0; q < kWidth; q += 4) {
    const float level = t.lod({u[q + 1] - u[q], v[q + 1] - v[q]}, {u[q + 2] - u[q], v[q + 2] - v[q]});
    for (int k = q; k < q + 4; ++k) lod[k] = level;
  }
  alignas(32) float rgba[4][kWidth];
  float* const out[4] = {rgba[0], rgba[1], rgba[2], rgba[3]};
  t.sample_lanes(u, v, lod, out, kWidth);
  return {Float::load(rgba[0]), Float::load(rgba[1]), Float::load(rgba[2]), Float::load(rgba[3])};
}

}  // namespace tessera::raster3d::lanes
