#pragma once
// The recursive ray tracer (Whitted's, the notes' "Recursive Ray Tracing") and its distribution extensions
// (antialiasing, soft shadows, glossy reflection, motion blur, depth of field), driven over image tiles in parallel.
//
// The color of a ray hitting a surface is the notes' sum
//   C = emission + ambient_light * ambient + sum over lights of C_L (diffuse (N . L) + specular highlight) visible(P,
//   L)
//       + K_refl C_reflected + K_trans C_transmitted,
// where an area light's term is the average over its shadow rays. Recursion stops at max_depth and when the product
// of the weights along the path falls below min_contribution (both of the notes' rules).
#include <cstdint>
#include <optional>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/raytrace/light.hpp"
#include "tessera/raytrace/material.hpp"
#include "tessera/raytrace/world.hpp"

namespace tessera {

/// Everything a render needs: geometry, materials (indexed by the objects), lights, camera and environment.
struct RayScene {
  World world;
  std::vector<Material> materials;
  std::vector<Light> lights;
  Camera camera;                ///< camera.aspect is replaced by the image's width / height
  float aperture = 0.0f;        ///< thin-lens radius (world units); 0 = pinhole
  float focal_distance = 0.0f;  ///< distance to the plane in focus; 0 = |center - eye|
  Vec3f ambient{0.1f};          ///< the ambient light C_a
  Vec3f background{0.0f};       ///< color of rays that leave the scene
};

/// How to render.
struct RenderSettings {
  int width = 512, height = 512;
  int samples = 1;                 ///< samples per pixel (stratified); each also samples time, lens, lights, gloss
  int max_depth = 5;               ///< eye ray = depth 1; no reflected or refracted ray beyond it; at most kMaxDepth
  float min_contribution = 1e-3f;  ///< stop a path whose weight (product of K's) is below this in every channel
  uint64_t seed = 0;               ///< the same seed gives the same picture for any thread count
  int tile_size = 16;              ///< pixels per tile side (parallel work unit)
  bool progress = true;            ///< progress bar with ETA on stderr (when it is a terminal)
  /// Render only the pixels [x0, x1) x [y0, y1) of the width x height frame (a tile of a split frame, render farms'
  /// crop window); each pixel is the one the whole frame would have, bit for bit. Empty: the whole frame.
  struct Window {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  std::optional<Window> window;
  /// The deepest recursion allowed (as in scene files): each level is a stack frame, and two facing mirrors would
  /// otherwise recurse until the stack overflows.
  static constexpr int kMaxDepth = 64;
};

/// What a render did.
struct RenderStats {
  uint64_t eye_rays = 0;  ///< primary rays
  uint64_t rays = 0;      ///< all rays: eye, reflected, refracted and shadow rays
  double seconds = 0;     ///< wall time of the render
};

/// The surface of an area light: its rectangle (corner, + edge_u, + edge_u + edge_v, + edge_v), disk or sphere. Throws
/// InvalidInput for a point or directional light, which has none.
Shape light_surface(const Light& light);

/// Adds the surface of every visible area light to the world (a rectangle, disk or sphere that emits the light's color
/// and casts no shadow), with one new emissive material each. Call before scene.world.build().
void add_light_surfaces(RayScene& scene);

/// The eye ray of a width x height image through image position (x + offset.x, y + offset.y) at `time`: the notes' eye
/// rays (as EyeRays, evaluated in float), then with an aperture the origin moves to `lens` (a point of [0, 1)^2 mapped
/// onto the aperture disk) and the direction aims at the pinhole ray's point on the focal plane.
Ray eye_ray(const RayScene& scene, int width, int height, int x, int y, const Vec2f& offset, const Vec2f& lens,
            float time);

/// The notes' 1/n sum visible(P, L_i) over n stratified samples of `light` seen from p (the visible fraction of an
/// area light; 0 or 1 for point and directional lights). `pattern` scrambles the samples.
float visible_fraction(const RayScene& scene, const Vec3f& p, const Light& light, int n, uint32_t pattern);

/// Renders the scene (or settings.window of it, an image of the window's size). Pixel (x, y)'s samples depend only
/// on (x, y), the settings and the seed, so the image is identical for any thread count and any split into windows.
/// Throws InvalidInput for a non-positive size or sample count, a max_depth outside [1, kMaxDepth], or an object whose
/// material index is out of range.
ImageRGB render(const RayScene& scene, const RenderSettings& settings, RenderStats* stats = nullptr);

/// The color seen along one ray (recursion and all), with `rng_sequence` selecting the random stream of the
/// distribution effects. For tests and tools that trace single rays.
Vec3f trace_ray(const RayScene& scene, const RenderSettings& settings, const Ray& ray, uint64_t rng_sequence = 0);

}  // namespace tessera
