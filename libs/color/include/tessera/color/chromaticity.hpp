#pragma once
// CIE 1931 chromaticity: the 2-degree color-matching functions as data, the spectral locus, RGB gamut triangles and
// the RGB <-> XYZ matrix of a set of primaries (the notes' "CIE Chromaticity Diagram" and "gamut").
#include <span>

#include "tessera/math/types.hpp"

namespace tessera {

/// One row of the CIE 1931 2-degree color-matching functions.
struct CmfSample {
  double wavelength_nm;  ///< wavelength in nanometres
  Vec3 xyz_bar;          ///< (x-bar, y-bar, z-bar)
};

/// The CIE 1931 2-degree standard observer at 5 nm steps from 380 to 780 nm (81 rows), six decimals.
/// Source: CIE 15:2004 Colorimetry, table T.4.
std::span<const CmfSample> cie1931_cmf_table();

/// The color-matching functions at any wavelength, linearly interpolated in the table; (0, 0, 0) outside
/// [380, 780] nm.
Vec3 cie1931_cmf(double wavelength_nm);

/// The spectral locus: chromaticity (x, y) of monochromatic light of the given wavelength, from the interpolated
/// color-matching functions. Precondition: wavelength in [380, 780] nm (throws InvalidInput outside).
Vec2 spectral_locus(double wavelength_nm);

/// True when the chromaticity (x, y) lies inside the horseshoe of visible colors: the polygon of the tabulated
/// spectral locus, closed by the line of purples from 780 nm back to 380 nm. Boundary points count as inside.
bool is_visible_chromaticity(const Vec2& xy);

/// The chromaticities of an additive display's primaries and of its white (the notes: a gamut is the triangle
/// whose vertices are the display's maximal red, green and blue).
struct RgbGamut {
  Vec2 red;    ///< chromaticity of (1, 0, 0)
  Vec2 green;  ///< chromaticity of (0, 1, 0)
  Vec2 blue;   ///< chromaticity of (0, 0, 1)
  Vec2 white;  ///< chromaticity of (1, 1, 1)
};

/// The chromaticity of CIE standard illuminant D65 as IEC 61966-2-1 gives it: (0.3127, 0.3290).
Vec2 d65_white();

/// The sRGB (= ITU-R BT.709) gamut: red (0.64, 0.33), green (0.30, 0.60), blue (0.15, 0.06), white D65.
/// Source: IEC 61966-2-1:1999, table 1.
RgbGamut srgb_gamut();

/// The matrix M with XYZ = M * rgb for linear RGB in the given primaries, scaled so that white (1, 1, 1) has Y = 1
/// (SMPTE RP 177-1993). Throws InvalidInput when the primaries are collinear or a chromaticity has y <= 0.
Mat3 rgb_to_xyz_matrix(const RgbGamut& gamut);

/// True when the chromaticity (x, y) lies inside the gamut triangle (edges count as inside): a display with these
/// primaries can show the color at some luminance.
bool in_gamut(const Vec2& xy, const RgbGamut& gamut);

}  // namespace tessera
