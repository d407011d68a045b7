#include "tessera/color/color.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "rows.hpp"
#include "tessera/color/chromaticity.hpp"
#include "tessera/core/error.hpp"

namespace tessera {
namespace {

// The hue (turns) and chroma max - min shared by HSV and HLS: the sector of the largest component, offset by the
// position of the other two (Smith 1978; the same branches as colorsys, so ties pick red, then green).
struct HueChroma {
  double hue, max, min;
};

HueChroma hue_chroma(const Vec3& rgb) {
  const double maxc = std::max({rgb.x, rgb.y, rgb.z});
  const double minc = std::min({rgb.x, rgb.y, rgb.z});
  const double range = maxc - minc;
  if (range == 0) return {0.0, maxc, minc};
  const double inv = 1.0 / range;  // one division for the three (within an ulp of colorsys's three)
  const double rc = (maxc - rgb.x) * inv, gc = (maxc - rgb.y) * inv, bc = (maxc - rgb.z) * inv;
  // The sector by weights of 0 or 1 instead of branches, which random colors mispredict (x * 1 + 0 + 0 is x exactly):
  // red wins ties, then green, as colorsys; / 6 as a product (an ulp of colorsys). h lies in [-1/6, 5/6]: wrapping
  // adds 1 below 0 (wrap_hue's floor is a library call without SSE4.1), and a sum that rounds to 1 is 0, as there.
  const double red = rgb.x == maxc, green = (1.0 - red) * double(rgb.y == maxc), blue = 1.0 - red - green;
  const double h = (red * (bc - gc) + green * (2.0 + rc - bc) + blue * (4.0 + gc - rc)) * (1.0 / 6.0);
  const double wrapped = h + double(h < 0);
  return {wrapped * double(wrapped < 1.0), maxc, minc};
}

// One channel of the HLS double hexcone: m1 + (m2 - m1) * ramp(hue) (Foley and van Dam, "HLS_TO_RGB" / Value()).
double hls_channel(double m1, double m2, double hue) {
  const double h = wrap_hue(hue);
  if (h < 1.0 / 6.0) return m1 + (m2 - m1) * h * 6.0;
  if (h < 0.5) return m2;
  if (h < 2.0 / 3.0) return m1 + (m2 - m1) * (2.0 / 3.0 - h) * 6.0;
  return m1;
}

// YIQ = kYiq * rgb with colorsys's FCC coefficients, expanded: I = 0.74 (R - Y) - 0.27 (B - Y) etc.
Mat3 yiq_matrix() {
  const Vec3 y(0.30, 0.59, 0.11);
  const Vec3 r_minus_y = Vec3(1, 0, 0) - y, b_minus_y = Vec3(0, 0, 1) - y;
  const Vec3 i = 0.74 * r_minus_y - 0.27 * b_minus_y;
  const Vec3 q = 0.48 * r_minus_y + 0.41 * b_minus_y;
  return glm::transpose(Mat3(y, i, q));  // rows y, i, q
}

const Mat3& rgb_to_yiq_matrix() {
  static const Mat3 m = yiq_matrix();
  return m;
}
const Mat3& yiq_to_rgb_matrix() {
  static const Mat3 m = glm::inverse(rgb_to_yiq_matrix());
  return m;
}
const Mat3& srgb_to_xyz_matrix() {
  static const Mat3 m = rgb_to_xyz_matrix(srgb_gamut());
  return m;
}
const Mat3& xyz_to_srgb_matrix() {
  static const Mat3 m = glm::inverse(srgb_to_xyz_matrix());
  return m;
}

}  // namespace

double wrap_hue(double turns) {
  const double h = turns - std::floor(turns);
  return h < 1.0 ? h : 0.0;
}

Vec3 rgb_to_cmy(const Vec3& rgb) { return Vec3(1.0) - rgb; }
Vec3 cmy_to_rgb(const Vec3& cmy) { return Vec3(1.0) - cmy; }

Vec4 cmy_to_cmyk(const Vec3& cmy) {
  const double k = std::min({cmy.x, cmy.y, cmy.z});
  if (k >= 1.0) return {0.0, 0.0, 0.0, 1.0};
  return {(cmy - k) / (1.0 - k), k};
}

Vec3 cmyk_to_cmy(const Vec4& cmyk) { return Vec3(cmyk) * (1.0 - cmyk.w) + cmyk.w; }
Vec4 rgb_to_cmyk(const Vec3& rgb) { return cmy_to_cmyk(rgb_to_cmy(rgb)); }
Vec3 cmyk_to_rgb(const Vec4& cmyk) { return (Vec3(1.0) - Vec3(cmyk)) * (1.0 - cmyk.w); }

Vec3 rgb_to_hsv(const Vec3& rgb) {
  const HueChroma hc = hue_chroma(rgb);
  const double s = hc.max > 0 ? (hc.max - hc.min) / hc.max : 0.0;
  return {hc.hue, s, hc.max};
}

Vec3 hsv_to_rgb(const Vec3& hsv) {
  const double s = hsv.y, v = hsv.z;
  if (s == 0.0) return Vec3(v);
  const double h6 = wrap_hue(hsv.x) * 6.0;
  const int sector = std::min(int(h6), 5);
  const double f = h6 - sector;
  const double p = v * (1.0 - s), q = v * (1.0 - s * f), t = v * (1.0 - s * (1.0 - f));
  switch (sector) {
    case 0:
      return {v, t, p};
    case 1:
      return {q, v, p};
    case 2:
      return {p, v, t};
    case 3:
      return {p, q, v};
    case 4:
      return {t, p, v};
    default:
      return {v, p, q};
  }
}

Vec3 rgb_to_hls(const Vec3& rgb) {
  const HueChroma hc = hue_chroma(rgb);
  const double sum = hc.max + hc.min, range = hc.max - hc.min;
  const double l = sum / 2.0;
  if (range == 0) return {0.0, l, 0.0};
  const double denominator = l <= 0.5 ? sum : 2.0 - hc.max - hc.min;
  return {hc.hue, l, denominator > 0 ? range / denominator : 0.0};
}

Vec3 hls_to_rgb(const Vec3& hls) {
  const double h = hls.x, l = hls.y, s = hls.z;
  if (s == 0.0) return Vec3(l);
  const double m2 = l <= 0.5 ? l * (1.0 + s) : l + s - l * s;
  const double m1 = 2.0 * l - m2;
  return {hls_channel(m1, m2, h + 1.0 / 3.0), hls_channel(m1, m2, h), hls_channel(m1, m2, h - 1.0 / 3.0)};
}

Vec3 rgb_to_yiq(const Vec3& rgb) { return rgb_to_yiq_matrix() * rgb; }
Vec3 yiq_to_rgb(const Vec3& yiq) { return yiq_to_rgb_matrix() * yiq; }

Vec3 rgb_to_xyz(const Vec3& rgb) { return srgb_to_xyz_matrix() * rgb; }
Vec3 xyz_to_rgb(const Vec3& xyz) { return xyz_to_srgb_matrix() * xyz; }

Vec3 xyz_to_xyy(const Vec3& xyz) {
  const double sum = xyz.x + xyz.y + xyz.z;
  if (sum == 0.0) {
    const Vec2 white = d65_white();
    return {white.x, white.y, 0.0};
  }
  return {xyz.x / sum, xyz.y / sum, xyz.y};
}

Vec3 xyy_to_xyz(const Vec3& xyy) {
  const double x = xyy.x, y = xyy.y, luminance = xyy.z;
  if (luminance == 0.0) return Vec3(0.0);
  if (!(y > 0.0))
    throw InvalidInput(fmt::format("xyY ({}, {}, {}): chromaticity y must be > 0 when Y is not 0", x, y, luminance));
  return {x * luminance / y, luminance, (1.0 - x - y) * luminance / y};
}

Vec3 rgb_to_xyy(const Vec3& rgb) { return xyz_to_xyy(rgb_to_xyz(rgb)); }
Vec3 xyy_to_rgb(const Vec3& xyy) { return xyz_to_rgb(xyy_to_xyz(xyy)); }

namespace detail {
namespace {

// Two doubles per register (SSE2, every x86-64; NEON on ARM): GCC's vector extension, as raster3d's lanes.
using D2 = double __attribute__((vector_size(16)));
using M2 = long long __attribute__((vector_size(16)));

D2 weight(M2 mask) { return __builtin_convertvector(-mask, D2); }  // true (-1) -> 1.0, false -> 0.0
D2 pick(M2 mask, D2 a, D2 b) { return mask ? a : b; }

/// Two colors' components from rows i and i + 1.
struct Pair {
  D2 r, g, b;
};
Pair load(std::span<const double> in, size_t i) {
  const double* p = in.data() + 3 * i;
  return {D2{p[0], p[3]}, D2{p[1], p[4]}, D2{p[2], p[5]}};
}
void store(std::span<double> out, size_t i, D2 x, D2 y, D2 z) {
  double* p = out.data() + 3 * i;
  p[0] = x[0], p[1] = y[0], p[2] = z[0], p[3] = x[1], p[4] = y[1], p[5] = z[1];
}

/// hue_chroma of two colors: the same operations (grays, range 0, get hue 0 by a select where it returns early).
struct HueChroma2 {
  D2 hue, max, min, range;
};
HueChroma2 hue_chroma2(const Pair& c) {
  D2 maxc = c.r, minc = c.r;  // as std::max_element and std::min_element: the first of equals
  maxc = pick(maxc < c.g, c.g, maxc), maxc = pick(maxc < c.b, c.b, maxc);
  minc = pick(c.g < minc, c.g, minc), minc = pick(c.b < minc, c.b, minc);
  const D2 range = maxc - minc;
  const D2 inv = 1.0 / range;
  const D2 rc = (maxc - c.r) * inv, gc = (maxc - c.g) * inv, bc = (maxc - c.b) * inv;
  const D2 red = weight(c.r == maxc), green = (1.0 - red) * weight(c.g == maxc), blue = 1.0 - red - green;
  const D2 h = (red * (bc - gc) + green * (2.0 + rc - bc) + blue * (4.0 + gc - rc)) * (1.0 / 6.0);
  const D2 wrapped = h + weight(h < 0.0);
  const D2 zero = {0.0, 0.0};
  return {pick(range == 0.0, zero, wrapped * weight(wrapped < 1.0)), maxc, minc, range};
}

/// f(pair) for each two rows, the one-color function for a last odd row.
template <class Two, class One>
void rows(std::span<const double> in, std::span<double> out, Two two, One one) {
  const size_t n = in.size() / 3;
  for (size_t i = 0; i + 1 < n; i += 2) two(load(in, i), i);
  if (n % 2 == 1) {
    const size_t i = n - 1;
    const Vec3 v = one(Vec3(in[3 * i], in[3 * i + 1], in[3 * i + 2]));
    out[3 * i] = v.x, out[3 * i + 1] = v.y, out[3 * i + 2] = v.z;
  }
}

}  // namespace

void rgb_to_hsv_rows(std::span<const double> in, std::span<double> out) {
  const D2 zero = {0.0, 0.0};
  rows(
      in, out,
      [&](const Pair& c, size_t i) {
        const HueChroma2 hc = hue_chroma2(c);
        store(out, i, hc.hue, pick(hc.max > 0.0, (hc.max - hc.min) / hc.max, zero), hc.max);
      },
      rgb_to_hsv);
}

void rgb_to_hls_rows(std::span<const double> in, std::span<double> out) {
  const D2 zero = {0.0, 0.0};
  rows(
      in, out,
      [&](const Pair& c, size_t i) {
        const HueChroma2 hc = hue_chroma2(c);
        const D2 sum = hc.max + hc.min, l = sum / 2.0;
        const D2 denominator = pick(l <= 0.5, sum, 2.0 - hc.max - hc.min);
        const D2 s = pick(denominator > 0.0, hc.range / denominator, zero);
        store(out, i, hc.hue, l, pick(hc.range == 0.0, zero, s));
      },
      rgb_to_hls);
}

}  // namespace detail
}  // namespace tessera
