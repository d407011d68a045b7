#include "tessera/raster3d/lighting.hpp"

#include <cmath>

namespace tessera::raster3d {

Material Material::plastic(const Vec3f& color, float shininess, float specular) {
  Material m;
  m.ambient = color;
  m.diffuse = color;
  m.specular = Vec3f(specular);
  m.shininess = shininess;
  return m;
}

Material Material::metal(const Vec3f& color, float shininess) {
  Material m = plastic(color, shininess);
  m.specular = color;
  return m;
}

namespace {

// x^e for x in [0, 1]: by repeated squaring for the usual integer exponents (a few multiplies instead of powf),
// std::pow otherwise.
float specular_power(float x, float e) {
  if (e >= 0 && e <= 256 && e == std::floor(e)) {
    float result = 1, base = x;
    for (auto n = unsigned(e); n; n >>= 1, base *= base)
      if (n & 1) result *= base;
    return result;
  }
  return std::pow(x, e);
}

}  // namespace

PreparedLighting::PreparedLighting(const Lighting& lighting)
    : emission_(lighting.material.emission),
      ambient_m_(lighting.material.ambient),
      ambient_sum_(lighting.model_ambient),
      shininess_(lighting.material.shininess),
      color_material_(lighting.color_material),
      local_viewer_(lighting.local_viewer),
      blinn_(lighting.specular_model == SpecularModel::blinn) {
  const Material& m = lighting.material;
  for (int i = 0; i < lighting.light_count; ++i) {
    const Light& light = lighting.lights[size_t(i)];
    PreparedLight& p = lights_[size_t(light_count_++)];
    p.position = light.position;
    p.directional = light.position.w == 0;
    p.direction = p.directional ? glm::normalize(Vec3f(light.position)) : Vec3f(0);
    p.half = glm::normalize(p.direction + Vec3f(0, 0, 1));
    p.diffuse = color_material_ ? light.diffuse : m.diffuse * light.diffuse;
    p.specular = m.specular * light.specular;
    p.has_specular = p.specular != Vec3f(0);  // else the term adds exactly 0: skip the power
    ambient_sum_ += light.ambient;
  }
}

Vec3f PreparedLighting::shade(const Vec3f& n, const Vec3f& p, const Vec3f& color,
                              std::span<const float> visibility) const {
  const Vec3f ambient_m = color_material_ ? color : ambient_m_;
  Vec3f c = emission_ + ambient_m * ambient_sum_;
  const Vec3f eye = local_viewer_ ? glm::normalize(-p) : Vec3f(0, 0, 1);
  for (int i = 0; i < light_count_; ++i) {
    const PreparedLight& light = lights_[size_t(i)];
    const Vec3f l = light.directional ? light.direction : glm::normalize(Vec3f(light.position) - p);
    const float n_dot_l = glm::dot(n, l);
    const float visible = size_t(i) < visibility.size() ? visibility[size_t(i)] : 1.0f;
    if (n_dot_l <= 0 || visible <= 0) continue;
    // Times 1 unless in shadow: exactly the unshadowed sums then.
    c += visible * (n_dot_l * (color_material_ ? color * light.diffuse : light.diffuse));
    if (!light.has_specular) continue;
    float spec;
    if (blinn_) {
      const Vec3f h = light.directional && !local_viewer_ ? light.half : glm::normalize(l + eye);
      spec = std::max(glm::dot(n, h), 0.0f);  // (H.N)
    } else {
      spec = std::max(glm::dot(eye, 2.0f * n_dot_l * n - l), 0.0f);  // (E.R), R = 2N(N.L) - L
    }
    c += visible * (specular_power(spec, shininess_) * light.specular);
  }
  return glm::clamp(c, 0.0f, 1.0f);
}

Lighting unlit_lighting() {
  Lighting l;
  l.light_count = 0;
  l.color_material = true;
  l.model_ambient = Vec3f(1);
  return l;
}

Vec3f shade(const Lighting& lighting, const Vec3f& n, const Vec3f& p, const Vec3f& color) {
  return PreparedLighting(lighting).shade(n, p, color);
}

}  // namespace tessera::raster3d
