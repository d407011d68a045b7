#include "tessera/image/texture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <variant>

#include "tessera/core/cpu.hpp"
#include "tessera/core/error.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/types.hpp"
#include "texture_lanes.hpp"

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
    case Wrap::repeat:
      return ((i % n) + n) % n;
    case Wrap::clamp:
      return std::clamp(i, 0LL, n - 1);
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

// v/255 for every byte, the division read_image and to_float compute (a multiplication by 1/255 differs for 126 of
// the 256 values), looked up: dividing on every fetch made an 8-bit bilinear sample about 1.7 times slower.
constexpr std::array<float, 256> kByteToUnit = [] {
  std::array<float, 256> table{};
  for (size_t v = 0; v < table.size(); ++v) table[v] = float(v) / 255.f;
  return table;
}();

// A stored texel as float: an 8-bit texel reads v/255, so an 8-bit texture samples the same values as the float
// texture of the same file.
inline glm::vec4 texel_value(const glm::vec4& texel) { return texel; }
inline glm::vec4 texel_value(const glm::u8vec4& texel) {
  return {kByteToUnit[texel.x], kByteToUnit[texel.y], kByteToUnit[texel.z], kByteToUnit[texel.w]};
}

// The notes' bilinear interpolation on one level (Texture2D::bilinear).
template <class Texel>
[[gnu::always_inline]] inline glm::vec4 bilinear_sample(const Image<Texel>& image, const Sampler& sampler,
                                                        glm::vec2 uv) {
  const int w = image.width(), h = image.height();
  // Texel centers sit at integer + 0.5: (i, j) is the bottom-left texel of the four, (a, b) the offset from it.
  const auto [i, a] = split(bilinear_coordinate(uv.x, w, sampler.wrap_u));
  const auto [j, b] = split(bilinear_coordinate(uv.y, h, sampler.wrap_v));
  const IndexPair x = wrap_pair(i, w, sampler.wrap_u), y = wrap_pair(j, h, sampler.wrap_v);
  const Texel* lower = image.row(h - 1 - y.lo);  // texel rows count from the bottom
  const Texel* upper = image.row(h - 1 - y.hi);
  const glm::vec4 bottom = glm::mix(texel_value(lower[x.lo]), texel_value(lower[x.hi]), a);
  const glm::vec4 top = glm::mix(texel_value(upper[x.lo]), texel_value(upper[x.hi]), a);
  return glm::mix(bottom, top, b);
}

// The texel of `image` containing (u, v) (Texture2D::nearest).
template <class Texel>
[[gnu::always_inline]] inline glm::vec4 nearest_sample(const Image<Texel>& image, const Sampler& sampler,
                                                       glm::vec2 uv) {
  const long long x = wrap_index(split(double(uv.x) * image.width()).index, image.width(), sampler.wrap_u);
  const long long y = wrap_index(split(double(uv.y) * image.height()).index, image.height(), sampler.wrap_v);
  return texel_value(image(int(x), image.height() - 1 - int(y)));
}

