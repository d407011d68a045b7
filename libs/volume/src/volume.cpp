#include "tessera/volume/volume.hpp"

#include <array>
#include <cmath>
#include <utility>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "tessera/core/parallel.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {

std::string voxel_type_name(VoxelType type) {
  switch (type) {
    case VoxelType::uint8:
      return "uint8";
    case VoxelType::uint16:
      return "uint16";
    case VoxelType::int16:
      return "int16";
    case VoxelType::float32:
      return "float32";
  }
  return "?";
}

VoxelType parse_voxel_type(const std::string& name) {
  if (name == "uint8" || name == "uchar" || name == "unsigned char" || name == "uint8_t") return VoxelType::uint8;
  if (name == "uint16" || name == "ushort" || name == "unsigned short" || name == "uint16_t" ||
      name == "unsigned short int")
    return VoxelType::uint16;
  if (name == "int16" || name == "short" || name == "signed short" || name == "int16_t" || name == "short int")
    return VoxelType::int16;
  if (name == "float32" || name == "float") return VoxelType::float32;
  throw InvalidInput(
      fmt::format("unknown voxel type '{}' (expected uint8, uint16, int16 or float32)", printable(name)));
}

size_t voxel_size(VoxelType type) {
  switch (type) {
    case VoxelType::uint8:
      return 1;
    case VoxelType::uint16:
    case VoxelType::int16:
      return 2;
    case VoxelType::float32:
      return 4;
  }
  return 0;
}

uint64_t checked_voxel_count(const glm::ivec3& dims) {
  if (dims.x < 1 || dims.y < 1 || dims.z < 1)
    throw InvalidInput(fmt::format("volume dimensions must be positive, got {}x{}x{}", dims.x, dims.y, dims.z));
  // Each factor is < 2^31, so the product of two fits in 64 bits; check before the third multiplication.
  const uint64_t xy = uint64_t(dims.x) * uint64_t(dims.y);
  if (xy > kMaxVoxels || xy * uint64_t(dims.z) > kMaxVoxels)
    throw InvalidInput(
        fmt::format("volume dimensions {}x{}x{} exceed the limit of {} voxels", dims.x, dims.y, dims.z, kMaxVoxels));
  return xy * uint64_t(dims.z);
}

VoxelType voxel_type(const AnyVolume& v) { return VoxelType(v.index()); }

Volume<float> to_float(const AnyVolume& any) {
  return std::visit(
      [](const auto& v) {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, Volume<float>>) {
          return v;
        } else {
          Volume<float> out(v.dims(), 0.0f, v.spacing(), v.origin());
          std::transform(v.voxels().begin(), v.voxels().end(), out.voxels().begin(), [](auto x) { return float(x); });
          return out;
        }
      },
      any);
}

Volume<float> to_float(AnyVolume&& any) {
  if (auto* v = std::get_if<Volume<float>>(&any)) return std::move(*v);
  Volume<float> out = to_float(std::as_const(any));
  any = AnyVolume();  // the integer voxels are freed now, not when the caller's variable goes
  return out;
}

const glm::ivec3& dims_of(const AnyVolume& v) {
  return std::visit([](const auto& x) -> const glm::ivec3& { return x.dims(); }, v);
}
const Vec3& spacing_of(const AnyVolume& v) {
  return std::visit([](const auto& x) -> const Vec3& { return x.spacing(); }, v);
}
const Vec3& origin_of(const AnyVolume& v) {
  return std::visit([](const auto& x) -> const Vec3& { return x.origin(); }, v);
}

