// Reflection, refraction, Fresnel and light sampling.
#include <cmath>

#include "tessera/math/frame.hpp"
#include "tessera/raytrace/light.hpp"
#include "tessera/raytrace/material.hpp"
#include "tessera/raytrace/sampling.hpp"

namespace tessera {

float glossy_exponent(float glossiness) { return glossiness > 0 ? 1.0f / (glossiness * glossiness) : 0.0f; }

std::optional<Vec3f> refract_dir(const Vec3f& d, const Vec3f& n, float eta) {
  const float cos_i = -glm::dot(d, n);
  const float sin2_t = eta * eta * std::max(0.0f, 1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return std::nullopt;  // total internal reflection
  return eta * d + (eta * cos_i - std::sqrt(1.0f - sin2_t)) * n;
}

double critical_angle(double n1, double n2) { return std::asin(n2 / n1); }

float schlick_fresnel(float cos_i, float n1, float n2) {
  float cos_theta = cos_i;
  if (n1 > n2) {  // going into the thinner medium, Schlick's formula takes the transmitted angle
    const float eta = n1 / n2;
    const float sin2_t = eta * eta * std::max(0.0f, 1.0f - cos_i * cos_i);
    if (sin2_t >= 1.0f) return 1.0f;
    cos_theta = std::sqrt(1.0f - sin2_t);
  }
  const float r0 = ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
  const float m = 1.0f - cos_theta;
  return r0 + (1.0f - r0) * m * m * m * m * m;
}

LightSample sample_light(const Light& light, const Vec3f& p, const Vec2f& u) {
  LightSample s;
  Vec3f q;             // the sampled point on the light
  Vec3f facing{0.0f};  // one-sided lights shine along this normal
  switch (light.type) {
    case LightType::directional:
      s.dir = -glm::normalize(light.direction);
      s.distance = std::numeric_limits<float>::infinity();
      s.color = light.color;
      return s;
    case LightType::point:
      q = light.position;
      break;
    case LightType::rect:
      q = light.position + u.x * light.edge_u + u.y * light.edge_v;
      facing = glm::normalize(glm::cross(light.edge_u, light.edge_v));
      break;
    case LightType::disk: {
      const Frame f = Frame::from_normal(glm::normalize(light.direction));
      const Vec2f d = sample_disk(u) * light.radius;
      q = light.position + d.x * f.s + d.y * f.t;
      facing = f.n;
      break;
    }
    case LightType::sphere: {
      // A uniform direction in the cone of half-angle asin(r / |c - p|), then its nearest point on the sphere.
      const Vec3f to_c = light.position - p;
      const float dist = glm::length(to_c);
      if (dist <= light.radius) {
        q = light.position;
        break;
      }
      const float sin_max = light.radius / dist, cos_max = std::sqrt(std::max(0.0f, 1.0f - sin_max * sin_max));
      const float cos_t = 1.0f - u.x * (1.0f - cos_max), sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
      const float phi = 2.0f * float(kPi) * u.y;
      const Frame f = Frame::from_normal(to_c / dist);
      const Vec3f dir = f.to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t});
      // Nearest root of |p + t dir - c| = r (clamped discriminant: the cone's rim is tangent).
      const float b = glm::dot(dir, to_c);
      const float t = b - std::sqrt(std::max(0.0f, b * b - (dist * dist - light.radius * light.radius)));
      q = p + t * dir;
      break;
    }
  }
  s = light_toward(q, p, light.color);
  if (facing != Vec3f(0.0f) && !(glm::dot(facing, -s.dir) > 0.0f)) s.color = Vec3f(0.0f);
  return s;
}

}  // namespace tessera
