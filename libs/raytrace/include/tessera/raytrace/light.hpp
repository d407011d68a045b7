#pragma once
// Light sources: the notes' point light (no falloff, as in C = C_L C_r (N . L)), directional lights, and area lights
// (rectangle, disk, sphere) that are sampled as many point lights for soft shadows ("Soft Shadows").
#include "tessera/math/types.hpp"

namespace tessera {

/// The kinds of light.
enum class LightType { point, directional, rect, disk, sphere };

/// A light source of color C_L. Area lights are one-sided (rect and disk shine along their normal).
struct Light {
  LightType type = LightType::point;
  Vec3f color{1.0f};          ///< C_L
  Vec3f position{0.0f};       ///< point: the position; rect: a corner; disk and sphere: the center
  Vec3f direction{0, -1, 0};  ///< directional: the direction the light travels; disk: the normal it shines along
  Vec3f edge_u{1, 0, 0};      ///< rect: the two edges from the corner; it shines along edge_u x edge_v
  Vec3f edge_v{0, 0, 1};
  float radius = 0.5f;  ///< disk and sphere
  int samples = 1;      ///< shadow rays per shading point (area lights), stratified
  bool visible = true;  ///< area lights: seen by eye and reflected rays as a surface of color `color`

  /// True for rect, disk and sphere.
  bool is_area() const { return type == LightType::rect || type == LightType::disk || type == LightType::sphere; }
};

/// One sample of a light seen from a shading point: unit direction toward the light, distance (infinity for a
/// directional light) and the color arriving along it (0 when the point is behind a one-sided light).
struct LightSample {
  Vec3f dir{0.0f};
  float distance = 0.0f;
  Vec3f color{0.0f};
};

/// The sample of a light at point q seen from p: unit direction toward q (by one reciprocal), distance and `color`; no
/// direction and no color when p is at q. The point light's sample and the tail of every area light's.
inline LightSample light_toward(const Vec3f& q, const Vec3f& p, const Vec3f& color) {
  LightSample s;
  const Vec3f d = q - p;
  s.distance = glm::length(d);
  if (!(s.distance > 0.0f)) return s;
  s.dir = d * (1.0f / s.distance);
  s.color = color;
  return s;
}

/// Samples `light` from point `p` with a 2D number u in [0, 1)^2: a uniform point on the rectangle or disk, a uniform
/// direction in the cone the sphere subtends (so the point lies on the side facing p); u is ignored for point and
/// directional lights.
LightSample sample_light(const Light& light, const Vec3f& p, const Vec2f& u);

}  // namespace tessera
