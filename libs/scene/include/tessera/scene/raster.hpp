#pragma once
// Driving the rasterizer (raster3d) from a scene description: every object tessellated into triangles and drawn with
// the z-buffer and per-pixel (Phong-interpolated) OpenGL lighting, with every light's hard shadows from shadow maps
// (the notes' 2-pass z-buffer) or from shadow volumes, the ray tracer's surface colors (checkerboards, textures) per
// pixel. Mirrors reflect a cube map of the scene drawn from their centers (one bounce) and glass is blended without
// refraction; no distribution effects (those need the ray tracer). docs/raytrace.md lists what differs.
#include "tessera/image/image.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera {

/// Triangles approximating a shape in its own coordinates (`segments` around curved shapes; an infinite plane becomes
/// a square of side `plane_size` about its point). Flat faces carry their face normal, curved surfaces smooth normals;
/// no texture coordinates (the rasterizer finds the shape's own at each pixel).
TriMesh tessellate(const Shape& shape, int segments = 48, double plane_size = 3000);

/// How the rasterizer draws shadows.
enum class RasterShadows {
  /// Every light's, through a shadow map per light fitted to the objects that cast shadows (the notes' 2-pass
  /// z-buffer): shadow_map_size squared (2048 x 2048 by default), or six faces of half that around a light inside
  /// those objects' bounding sphere (ShadowMap::point).
  map,
  /// Every light's, exact to the pixel, through shadow volumes counted z-fail in the stencil buffer (one additive
  /// pass per light; raster3d's draw_lights_with_shadow_volumes), for lights anywhere.
  volumes,
};

/// Rasterizes the scene at width x height: the camera's perspective (near 0.05, far 4000; at infinity with shadow
/// volumes) or orthographic projection, its lights (area lights as point lights at their centers, their surfaces
/// glowing where visible; at most 8), and per pixel each material's surface color as the ray tracer computes it (the
/// checkerboard's world-space cells, the texture at the ray tracer's uv), ambient, highlight and emission. Mirrors add
/// K_refl times the environment seen by the reflected view vector: a cube map of the other objects drawn from the
/// mirror's center (for a plane, from the eye's mirror image), one bounce deep, and the background beyond them.
/// Transparent materials (transmission) are blended over what lies behind them, sorted far to near (no refraction).
/// The background is the clear color. Shadows are hard, cast by the objects marked so (planes, being infinite, only
/// receive them), as `shadows` says. docs/raytrace.md lists what differs from the ray tracer. Throws InvalidInput for a
/// bad image size, a shadow_map_size outside [1, ShadowMap::kMaxSize] when the maps are drawn, or shadow volumes
/// under an orthographic camera (they need a perspective one).
ImageRGB rasterize_scene(const Scene& scene, int width, int height, RasterShadows shadows = RasterShadows::map,
                         int shadow_map_size = 2048);

}  // namespace tessera