// Texture2D::sample on a pyramid of either storage.
template <class Texel>
[[gnu::always_inline]] inline glm::vec4 sample_levels(const std::vector<Image<Texel>>& levels, const Sampler& sampler,
                                                      glm::vec2 uv, float lod) {
  switch (sampler.filter) {
    case Filter::nearest:
      return nearest_sample(levels.front(), sampler, uv);
    case Filter::bilinear:
      return bilinear_sample(levels.front(), sampler, uv);
    case Filter::trilinear:
      break;
  }
  const float last = float(levels.size() - 1);
  const float clamped = lod > 0.f ? std::min(lod, last) : 0.f;  // NaN and -infinity read level 0
  const int lower = int(clamped);
  const float blend = clamped - float(lower);
  // The two levels' samples inlined here: as calls, their results went through memory.
  const glm::vec4 near = bilinear_sample(levels[size_t(lower)], sampler, uv);
  if (blend == 0.f) return near;
  return glm::mix(near, bilinear_sample(levels[size_t(lower) + 1], sampler, uv), blend);
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

// The filter works on texels as stored: floats as they are, 8-bit values in [0, 255]; a float result is stored as
// is, an 8-bit one rounded to nearest, halves up (GL's unorm conversion).
inline glm::vec4 filter_value(const glm::vec4& texel) { return texel; }
inline glm::vec4 filter_value(const glm::u8vec4& texel) { return glm::vec4(texel); }
inline void store(const glm::vec4& value, glm::vec4& texel) { texel = value; }
inline void store(const glm::vec4& value, glm::u8vec4& texel) {
  texel = glm::u8vec4(glm::clamp(value + 0.5f, glm::vec4(0.f), glm::vec4(255.f)));
}

// The next MIPmap level: reduce along x, then along y (separable, so even sizes give the notes' 2x2 average). Row
// by row, the x-reduced rows in a 3-row cache (an output row reads source rows 2y..2y+2), so no image-sized
// intermediate is allocated.
template <class Texel>
Image<Texel> reduce(const Image<Texel>& image) {
  const std::vector<Taps> tx = reduction_taps(image.width()), ty = reduction_taps(image.height());
  Image<Texel> out(int(tx.size()), int(ty.size()));
  std::vector<glm::vec4> cache[3];
  int cached[3] = {-1, -1, -1};
  const auto reduced_row = [&](int y) -> const std::vector<glm::vec4>& {
    const size_t slot = size_t(y % 3);
    std::vector<glm::vec4>& row = cache[slot];
    if (cached[slot] == y) return row;
    row.resize(tx.size());
    const Texel* source = image.row(y);
    for (size_t x = 0; x < tx.size(); ++x) {
      const Taps& t = tx[x];
      row[x] = filter_value(source[t.index[0]]) * t.weight[0] + filter_value(source[t.index[1]]) * t.weight[1] +
               filter_value(source[t.index[2]]) * t.weight[2];
    }
    cached[slot] = y;
    return row;
  };
  for (int y = 0; y < out.height(); ++y) {
    const Taps& t = ty[size_t(y)];
    const std::vector<glm::vec4>& r0 = reduced_row(t.index[0]);
    const std::vector<glm::vec4>& r1 = reduced_row(t.index[1]);
    const std::vector<glm::vec4>& r2 = reduced_row(t.index[2]);
    Texel* row = out.row(y);
    for (int x = 0; x < out.width(); ++x)
      store(r0[size_t(x)] * t.weight[0] + r1[size_t(x)] * t.weight[1] + r2[size_t(x)] * t.weight[2], row[x]);
  }
  return out;
}

template <class Texel>
void check_nonempty(const Image<Texel>& image, const char* what) {
  if (image.empty()) throw InvalidInput(fmt::format("{}: the image is empty", what));
}

template <class Texel>
std::vector<Image<Texel>> mipmaps(Image<Texel> image) {
  check_nonempty(image, "build_mipmaps");
  std::vector<Image<Texel>> levels;
  levels.push_back(std::move(image));
  while (levels.back().width() > 1 || levels.back().height() > 1) levels.push_back(reduce(levels.back()));
  return levels;
}

template <class Texel>
size_t level_bytes(const std::vector<Image<Texel>>& levels) {
  size_t bytes = 0;
  for (const Image<Texel>& level : levels) bytes += level.pixels().size_bytes();
  return bytes;
}

}  // namespace

std::vector<ImageRGBA> build_mipmaps(ImageRGBA image) { return mipmaps(std::move(image)); }
std::vector<ImageRGBA8> build_mipmaps(ImageRGBA8 image) { return mipmaps(std::move(image)); }

Texture2D::Texture2D(ImageRGBA image, const Sampler& sampler)
    : width_(image.width()), height_(image.height()), sampler_(sampler) {
  check_nonempty(image, "Texture2D");
  levels_ = build_mipmaps(std::move(image));
}

Texture2D::Texture2D(ImageRGBA8 image, const Sampler& sampler)
    : width_(image.width()), height_(image.height()), rgba8_(true), sampler_(sampler) {
  check_nonempty(image, "Texture2D");
  levels8_ = build_mipmaps(std::move(image));
}

