#pragma once
// The sRGB transfer curve (IEC 61966-2-1): linear light <-> encoded values, both in [0, 1].
#include <glm/glm.hpp>

namespace tessera {

/// Encodes linear light with the sRGB curve: 12.92 v below 0.0031308, else 1.055 v^(1/2.4) - 0.055. Clamps to [0,1].
/// Source: IEC 61966-2-1:1999, section 5.2.
float srgb_encode(float linear);
/// Decodes an sRGB value to linear light: v/12.92 below 0.04045, else ((v + 0.055)/1.055)^2.4. Clamps to [0,1].
float srgb_decode(float encoded);
/// Double-precision versions (the color-model conversions use these); same curve, same clamping.
double srgb_encode(double linear);
double srgb_decode(double encoded);
/// Per-channel versions.
glm::vec3 srgb_encode(const glm::vec3& linear);
glm::vec3 srgb_decode(const glm::vec3& encoded);
glm::dvec3 srgb_encode(const glm::dvec3& linear);
glm::dvec3 srgb_decode(const glm::dvec3& encoded);

}  // namespace tessera
