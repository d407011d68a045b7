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

Vec3f shade(const Lighting& lighting, const Vec3f& n, const Vec3f& p, const Vec3f& color) {
  const Material& m = lighting.material;
  const Vec3f ambient_m = lighting.color_material ? color : m.ambient;
  const Vec3f diffuse_m = lighting.color_material ? color : m.diffuse;
  const Vec3f eye = lighting.local_viewer ? glm::normalize(-p) : Vec3f(0, 0, 1);
  Vec3f c = m.emission + ambient_m * lighting.model_ambient;
  for (int i = 0; i < lighting.light_count; ++i) {
    const Light& light = lighting.lights[size_t(i)];
    const Vec3f l = glm::normalize(light.position.w == 0 ? Vec3f(light.position) : Vec3f(light.position) - p);
    c += ambient_m * light.ambient;
    const float n_dot_l = glm::dot(n, l);
    if (n_dot_l <= 0) continue;
    c += n_dot_l * diffuse_m * light.diffuse;
    const Vec3f specular = m.specular * light.specular;
    if (specular == Vec3f(0)) continue;  // adds exactly 0: skip the power
    float spec;
    if (lighting.specular_model == SpecularModel::blinn) {
      spec = std::max(glm::dot(n, glm::normalize(l + eye)), 0.0f);  // (H.N)
    } else {
      spec = std::max(glm::dot(eye, 2.0f * n_dot_l * n - l), 0.0f);  // (E.R), R = 2N(N.L) - L
    }
    c += specular_power(spec, m.shininess) * specular;
  }
  return glm::clamp(c, 0.0f, 1.0f);
}

}  // namespace tessera::raster3d
