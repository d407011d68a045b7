#include "tessera/color/chromaticity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

constexpr double kFirstNm = 380.0, kStepNm = 5.0, kLastNm = 780.0;

// CIE 15:2004 table T.4: the CIE 1931 standard colorimetric observer, 380..780 nm at 5 nm, six decimals.
// Check: each column sums to 21.3715 (equal-energy white at x = y = 1/3); the tests verify this and the locus.
const std::array<CmfSample, 81> kCie1931 = {{
    {380, {0.001368, 0.000039, 0.006450}}, {385, {0.002236, 0.000064, 0.010550}}, {390, {0.004243, 0.000120, 0.020050}},
    {395, {0.007650, 0.000217, 0.036210}}, {400, {0.014310, 0.000396, 0.067850}}, {405, {0.023190, 0.000640, 0.110200}},
    {410, {0.043510, 0.001210, 0.207400}}, {415, {0.077630, 0.002180, 0.371300}}, {420, {0.134380, 0.004000, 0.645600}},
    {425, {0.214770, 0.007300, 1.039050}}, {430, {0.283900, 0.011600, 1.385600}}, {435, {0.328500, 0.016840, 1.622960}},
    {440, {0.348280, 0.023000, 1.747060}}, {445, {0.348060, 0.029800, 1.782600}}, {450, {0.336200, 0.038000, 1.772110}},
    {455, {0.318700, 0.048000, 1.744100}}, {460, {0.290800, 0.060000, 1.669200}}, {465, {0.251100, 0.073900, 1.528100}},
    {470, {0.195360, 0.090980, 1.287640}}, {475, {0.142100, 0.112600, 1.041900}}, {480, {0.095640, 0.139020, 0.812950}},
    {485, {0.057950, 0.169300, 0.616200}}, {490, {0.032010, 0.208020, 0.465180}}, {495, {0.014700, 0.258600, 0.353300}},
    {500, {0.004900, 0.323000, 0.272000}}, {505, {0.002400, 0.407300, 0.212300}}, {510, {0.009300, 0.503000, 0.158200}},
    {515, {0.029100, 0.608200, 0.111700}}, {520, {0.063270, 0.710000, 0.078250}}, {525, {0.109600, 0.793200, 0.057250}},
    {530, {0.165500, 0.862000, 0.042160}}, {535, {0.225750, 0.914850, 0.029840}}, {540, {0.290400, 0.954000, 0.020300}},
    {545, {0.359700, 0.980300, 0.013400}}, {550, {0.433450, 0.994950, 0.008750}}, {555, {0.512050, 1.000000, 0.005750}},
    {560, {0.594500, 0.995000, 0.003900}}, {565, {0.678400, 0.978600, 0.002750}}, {570, {0.762100, 0.952000, 0.002100}},
    {575, {0.842500, 0.915400, 0.001800}}, {580, {0.916300, 0.870000, 0.001650}}, {585, {0.978600, 0.816300, 0.001400}},
    {590, {1.026300, 0.757000, 0.001100}}, {595, {1.056700, 0.694900, 0.001000}}, {600, {1.062200, 0.631000, 0.000800}},
    {605, {1.045600, 0.566800, 0.000600}}, {610, {1.002600, 0.503000, 0.000340}}, {615, {0.938400, 0.441200, 0.000240}},
    {620, {0.854450, 0.381000, 0.000190}}, {625, {0.751400, 0.321000, 0.000100}}, {630, {0.642400, 0.265000, 0.000050}},
    {635, {0.541900, 0.217000, 0.000030}}, {640, {0.447900, 0.175000, 0.000020}}, {645, {0.360800, 0.138200, 0.000010}},
    {650, {0.283500, 0.107000, 0.000000}}, {655, {0.218700, 0.081600, 0.000000}}, {660, {0.164900, 0.061000, 0.000000}},
    {665, {0.121200, 0.044580, 0.000000}}, {670, {0.087400, 0.032000, 0.000000}}, {675, {0.063600, 0.023200, 0.000000}},
    {680, {0.046770, 0.017000, 0.000000}}, {685, {0.032900, 0.011920, 0.000000}}, {690, {0.022700, 0.008210, 0.000000}},
    {695, {0.015840, 0.005723, 0.000000}}, {700, {0.011359, 0.004102, 0.000000}}, {705, {0.008111, 0.002929, 0.000000}},
    {710, {0.005790, 0.002091, 0.000000}}, {715, {0.004109, 0.001484, 0.000000}}, {720, {0.002899, 0.001047, 0.000000}},
    {725, {0.002049, 0.000740, 0.000000}}, {730, {0.001440, 0.000520, 0.000000}}, {735, {0.001000, 0.000361, 0.000000}},
    {740, {0.000690, 0.000249, 0.000000}}, {745, {0.000476, 0.000172, 0.000000}}, {750, {0.000332, 0.000120, 0.000000}},
    {755, {0.000235, 0.000085, 0.000000}}, {760, {0.000166, 0.000060, 0.000000}}, {765, {0.000117, 0.000042, 0.000000}},
    {770, {0.000083, 0.000030, 0.000000}}, {775, {0.000059, 0.000021, 0.000000}}, {780, {0.000042, 0.000015, 0.000000}},
}};

