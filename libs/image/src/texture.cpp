#include "tessera/image/texture.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tessera/core/error.hpp"
#include "tessera/math/types.hpp"

namespace tessera {
namespace {

// A texel-space coordinate split into floor(x) and x - floor(x). NaN reads texel 0 and huge values are clamped far
// outside any texture (wrapping then folds them back), so no input is undefined behavior.
struct Split {
  long long index;
  float fraction;
};

// floor(x) for |x| <= 1e15 by truncation: the x86-64 baseline has no rounding instruction, and std::floor's
// emulation was a good part of a bilinear sample.
double floor_small(double x) {
  const double t = double((long long)x);
  return t > x ? t - 1 : t;
}

Split split(double x) {
  if (!(x == x)) return {0, 0.f};
  x = std::clamp(x, -1e15, 1e15);
  const double f = floor_small(x);
  return {(long long)f, float(x - f)};
}

// Texel index i of a row of n texels after wrapping.
long long wrap_index(long long i, long long n, Wrap wrap) {
  switch (wrap) {
    case Wrap::repeat: return ((i % n) + n) % n;
    case Wrap::clamp: return std::clamp(i, 0LL, n - 1);
    case Wrap::mirror: {
      const long long m = ((i % (2 * n)) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
  }
  return 0;
}

// The texel indices (i, i + 1) of a row of n texels after wrapping: the interior without any wrapping arithmetic.
struct IndexPair {
  int lo, hi;
};

IndexPair wrap_pair(long long i, int n, Wrap wrap) {
  if (i >= 0 && i < n - 1) return {int(i), int(i) + 1};
  return {int(wrap_index(i, n, wrap)), int(wrap_index(i + 1, n, wrap))};
}

// The texel-space coordinate x = t n - 1/2 of bilinear filtering; with repeat wrapping brought into [-1/2, n - 1/2)
// first, so that the integer wrapping (two divisions per index) is left for the last column only.
double bilinear_coordinate(float t, int n, Wrap wrap) {
  double x = double(t) * n - 0.5;
  if (wrap == Wrap::repeat && !(x >= -0.5 && x < n - 0.5) && std::abs(x) < 1e15) x -= n * floor_small((x + 0.5) / n);
  return x;
}

// The notes' bilinear interpolation on one level (Texture2D::bilinear).
[[gnu::always_inline]] inline glm::vec4 bilinear_sample(const ImageRGBA& image, const Sampler& sampler, glm::vec2 uv) {
  const int w = image.width(), h = image.height();
  // Texel centers sit at integer + 0.5: (i, j) is the bottom-left texel of the four, (a, b) the offset from it.
  const auto [i, a] = split(bilinear_coordinate(uv.x, w, sampler.wrap_u));
  const auto [j, b] = split(bilinear_coordinate(uv.y, h, sampler.wrap_v));
  const IndexPair x = wrap_pair(i, w, sampler.wrap_u), y = wrap_pair(j, h, sampler.wrap_v);
  const glm::vec4* lower = image.row(h - 1 - y.lo);  // texel rows count from the bottom
  const glm::vec4* upper = image.row(h - 1 - y.hi);
  const glm::vec4 bottom = glm::mix(lower[x.lo], lower[x.hi], a);
  const glm::vec4 top = glm::mix(upper[x.lo], upper[x.hi], a);
  return glm::mix(bottom, top, b);
}

// One output sample of a 1D reduction: up to three source indices and their weights.
struct Taps {
  int index[3];
  float weight[3];
};

// The taps reducing n samples to max(1, n / 2): pairs for even n, the mean-preserving three-tap box for odd n.
std::vector<Taps> reduction_taps(int n) {
  const int m = std::max(1, n / 2);
  std::vector<Taps> taps(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) {
    if (n == 1)
      taps[size_t(i)] = {{0, 0, 0}, {1.f, 0.f, 0.f}};
    else if (n % 2 == 0)
      taps[size_t(i)] = {{2 * i, 2 * i + 1, 2 * i}, {0.5f, 0.5f, 0.f}};
    else
      taps[size_t(i)] = {{2 * i, 2 * i + 1, 2 * i + 2},
                         {float(m - i) / float(n), float(m) / float(n), float(i + 1) / float(n)}};
  }
  return taps;
}

// The next MIPmap level: reduce along x, then along y (separable, so even sizes give the notes' 2x2 average).
ImageRGBA reduce(const ImageRGBA& image) {
  const std::vector<Taps> tx = reduction_taps(image.width()), ty = reduction_taps(image.height());
  ImageRGBA half_x(int(tx.size()), image.height());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < half_x.width(); ++x) {
      const Taps& t = tx[size_t(x)];
      half_x(x, y) = image(t.index[0], y) * t.weight[0] + image(t.index[1], y) * t.weight[1] +
                     image(t.index[2], y) * t.weight[2];
    }
  ImageRGBA out(half_x.width(), int(ty.size()));
  for (int y = 0; y < out.height(); ++y) {
    const Taps& t = ty[size_t(y)];
    for (int x = 0; x < out.width(); ++x)
      out(x, y) = half_x(x, t.index[0]) * t.weight[0] + half_x(x, t.index[1]) * t.weight[1] +
                  half_x(x, t.index[2]) * t.weight[2];
  }
  return out;
}

void check_nonempty(const ImageRGBA& image, const char* what) {
  if (image.empty()) throw InvalidInput(fmt::format("{}: the image is empty", what));
}

}  // namespace

std::vector<ImageRGBA> build_mipmaps(ImageRGBA image) {
  check_nonempty(image, "build_mipmaps");
  std::vector<ImageRGBA> levels;
  levels.push_back(std::move(image));
  while (levels.back().width() > 1 || levels.back().height() > 1) levels.push_back(reduce(levels.back()));
  return levels;
}

Texture2D::Texture2D(ImageRGBA image, const Sampler& sampler) : sampler_(sampler) {
  check_nonempty(image, "Texture2D");
  levels_ = build_mipmaps(std::move(image));
}

const ImageRGBA& Texture2D::level(int i) const {
  if (i < 0 || i >= levels())
    throw InvalidInput(fmt::format("MIPmap level {} is outside [0, {})", i, levels()));
  return levels_[size_t(i)];
}

glm::vec4 Texture2D::texel(const ImageRGBA& image, long long i, long long j) const {
  const long long x = wrap_index(i, image.width(), sampler_.wrap_u);
  const long long y = wrap_index(j, image.height(), sampler_.wrap_v);
  return image(int(x), image.height() - 1 - int(y));
}

glm::vec4 Texture2D::nearest(glm::vec2 uv, int level) const {
  const ImageRGBA& image = levels_[size_t(level)];
  return texel(image, split(double(uv.x) * image.width()).index, split(double(uv.y) * image.height()).index);
}

glm::vec4 Texture2D::bilinear(glm::vec2 uv, int level) const {
  return bilinear_sample(levels_[size_t(level)], sampler_, uv);
}

glm::vec4 Texture2D::sample(glm::vec2 uv, float lod) const {
  switch (sampler_.filter) {
    case Filter::nearest: return nearest(uv, 0);
    case Filter::bilinear: return bilinear_sample(levels_.front(), sampler_, uv);
    case Filter::trilinear: break;
  }
  const float last = float(levels() - 1);
  const float clamped = lod > 0.f ? std::min(lod, last) : 0.f;  // NaN and -infinity read level 0
  const int lower = int(clamped);
  const float blend = clamped - float(lower);
  // The two levels' samples inlined here: as calls, their results went through memory.
  const glm::vec4 near = bilinear_sample(levels_[size_t(lower)], sampler_, uv);
  if (blend == 0.f) return near;
  return glm::mix(near, bilinear_sample(levels_[size_t(lower) + 1], sampler_, uv), blend);
}

float Texture2D::lod(glm::vec2 duv_dx, glm::vec2 duv_dy) const {
  const glm::vec2 size{float(width()), float(height())};
  const float rho = std::max(glm::length(duv_dx * size), glm::length(duv_dy * size));
  return std::log2(rho);
}

glm::vec2 latlong_uv(glm::vec3 direction) {
  const double x = direction.x, y = direction.y, z = direction.z;
  return {float(0.5 + std::atan2(x, -z) / (2.0 * kPi)), float(0.5 + std::atan2(y, std::hypot(x, z)) / kPi)};
}

glm::vec3 latlong_direction(glm::vec2 uv) {
  const double phi = (double(uv.x) - 0.5) * (2.0 * kPi), theta = (double(uv.y) - 0.5) * kPi;
  return {float(std::cos(theta) * std::sin(phi)), float(std::sin(theta)), float(-std::cos(theta) * std::cos(phi))};
}

EnvironmentMap::EnvironmentMap(ImageRGBA latlong, Filter filter)
    : texture_(std::move(latlong), Sampler{Wrap::repeat, Wrap::clamp, filter}) {}

glm::vec4 EnvironmentMap::lookup(glm::vec3 direction, float lod) const {
  return texture_.sample(latlong_uv(direction), lod);
}

CubeCoord cube_coord(glm::vec3 d) {
  const float ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  CubeFace face;
  float sc, tc, ma;
  if (ax >= ay && ax >= az) {
    if (ax == 0.f) return {CubeFace::pos_x, {0.5f, 0.5f}};
    face = d.x > 0 ? CubeFace::pos_x : CubeFace::neg_x;
    sc = d.x > 0 ? -d.z : d.z;
    tc = -d.y;
    ma = ax;
  } else if (ay >= az) {
    face = d.y > 0 ? CubeFace::pos_y : CubeFace::neg_y;
    sc = d.x;
    tc = d.y > 0 ? d.z : -d.z;
    ma = ay;
  } else {
    face = d.z > 0 ? CubeFace::pos_z : CubeFace::neg_z;
    sc = d.z > 0 ? d.x : -d.x;
    tc = -d.y;
    ma = az;
  }
  return {face, {0.5f * (sc / ma + 1.f), 0.5f * (tc / ma + 1.f)}};
}

glm::vec3 cube_direction(const CubeCoord& coord) {
  const float sc = 2.f * coord.st.x - 1.f, tc = 2.f * coord.st.y - 1.f;
  switch (coord.face) {
    case CubeFace::pos_x: return {1.f, -tc, -sc};
    case CubeFace::neg_x: return {-1.f, -tc, sc};
    case CubeFace::pos_y: return {sc, 1.f, tc};
    case CubeFace::neg_y: return {sc, -1.f, -tc};
    case CubeFace::pos_z: return {sc, -tc, 1.f};
    case CubeFace::neg_z: return {-sc, -tc, -1.f};
  }
  return {1.f, 0.f, 0.f};
}

CubeMap::CubeMap(std::array<ImageRGBA, 6> faces, Filter filter) {
  const int size = faces[0].width();
  for (size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].empty() || faces[f].width() != size || faces[f].height() != size)
      throw InvalidInput(fmt::format("cube map face {} is {}x{}; all six faces must be square and {}x{}", f,
                                     faces[f].width(), faces[f].height(), std::max(size, 1), std::max(size, 1)));
  }
  faces_.reserve(faces.size());
  for (ImageRGBA& face : faces) faces_.emplace_back(std::move(face), Sampler{Wrap::clamp, Wrap::clamp, filter});
}

CubeMap CubeMap::from_function(int size, const std::function<glm::vec4(glm::vec3)>& radiance, Filter filter) {
  if (size < 1) throw InvalidInput(fmt::format("cube map size {} must be at least 1", size));
  std::array<ImageRGBA, 6> faces;
  for (int f = 0; f < 6; ++f) {
    faces[size_t(f)] = ImageRGBA(size, size);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::vec2 st((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size));
        faces[size_t(f)](x, y) = radiance(glm::normalize(cube_direction({CubeFace(f), st})));
      }
  }
  return CubeMap(std::move(faces), filter);
}

glm::vec4 CubeMap::lookup(glm::vec3 direction, float lod) const {
  const CubeCoord c = cube_coord(direction);
  // Face row 0 is t = 0 while Texture2D's v = 0 is the bottom row: v = 1 - t.
  return faces_[size_t(c.face)].sample({c.st.x, 1.f - c.st.y}, lod);
}

}  // namespace tessera
