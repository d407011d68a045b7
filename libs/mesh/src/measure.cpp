#include "tessera/mesh/measure.hpp"

#include <cmath>

#include "normal_scale.hpp"
#include "tessera/math/power_of_two.hpp"

namespace tessera {

Bounds3 bounding_box(const PolyMesh& mesh) {
  Bounds3 box;
  for (const Vec3& p : mesh.positions) {
    box.lo = glm::min(box.lo, p);
    box.hi = glm::max(box.hi, p);
  }
  return box;
}

double surface_area(const PolyMesh& mesh) {
  double area = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) area += detail::face_area(mesh, f);
  return area;
}

double signed_volume(const PolyMesh& mesh) {
  // Coordinates outside 2^+-128 are scaled by a power of two first (exactly): about 1e300 the triple products were
  // infinite with both signs and summed to NaN; the volume is then scaled back (inf where it passes the largest
  // double).
  const int s = rescale_exponent(std::span<const Vec3>(mesh.positions));
  const auto point = [&](uint32_t v) { return ldexp(mesh.positions[v], -s); };
  double volume = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    const Vec3 p0 = point(face[0]);
    for (size_t i = 1; i + 1 < face.size(); ++i) volume += glm::dot(p0, glm::cross(point(face[i]), point(face[i + 1])));
  }
  return std::ldexp(volume / 6.0, 3 * s);
}

}  // namespace tessera