double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

// The chromaticities of the table's rows: the corners of the horseshoe polygon.
const std::array<Vec2, 81>& locus_corners() {
  static const std::array<Vec2, 81> corners = [] {
    std::array<Vec2, 81> c;
    for (size_t i = 0; i < c.size(); ++i) c[i] = spectral_locus(kCie1931[i].wavelength_nm);
    return c;
  }();
  return corners;
}

}  // namespace

std::span<const CmfSample> cie1931_cmf_table() { return kCie1931; }

Vec3 cie1931_cmf(double wavelength_nm) {
  if (!(wavelength_nm >= kFirstNm && wavelength_nm <= kLastNm)) return Vec3(0.0);
  const double position = (wavelength_nm - kFirstNm) / kStepNm;
  const size_t i = std::min(size_t(position), kCie1931.size() - 2);
  const double t = position - double(i);
  return kCie1931[i].xyz_bar * (1.0 - t) + kCie1931[i + 1].xyz_bar * t;
}

Vec2 spectral_locus(double wavelength_nm) {
  if (!(wavelength_nm >= kFirstNm && wavelength_nm <= kLastNm))
    throw InvalidInput(fmt::format("spectral locus: wavelength {} nm is outside [380, 780] nm", wavelength_nm));
  const Vec3 xyz = cie1931_cmf(wavelength_nm);
  return Vec2(xyz.x, xyz.y) / (xyz.x + xyz.y + xyz.z);
}

bool is_visible_chromaticity(const Vec2& xy) {
  // Even-odd crossing test against the closed polygon of the tabulated locus (its last edge is the purple line);
  // points on an edge are inside.
  bool inside = false;
  const auto& corners = locus_corners();
  for (size_t i = 0, j = corners.size() - 1; i < corners.size(); j = i++) {
    const Vec2 a = corners[j], b = corners[i];
    const Vec2 ab = b - a, ap = xy - a;
    const double along = glm::dot(ap, ab);
    if (std::abs(cross(ab, ap)) <= 1e-12 && along >= 0 && along <= glm::dot(ab, ab)) return true;
    if ((a.y > xy.y) != (b.y > xy.y) && xy.x < a.x + (xy.y - a.y) * ab.x / ab.y) inside = !inside;
  }
  return inside;
}

Vec2 d65_white() { return {0.3127, 0.3290}; }

RgbGamut srgb_gamut() { return {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, d65_white()}; }

Mat3 rgb_to_xyz_matrix(const RgbGamut& gamut) {
  const auto xyz_of = [](const Vec2& xy) {
    if (!(xy.y > 0)) throw InvalidInput(fmt::format("chromaticity ({}, {}) has y <= 0", xy.x, xy.y));
    return Vec3(xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y);
  };
  // Columns: the primaries' XYZ at unit luminance, then scaled so that their sum is the white's XYZ (Y = 1).
  const Mat3 primaries(xyz_of(gamut.red), xyz_of(gamut.green), xyz_of(gamut.blue));
  if (std::abs(glm::determinant(primaries)) < 1e-12)
    throw InvalidInput("gamut: the three primaries are collinear in the chromaticity diagram");
  const Vec3 scale = glm::inverse(primaries) * xyz_of(gamut.white);
  return Mat3(primaries[0] * scale.x, primaries[1] * scale.y, primaries[2] * scale.z);
}

bool in_gamut(const Vec2& xy, const RgbGamut& gamut) {
  const double d1 = cross(gamut.green - gamut.red, xy - gamut.red);
  const double d2 = cross(gamut.blue - gamut.green, xy - gamut.green);
  const double d3 = cross(gamut.red - gamut.blue, xy - gamut.blue);
  const bool has_negative = d1 < 0 || d2 < 0 || d3<0, has_positive = d1> 0 || d2 > 0 || d3 > 0;
  return !(has_negative && has_positive);
}

}  // namespace tessera
