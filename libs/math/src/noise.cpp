#include "tessera/math/noise.hpp"

#include <cmath>
#include <limits>

namespace tessera {
namespace {

constexpr uint64_t kJavaMultiplier = 0x5DEECE66Dull, kJavaIncrement = 0xB, kJavaMask = (uint64_t(1) << 48) - 1;

// PApplet's constants: the table of 4096 values and the lattice strides of y and z in it.
constexpr uint32_t kTableMask = 4095, kYStride = 1u << 4, kZStride = 1u << 8;

// Processing's cosine table: 720 entries in half-degree steps, computed as PApplet computes it (float angle
// i * (PI / 180) * 0.5 with PI = (float) Math.PI, cosine in double, stored as float); noise reads its first half.
constexpr int kCosTableSize = 720, kCosHalfTurn = kCosTableSize / 2;

const std::array<float, kCosTableSize>& cos_table() {
  static const std::array<float, kCosTableSize> table = [] {
    std::array<float, kCosTableSize> t{};
    const float deg_to_rad = float(3.141592653589793) / 180.0f;
    for (int i = 0; i < kCosTableSize; ++i) t[size_t(i)] = float(std::cos(double(float(i) * deg_to_rad * 0.5f)));
    return t;
  }();
  return table;
}

// Java's (int) cast of a float: truncation toward zero, saturating, NaN to 0.
int32_t java_int(float v) {
  if (std::isnan(v)) return 0;
  if (v >= 2147483648.0f) return std::numeric_limits<int32_t>::max();
  if (v <= -2147483648.0f) return std::numeric_limits<int32_t>::min();
  return int32_t(v);
}

// PApplet's noise_fsc: the cosine ease 0.5 (1 - cos(pi t)) of t in [0, 1), read from the table.
float ease(float t) { return 0.5f * (1.0f - cos_table()[size_t(java_int(t * float(kCosHalfTurn)) % kCosTableSize)]); }

// Ken Perlin's permutation (the reference implementation's), repeated so that p[i + 1] never needs a wrap.
constexpr uint8_t kPermutation[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

int perm(int i) { return kPermutation[i & 255]; }

double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

double lerp(double t, double a, double b) { return a + t * (b - a); }

// The gradient of hash's low 4 bits (12 cube-edge directions, 4 of them twice) dotted with (x, y, z).
double grad(int hash, double x, double y, double z) {
  const int h = hash & 15;
  const double u = h < 8 ? x : y;
  const double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

// One coordinate at the next octave: the lattice cell i and the position f in it, at twice the frequency.
void double_frequency(uint32_t& i, float& f) {
  i <<= 1;
  f *= 2;
  if (f >= 1.0f) {
    ++i;
    --f;
  }
}

}  // namespace

void JavaRandom::set_seed(int64_t seed) { state_ = (uint64_t(seed) ^ kJavaMultiplier) & kJavaMask; }

int32_t JavaRandom::next(int bits) {
  state_ = (state_ * kJavaMultiplier + kJavaIncrement) & kJavaMask;
  return int32_t(uint32_t(state_ >> (48 - bits)));
}

void ProcessingNoise::noise_seed(int64_t seed) {
  JavaRandom random(seed);
  for (float& v : table_) v = random.next_float();
}

void ProcessingNoise::noise_detail(int octaves) {
  if (octaves > 0) octaves_ = octaves;
}

void ProcessingNoise::noise_detail(int octaves, double falloff) {
  noise_detail(octaves);
  if (falloff > 0) falloff_ = float(falloff);
}

float ProcessingNoise::noise(float x, float y, float z) const {
  x = std::fabs(x);
  y = std::fabs(y);
  z = std::fabs(z);
  // Lattice cells as Java ints; shifts and sums wrap as Java's do (two's complement), hence unsigned arithmetic.
  uint32_t xi = uint32_t(java_int(x)), yi = uint32_t(java_int(y)), zi = uint32_t(java_int(z));
  float xf = x - float(int32_t(xi)), yf = y - float(int32_t(yi)), zf = z - float(int32_t(zi));
  const auto at = [&](uint32_t i) { return table_[i & kTableMask]; };
  float sum = 0, amplitude = 0.5f;
  for (int octave = 0; octave < octaves_; ++octave) {
    const uint32_t of = xi + (yi << 4) + (zi << 8);
    const float rxf = ease(xf), ryf = ease(yf);
    // Bilinear (with the eased weights) on the z plane of the cell that starts at table entry p.
    const auto plane = [&](uint32_t p) {
      float n1 = at(p);
      n1 += rxf * (at(p + 1) - n1);
      float n2 = at(p + kYStride);
      n2 += rxf * (at(p + kYStride + 1) - n2);
      return n1 + ryf * (n2 - n1);
    };
    // The cell's plane, then the next, then between them.
    float n1 = plane(of);
    const float n2 = plane(of + kZStride);
    n1 += ease(zf) * (n2 - n1);
    sum += n1 * amplitude;
    amplitude *= falloff_;
    double_frequency(xi, xf);
    double_frequency(yi, yf);
    double_frequency(zi, zf);
  }
  return sum;
}

double perlin_noise(double x, double y, double z) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return std::numeric_limits<double>::quiet_NaN();
  const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  // The unit cube's corner, wrapped to the table as the reference's (int) floor(x) & 255 (fmod keeps the cast
  // defined for any finite coordinate), and the point inside it.
  const auto cell = [](double f) { return int(std::fmod(f, 256.0)) & 255; };
  const int cx = cell(fx), cy = cell(fy), cz = cell(fz);
  x -= fx;
  y -= fy;
  z -= fz;
  const double u = fade(x), v = fade(y), w = fade(z);
  // The hashes of the cube's eight corners.
  const int a = perm(cx) + cy, aa = perm(a) + cz, ab = perm(a + 1) + cz;
  const int b = perm(cx + 1) + cy, ba = perm(b) + cz, bb = perm(b + 1) + cz;
  return lerp(w,
              lerp(v, lerp(u, grad(perm(aa), x, y, z), grad(perm(ba), x - 1, y, z)),
                   lerp(u, grad(perm(ab), x, y - 1, z), grad(perm(bb), x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(perm(aa + 1), x, y, z - 1), grad(perm(ba + 1), x - 1, y, z - 1)),
                   lerp(u, grad(perm(ab + 1), x, y - 1, z - 1), grad(perm(bb + 1), x - 1, y - 1, z - 1))));
}

}  // namespace tessera
