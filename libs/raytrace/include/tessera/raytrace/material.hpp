#pragma once
// The notes' surface model ("Surface Shading", "Recursive Ray Tracing", "Transparent Surfaces"): ambient + diffuse +
// specular (Phong or Blinn) per light, mirror reflection weighted by K_refl, transmission weighted by K_trans with
// Snell's law, and the optical helpers they need (reflect, refract, Schlick's Fresnel approximation).
#include <memory>
#include <optional>

#include "tessera/math/types.hpp"

namespace tessera {

class Texture2D;

/// The notes' index-of-refraction table (speed of light in vacuum / speed of light in the material).
namespace ior {
inline constexpr float kVacuum = 1.0f;
inline constexpr float kAir = 1.0003f;
inline constexpr float kWater = 1.33f;
inline constexpr float kGlass = 1.5f;
inline constexpr float kIce = 1.3f;
inline constexpr float kDiamond = 2.4f;
}  // namespace ior

/// Which highlight term the specular coefficient multiplies.
enum class SpecularModel {
  phong,  ///< (E . R)^P with R = 2 N (N . L) - L
  blinn,  ///< (N . H)^P with H = (L + E) / |L + E|
};

/// A surface: the notes' coefficients as RGB colors. Defaults give a matte white surface.
struct Material {
  Vec3f diffuse{0.8f};      ///< the surface color C_r: C = C_r (ambient C_a + sum of C_L (N . L)) + ...
  Vec3f ambient{1.0f};      ///< weight of the scene's ambient light C_a (the notes' "indirect illumination cheat")
  Vec3f specular{0.0f};     ///< the highlight color, multiplies C_L (E . R)^P or (N . H)^P
  float shininess = 32.0f;  ///< the specular exponent P
  SpecularModel model = SpecularModel::phong;
  Vec3f reflection{0.0f};     ///< K_refl: weight of the mirror-reflected ray
  Vec3f transmission{0.0f};   ///< K_trans: weight of the refracted ray
  float ior = ior::kGlass;    ///< index of refraction of the inside (the outside is vacuum, index 1)
  bool fresnel = false;       ///< Schlick's Fresnel term moves weight from transmission to reflection at grazing angles
  float glossiness = 0.0f;    ///< 0: perfect mirror; > 0: reflected rays spread in a Phong lobe of exponent 1/g^2
  Vec3f emission{0.0f};       ///< light the surface gives off by itself (seen directly and in reflections)
  float checker = 0.0f;       ///< > 0: a 3D checkerboard of this cell size alternating diffuse and checker_color
  Vec3f checker_color{0.0f};  ///< the second checkerboard color
  std::shared_ptr<const Texture2D> texture;  ///< when set, its color at the hit's uv multiplies C_r
};

/// The lobe exponent used for glossy reflection, 1 / glossiness^2 (0 for a perfect mirror).
float glossy_exponent(float glossiness);

/// The notes' mirror direction R = 2 (N . E) N - E for unit N and unit E pointing away from the surface.
inline Vec3f reflect_dir(const Vec3f& e, const Vec3f& n) { return 2.0f * glm::dot(n, e) * n - e; }

/// Snell's law sin t1 / sin t2 = n2 / n1 for the unit incoming direction d and the unit normal n on d's side
/// (dot(d, n) <= 0), with eta = n1 / n2. Returns the refracted direction, or nothing for total internal reflection
/// (sin t2 >= 1). It is unit within float rounding without normalizing: |eta d + (eta cos t1 - cos t2) n|^2 =
/// eta^2 sin^2 t1 + cos^2 t2 = 1.
std::optional<Vec3f> refract_dir(const Vec3f& d, const Vec3f& n, float eta);

/// The critical angle asin(n2 / n1) beyond which light going from index n1 into n2 < n1 is totally reflected.
double critical_angle(double n1, double n2);

/// Schlick's approximation of the Fresnel reflectance for light going from index n1 into n2; cos_i is the cosine of
/// the incident angle. Uses the transmitted angle's cosine when n1 > n2 and returns 1 under total internal reflection.
float schlick_fresnel(float cos_i, float n1, float n2);

}  // namespace tessera
