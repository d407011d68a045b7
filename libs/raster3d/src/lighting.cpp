#include "tessera/raster3d/lighting.hpp"

#include <algorithm>
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
// pow otherwise. F is float or lanes::Float: the same operations on each lane.
template <class F>
F specular_power(const F& x, float e) {
  if (e >= 0 && e <= 256 && e == std::floor(e)) {
    F result(1.0f), base = x;
    for (auto n = unsigned(e); n; n >>= 1, base = base * base)
      if (n & 1) result = result * base;
    return result;
  }
  using std::pow;
  return pow(x, F(e));
}

// The scalar forms of the lane operations shade_any uses (lanes.hpp has the lane forms).
bool any(bool b) { return b; }
template <class T>
T select(bool m, const T& a, const T& b) {
  return m ? a : b;
}
float max(float a, float b) { return std::max(a, b); }
Vec3f clamp(const Vec3f& x, float lo, float hi) { return glm::clamp(x, lo, hi); }

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

template <class F, class V3>
V3 PreparedLighting::shade_any(const V3& n, const V3& p, const V3& color, std::span<const F> visibility) const {
  const V3 ambient_m = color_material_ ? color : V3(ambient_m_);
  V3 c = V3(emission_) + ambient_m * V3(ambient_sum_);
  const V3 eye = local_viewer_ ? normalize(-p) : V3(Vec3f(0, 0, 1));
  for (int i = 0; i < light_count_; ++i) {
    const PreparedLight& light = lights_[size_t(i)];
    const V3 l = light.directional ? V3(light.direction) : normalize(V3(Vec3f(light.position)) - p);
    const F n_dot_l = dot(n, l);
    const F visible = size_t(i) < visibility.size() ? visibility[size_t(i)] : F(1.0f);
    // Lit where N.L > 0 and the light is visible (a lane's sums are exactly the scalar's: the others keep c).
    const auto lit = (n_dot_l > F(0.0f)) & (visible > F(0.0f));
    if (!any(lit)) continue;
    c = select(lit, c + visible * (n_dot_l * (color_material_ ? color * V3(light.diffuse) : V3(light.diffuse))), c);
    if (!light.has_specular) continue;
    F spec;
    if (blinn_) {
      const V3 h = light.directional && !local_viewer_ ? V3(light.half) : normalize(l + eye);
      spec = max(dot(n, h), F(0.0f));  // (H.N)
    } else {
      spec = max(dot(eye, F(2.0f) * n_dot_l * n - l), F(0.0f));  // (E.R), R = 2N(N.L) - L
    }
    c = select(lit, c + visible * (specular_power(spec, shininess_) * V3(light.specular)), c);
  }
  return clamp(c, 0.0f, 1.0f);
}

Vec3f PreparedLighting::shade(const Vec3f& n, const Vec3f& p, const Vec3f& color,
                              std::span<const float> visibility) const {
  return shade_any<float, Vec3f>(n, p, color, visibility);
}

lanes::vec3 PreparedLighting::shade(const lanes::vec3& n, const lanes::vec3& p, const lanes::vec3& color,
                                    std::span<const lanes::Float> visibility) const {
  return shade_any<lanes::Float, lanes::vec3>(n, p, color, visibility);
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