namespace {

/// Float min/max in parallel blocks, 4 x 4 lanes at a time (the renderer's prepare step begins with it; the scalar
/// minmax_element was a sixth of that step). Returns false when a NaN is present: minmax_element then decides,
/// because its result depends on where the NaNs are.
bool float_range(std::span<const float> values, float& lo, float& hi) {
#if defined(__SSE2__)
  constexpr int64_t kBlock = 1 << 16;
  const int64_t n = int64_t(values.size()), blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::array<float, 3>> part(static_cast<size_t>(blocks));  // min, max, NaN seen
  parallel_for(0, blocks, 1, [&](int64_t b0, int64_t b1) {
    for (int64_t b = b0; b < b1; ++b) {
      const float* p = values.data() + b * kBlock;
      const int64_t m = std::min(kBlock, n - b * kBlock);
      __m128 mn[4], mx[4];
      for (int k = 0; k < 4; ++k) mn[k] = _mm_set1_ps(INFINITY), mx[k] = _mm_set1_ps(-INFINITY);
      __m128 nan = _mm_setzero_ps();
      int64_t i = 0;
      for (; i + 16 <= m; i += 16)
        for (int k = 0; k < 4; ++k) {
          const __m128 x = _mm_loadu_ps(p + i + 4 * k);
          mn[k] = _mm_min_ps(mn[k], x);
          mx[k] = _mm_max_ps(mx[k], x);
          nan = _mm_or_ps(nan, _mm_cmpunord_ps(x, x));
        }
      alignas(16) std::array<float, 4> a, c;
      _mm_store_ps(a.data(), _mm_min_ps(_mm_min_ps(mn[0], mn[1]), _mm_min_ps(mn[2], mn[3])));
      _mm_store_ps(c.data(), _mm_max_ps(_mm_max_ps(mx[0], mx[1]), _mm_max_ps(mx[2], mx[3])));
      float l = std::min({a[0], a[1], a[2], a[3]}), h = std::max({c[0], c[1], c[2], c[3]});
      bool has_nan = _mm_movemask_ps(nan) != 0;
      for (; i < m; ++i) {
        has_nan |= std::isnan(p[i]);
        l = std::min(l, p[i]);
        h = std::max(h, p[i]);
      }
      part[size_t(b)] = {l, h, has_nan ? 1.0f : 0.0f};
    }
  });
  lo = INFINITY;
  hi = -INFINITY;
  for (const auto& [l, h, has_nan] : part) {
    if (has_nan != 0) return false;
    lo = std::min(lo, l);
    hi = std::max(hi, h);
  }
  return true;
#else
  (void)values, (void)lo, (void)hi;
  return false;
#endif
}

}  // namespace

template <class T>
std::pair<double, double> value_range(const Volume<T>& v) {
  if (v.empty()) throw InvalidInput("value range of an empty volume");
  if constexpr (std::is_same_v<T, float>) {
    float lo, hi;
    if (float_range(v.voxels(), lo, hi)) return {double(lo), double(hi)};
  }
  const auto [lo, hi] = std::minmax_element(v.voxels().begin(), v.voxels().end());
  return {double(*lo), double(*hi)};
}

template <class T>
std::vector<uint64_t> histogram(const Volume<T>& v, int bins, double lo, double hi) {
  if (bins < 1 || !(lo < hi))
    throw InvalidInput(fmt::format("histogram needs bins >= 1 and lo < hi, got {} bins over [{}, {}]", bins, lo, hi));
  std::vector<uint64_t> counts(size_t(bins), 0);
  const double scale = double(bins) / (hi - lo);
  for (const T x : v.voxels()) {
    const double b = std::floor((double(x) - lo) * scale);
    counts[size_t(std::clamp(b, 0.0, double(bins - 1)))]++;
  }
  return counts;
}

Axis parse_axis(const std::string& text) {
  if (text == "x" || text == "X") return Axis::x;
  if (text == "y" || text == "Y") return Axis::y;
  if (text == "z" || text == "Z") return Axis::z;
  throw InvalidInput(fmt::format("axis: expected x, y or z, got '{}'", text));
}

template <class T>
DepthImage slice(const Volume<T>& v, Axis axis, int index) {
  const glm::ivec3 d = v.dims();
  const int a = int(axis);
  if (index < 0 || index >= d[a])
    throw InvalidInput(fmt::format("slice {} is outside the volume's {} range [0, {})", index, "xyz"[a], d[a]));
  const int w = axis == Axis::x ? d.y : d.x, h = axis == Axis::z ? d.y : d.z;
  DepthImage out(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      out(i, j) = float(axis == Axis::z ? v(i, j, index) : axis == Axis::y ? v(i, index, j) : v(index, i, j));
  return out;
}

#define TESSERA_VOLUME_INSTANTIATE(T)                                              \
  template std::pair<double, double> value_range(const Volume<T>&);                \
  template std::vector<uint64_t> histogram(const Volume<T>&, int, double, double); \
  template DepthImage slice(const Volume<T>&, Axis, int);
TESSERA_VOLUME_INSTANTIATE(uint8_t)
TESSERA_VOLUME_INSTANTIATE(uint16_t)
TESSERA_VOLUME_INSTANTIATE(int16_t)
TESSERA_VOLUME_INSTANTIATE(float)
#undef TESSERA_VOLUME_INSTANTIATE

}  // namespace tessera
