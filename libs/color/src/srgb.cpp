#include "tessera/color/srgb.hpp"

#include <algorithm>
#include <cmath>

namespace tessera {
namespace {
// One definition of the curve for float and double (IEC 61966-2-1 section 5.2).
template <class T>
T encode(T linear) {
  const T v = std::clamp(linear, T(0), T(1));
  if (v <= T(0.0031308)) return T(12.92) * v;
  // 1.055 p - 0.055 written as p + 0.055 (p - 1), so that white stays exactly 1 in floating point.
  const T p = std::pow(v, T(1) / T(2.4));
  return p + T(0.055) * (p - T(1));
}

template <class T>
T decode(T encoded) {
  const T v = std::clamp(encoded, T(0), T(1));
  return v <= T(0.04045) ? v / T(12.92) : std::pow((v + T(0.055)) / T(1.055), T(2.4));
}
}  // namespace

float srgb_encode(float linear) { return encode(linear); }
float srgb_decode(float encoded) { return decode(encoded); }
double srgb_encode(double linear) { return encode(linear); }
double srgb_decode(double encoded) { return decode(encoded); }

glm::vec3 srgb_encode(const glm::vec3& linear) { return {encode(linear.x), encode(linear.y), encode(linear.z)}; }
glm::vec3 srgb_decode(const glm::vec3& encoded) { return {decode(encoded.x), decode(encoded.y), decode(encoded.z)}; }
glm::dvec3 srgb_encode(const glm::dvec3& linear) { return {encode(linear.x), encode(linear.y), encode(linear.z)}; }
glm::dvec3 srgb_decode(const glm::dvec3& encoded) { return {decode(encoded.x), decode(encoded.y), decode(encoded.z)}; }

}  // namespace tessera
