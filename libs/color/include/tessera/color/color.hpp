#pragma once
// Color-model conversions in double precision, all to and from RGB (the notes' "Color" section, docs/color.md).
//
// Conventions:
// - `rgb` is Tessera's working RGB: linear light with the sRGB/Rec. 709 primaries and white point D65, components in
//   [0, 1] for colors inside the RGB cube. CMY, CMYK, HSV, HLS and YIQ are functions of these numbers as they are
//   (the notes' RGB cube); XYZ treats them as linear light; `srgb` is their sRGB encoding (srgb.hpp).
// - Hue is in turns: [0, 1) for one full turn, red 0, yellow 1/6, green 1/3, cyan 1/2, blue 2/3, magenta 5/6 (as
//   Python's colorsys). The notes' angle is 2*pi*turns radians; model.hpp converts between units. Hue inputs of any
//   value are taken modulo 1.
// - Component order follows the model's name: HSV is (h, s, v), HLS is (h, l, s) (as colorsys), xyY is (x, y, Y).
// - Nothing is clamped except sRGB (whose curve is defined on [0, 1]): out-of-gamut results stay out of gamut.
#include "tessera/math/types.hpp"

namespace tessera {

/// Wraps a hue in turns into [0, 1): h - floor(h), with results that round up to 1 mapped to 0.
double wrap_hue(double turns);

/// CMY from RGB: (C, M, Y) = (1, 1, 1) - (R, G, B) (the notes: subtractive primaries).
Vec3 rgb_to_cmy(const Vec3& rgb);
/// RGB from CMY: (R, G, B) = (1, 1, 1) - (C, M, Y).
Vec3 cmy_to_rgb(const Vec3& cmy);

/// CMYK from CMY by undercolor removal: K = min(C, M, Y), then C' = (C - K) / (1 - K) (same for M, Y). Black
/// (K = 1) gives C' = M' = Y' = 0. Precondition: components in [0, 1].
Vec4 cmy_to_cmyk(const Vec3& cmy);
/// CMY from CMYK: C = C' (1 - K) + K (same for M, Y).
Vec3 cmyk_to_cmy(const Vec4& cmyk);
/// CMYK (C, M, Y, K) from RGB: cmy_to_cmyk(rgb_to_cmy(rgb)).
Vec4 rgb_to_cmyk(const Vec3& rgb);
/// RGB from CMYK: R = (1 - C)(1 - K), G = (1 - M)(1 - K), B = (1 - Y)(1 - K).
Vec3 cmyk_to_rgb(const Vec4& cmyk);

/// HSV (hue in turns, saturation, value) from RGB: V = max, S = (max - min) / max, hue from the hexcone sector of
/// the largest component (Smith 1978, as colorsys.rgb_to_hsv). Grays (max = min) have H = S = 0; black has V = 0.
Vec3 rgb_to_hsv(const Vec3& rgb);
/// RGB from HSV (hue in turns, any value, wrapped). S = 0 gives the gray (V, V, V).
Vec3 hsv_to_rgb(const Vec3& hsv);

/// HLS (hue in turns, lightness, saturation) from RGB: L = (max + min) / 2, S = (max - min) / (max + min) for
/// L <= 1/2, else (max - min) / (2 - max - min); hue as HSV (Foley and van Dam's double hexcone, as
/// colorsys.rgb_to_hls). Grays have H = S = 0.
Vec3 rgb_to_hls(const Vec3& rgb);
/// RGB from HLS (hue in turns, wrapped). S = 0 gives the gray (L, L, L).
Vec3 hls_to_rgb(const Vec3& hls);

/// YIQ with the FCC NTSC coefficients Python's colorsys uses: Y = 0.30 R + 0.59 G + 0.11 B,
/// I = 0.74 (R - Y) - 0.27 (B - Y), Q = 0.48 (R - Y) + 0.41 (B - Y).
Vec3 rgb_to_yiq(const Vec3& rgb);
/// RGB from YIQ: the exact inverse of rgb_to_yiq (colorsys.yiq_to_rgb uses the same matrix but clamps to [0, 1];
/// Tessera does not clamp).
Vec3 yiq_to_rgb(const Vec3& yiq);

/// CIE 1931 XYZ from linear RGB: the matrix derived from the sRGB primaries and D65 (chromaticity.hpp), equal to the
/// 4-decimal matrix of IEC 61966-2-1 to rounding. White (1, 1, 1) maps to Y = 1 at chromaticity (0.3127, 0.3290).
Vec3 rgb_to_xyz(const Vec3& rgb);
/// Linear RGB from XYZ: the inverse matrix. Colors outside the sRGB gamut give components outside [0, 1].
Vec3 xyz_to_rgb(const Vec3& xyz);

/// xyY from XYZ: x = X / (X + Y + Z), y = Y / (X + Y + Z), Y. Black (X + Y + Z = 0) takes the chromaticity of the
/// D65 white point, (0.3127, 0.3290), with Y = 0.
Vec3 xyz_to_xyy(const Vec3& xyz);
/// XYZ from xyY: X = x Y / y, Z = (1 - x - y) Y / y. Y = 0 gives black whatever x, y. Throws InvalidInput when
/// y <= 0 and Y != 0 (no such color).
Vec3 xyy_to_xyz(const Vec3& xyy);
/// xyY from linear RGB: xyz_to_xyy(rgb_to_xyz(rgb)).
Vec3 rgb_to_xyy(const Vec3& rgb);
/// Linear RGB from xyY: xyz_to_rgb(xyy_to_xyz(xyy)). Throws as xyy_to_xyz.
Vec3 xyy_to_rgb(const Vec3& xyy);

}  // namespace tessera
