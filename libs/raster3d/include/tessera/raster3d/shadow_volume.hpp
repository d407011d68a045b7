#pragma once
// Shadow volumes, the notes' first way to shadows with rasterization (Crow 1977; counted in the stencil buffer,
// Heidmann 1991). The region a caster hides from a light is bounded by the caster's light-facing triangles and by
// its silhouette edges extruded away from the light to infinity. A visible point is in shadow when a ray from the eye
// to it enters more of these volumes than it leaves: the stencil buffer counts the crossings per pixel, and the lit
// pass draws only where the count is 0. Unlike a shadow map, the shadow is exact to the pixel at any distance (no
// resolution, no bias), at the price of drawing the volumes' large polygons.
#include <functional>
#include <span>
#include <vector>

#include "tessera/math/types.hpp"
#include "tessera/raster3d/framebuffer.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d {

/// The shadow volume of one caster for one light, in world space.
struct ShadowVolume {
  /// Homogeneous positions: the caster's vertices (w = 1), then the same vertices projected to infinity away from
  /// the light (w = 0).
  std::vector<Vec4f> positions;
  /// The extruded silhouette: two triangles per silhouette edge, counterclockwise seen from outside the volume.
  std::vector<uint32_t> sides;
  /// The near cap (the light-facing triangles) and the far cap (the same at infinity, reversed), which z-fail
  /// counting needs: with them the volume is closed.
  std::vector<uint32_t> caps;
};

/// The shadow volume of the triangles `indices` (3 per triangle, counterclockwise seen from outside) over world
/// `positions`, for a light given homogeneously: (p, 1) a point light at p, (d, 0) a directional light shining along
/// -d. A triangle faces the light when its plane has the light strictly on its front side.
///
/// The silhouette is the boundary of the light-facing triangles: each directed edge of a facing triangle counts +1,
/// its reverse -1, and an edge whose count m is not 0 is extruded |m| times, turned by the sign. On a closed manifold
/// mesh these are exactly the edges between a facing and a non-facing triangle. On an open or non-manifold mesh (the
/// bunny's holes) the volume is still closed: it is the union of the facing triangles' own volumes, so the mesh
/// shadows as its light-facing triangles do. Throws InvalidInput for an index out of range or a light with
/// non-finite coordinates or (0, 0, 0, 0).
ShadowVolume shadow_volume(std::span<const Vec3f> positions, std::span<const uint32_t> indices, const Vec4f& light);

/// How the stencil buffer counts the volumes a line of sight crosses in front of the visible surface.
enum class ShadowCount {
  /// z-pass (Heidmann 1991): +1 for each front face in front of the surface, -1 for each back face. No caps needed,
  /// but wrong wherever the eye is itself in shadow (the near plane cuts the volume open).
  zpass,
  /// z-fail (Carmack 2000; Everitt and Kilgard 2002): +1 for each back face behind the surface, -1 for each front
  /// face behind it, with the caps. Right wherever the eye is; needs a projection that keeps the far cap, at
  /// infinity, in the clip volume (infinite_perspective).
  zfail,
};

/// Adds `volume`'s crossings to the stencil buffer (incrementing and decrementing with wrap-around, so that counts of
/// up to 255 overlapping volumes are exact): its triangles drawn with `view_projection` (world to clip space),
/// depth-tested (less) against the depth buffer, writing neither depth nor color. `state` gives the viewport.
/// Throws InvalidInput for zfail with a projection that does not map points at infinity in front of the camera onto
/// the far plane (its third and fourth rows must agree in z and be 0 in w, as infinite_perspective's are).
DrawStats draw_shadow_volume(Framebuffer& framebuffer, const RasterState& state, const ShadowVolume& volume,
                             const Mat4f& view_projection, ShadowCount count);

/// The notes' shadows by shadow volumes for light 0, in three passes over the depth buffer the caller has cleared:
/// `draw(state, 0)` draws the scene with light 0 off (writing depth); the volumes are counted into the stencil buffer
/// (cleared to 0 first); `draw(state, 1)` draws the scene again with light 0 on where the count is 0 (depth func
/// equal: the same vertex shader gives the same depths, so exactly the visible surface is redrawn). `draw` must use
/// the state it gets (it may change culling or flat shading; both calls must draw the same geometry).
void draw_with_shadow_volumes(Framebuffer& framebuffer, std::span<const ShadowVolume> volumes,
                              const Mat4f& view_projection, ShadowCount count,
                              const std::function<void(const RasterState& state, float light0)>& draw);

/// Shadow volumes for several lights, as GPUs draw them (one stencil count and one additive pass per light):
/// `draw(state, -1)` draws the scene lit by what casts no shadow (ambient, emission, lights without volumes), writing
/// depth; then for each light i, its casters' volumes `volumes[i]` are counted into the stencil buffer (cleared to 0
/// first) and `draw(state, i)` adds light i's own contribution (its diffuse and specular terms alone) where the count
/// is 0: depth func equal, blending (one, one), so that the passes sum (in 8 bits, saturating, as on a GPU). `draw`
/// must use the state it gets and draw the same geometry in every pass.
void draw_lights_with_shadow_volumes(Framebuffer& framebuffer, std::span<const std::vector<ShadowVolume>> volumes,
                                     const Mat4f& view_projection, ShadowCount count,
                                     const std::function<void(const RasterState& state, int light)>& draw);

}  // namespace tessera::raster3d
