#include "tessera/color/srgb.hpp"

#include <algorithm>
#include <cmath>

namespace tessera {

float srgb_encode(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded) {
  const float v = std::clamp(encoded, 0.0f, 1.0f);
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 srgb_encode(const glm::vec3& linear) {
  return {srgb_encode(linear.x), srgb_encode(linear.y), srgb_encode(linear.z)};
}

glm::vec3 srgb_decode(const glm::vec3& encoded) {
  return {srgb_decode(encoded.x), srgb_decode(encoded.y), srgb_decode(encoded.z)};
}

}  // namespace tessera