size_t Texture2D::bytes() const { return rgba8_ ? level_bytes(levels8_) : level_bytes(levels_); }

void Texture2D::check_level(int i) const {
  if (i < 0 || i >= levels()) throw InvalidInput(fmt::format("MIPmap level {} is outside [0, {})", i, levels()));
}

ImageRGBA Texture2D::level(int i) const {
  check_level(i);
  if (!rgba8_) return levels_[size_t(i)];
  const ImageRGBA8& stored = levels8_[size_t(i)];
  ImageRGBA out(stored.width(), stored.height());
  std::transform(stored.pixels().begin(), stored.pixels().end(), out.pixels().begin(),
                 [](const glm::u8vec4& texel) { return texel_value(texel); });
  return out;
}

const ImageRGBA8& Texture2D::level_rgba8(int i) const {
  if (!rgba8_) throw InvalidInput("level_rgba8: the texture stores float texels");
  check_level(i);
  return levels8_[size_t(i)];
}

glm::vec4 Texture2D::nearest(glm::vec2 uv, int level) const {
  return rgba8_ ? nearest_sample(levels8_[size_t(level)], sampler_, uv)
                : nearest_sample(levels_[size_t(level)], sampler_, uv);
}

glm::vec4 Texture2D::bilinear(glm::vec2 uv, int level) const {
  return rgba8_ ? bilinear_sample(levels8_[size_t(level)], sampler_, uv)
                : bilinear_sample(levels_[size_t(level)], sampler_, uv);
}

// One branch on the storage per sample, not per texel (measured in docs/image.md).
glm::vec4 Texture2D::sample(glm::vec2 uv, float lod) const {
  return rgba8_ ? sample_levels(levels8_, sampler_, uv, lod) : sample_levels(levels_, sampler_, uv, lod);
}

void Texture2D::sample_lanes(const float* u, const float* v, const float* lod, float* const out[4], int count) const {
  static const bool avx2 = simd_level() >= SimdLevel::avx2;
  if (avx2 && rgba8_ && sampler_.filter != Filter::nearest && sampler_.wrap_u != Wrap::mirror &&
      sampler_.wrap_v != Wrap::mirror && count % 8 == 0 && size_t(width_) * size_t(height_) < (size_t(1) << 31)) {
    sample_lanes_avx2(*this, u, v, lod, out, count);
    return;
  }
  for (int k = 0; k < count; ++k) {
    const glm::vec4 c = sample(glm::vec2(u[k], v[k]), lod[k]);
    out[0][k] = c.x, out[1][k] = c.y, out[2][k] = c.z, out[3][k] = c.w;
  }
}

float Texture2D::lod(glm::vec2 duv_dx, glm::vec2 duv_dy) const {
  const glm::vec2 size{float(width()), float(height())};
  const float rho = std::max(glm::length(duv_dx * size), glm::length(duv_dy * size));
  return std::log2(rho);
}

Texture2D load_texture(const std::filesystem::path& path, const Sampler& sampler) {
  return std::visit([&](auto&& image) { return Texture2D(std::move(image), sampler); }, read_image_native(path));
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

EnvironmentMap::EnvironmentMap(ImageRGBA8 latlong, Filter filter)
    : texture_(std::move(latlong), Sampler{Wrap::repeat, Wrap::clamp, filter}) {}

EnvironmentMap load_environment_map(const std::filesystem::path& path, Filter filter) {
  return std::visit([&](auto&& image) { return EnvironmentMap(std::move(image), filter); }, read_image_native(path));
}

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
    case CubeFace::pos_x:
      return {1.f, -tc, -sc};
    case CubeFace::neg_x:
      return {-1.f, -tc, sc};
    case CubeFace::pos_y:
      return {sc, 1.f, tc};
    case CubeFace::neg_y:
      return {sc, -1.f, -tc};
    case CubeFace::pos_z:
      return {sc, -tc, 1.f};
    case CubeFace::neg_z:
      return {-sc, -tc, -1.f};
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
