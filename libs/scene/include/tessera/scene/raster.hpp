#pragma once
// Driving the rasterizer (raster3d) from a scene description: every object tessellated into triangles and drawn with
// the z-buffer and per-pixel (Phong-interpolated) OpenGL lighting, with the first light's shadows from a shadow map
// (the notes' 2-pass z-buffer). No reflections, refraction or distribution effects (those need the ray tracer).
#include "tessera/image/image.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera {

/// Triangles approximating a shape in its own coordinates (`segments` around curved shapes; an infinite plane becomes
/// a square of side `plane_size` about its point). Flat faces carry their face normal, curved surfaces smooth normals.
TriMesh tessellate(const Shape& shape, int segments = 48, double plane_size = 3000);

/// Rasterizes the scene at width x height: the camera's perspective (near 0.05, far 4000), its lights (area lights as
/// point lights at their centers; at most 8), each material's color, ambient, highlight and emission (a checkerboard
/// shows its first color), the background as the clear color. The first light casts hard shadows through a
/// 2048 x 2048 shadow map fitted to the objects that cast shadows (planes, being infinite, only receive them); a
/// point light inside those objects' bounding sphere casts none.
ImageRGB rasterize_scene(const Scene& scene, int width, int height);

}  // namespace tessera
