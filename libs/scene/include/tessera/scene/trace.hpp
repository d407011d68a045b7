#pragma once
// Driving the ray tracer from a scene description.
#include "tessera/raytrace/render.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera {

/// The ray tracer's view of a scene: world built (with visible area lights), materials indexed, camera set. Throws
/// InvalidInput for an object naming an unknown material.
RayScene to_ray_scene(const Scene& scene);

/// The scene's image settings as render settings (size, samples, depth).
RenderSettings render_settings(const Scene& scene);

}  // namespace tessera
