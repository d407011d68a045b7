#include "tessera/volume/volume_render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/cpu.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {

TransferFunction::TransferFunction(std::vector<Point> points) : points_(std::move(points)) {
  if (points_.empty()) throw InvalidInput("a transfer function needs at least one point");
  for (const auto& p : points_) {
    if (!std::isfinite(p.value)) throw InvalidInput(fmt::format("point value {} is not finite", p.value));
    for (int k = 0; k < 3; ++k)
      if (!(p.color[k] >= 0 && p.color[k] <= kMaxColor))
        throw InvalidInput(fmt::format("color component {} is outside [0, {}]", p.color[k], kMaxColor));
    if (!(p.opacity >= 0 && p.opacity <= 1)) throw InvalidInput(fmt::format("opacity {} is outside [0, 1]", p.opacity));
  }
  std::stable_sort(points_.begin(), points_.end(), [](const Point& a, const Point& b) { return a.value < b.value; });
}

Vec4f TransferFunction::operator()(float v) const {
  if (points_.empty()) return Vec4f(0.0f);
  if (v <= points_.front().value) return Vec4f(points_.front().color, points_.front().opacity);
  if (v >= points_.back().value) return Vec4f(points_.back().color, points_.back().opacity);
  const auto hi = std::upper_bound(points_.begin(), points_.end(), v, [](float x, const Point& p) { return x < p.value; });
  const auto lo = hi - 1;
  // In double: the difference of two finite floats can overflow a float (values of both signs near its limit).
  const float t = float((double(v) - lo->value) / (double(hi->value) - lo->value));
  return Vec4f(glm::mix(lo->color, hi->color, t), lo->opacity + t * (hi->opacity - lo->opacity));
}

float TransferFunction::max_opacity(float lo, float hi) const {
  float m = std::max((*this)(lo).w, (*this)(hi).w);
  for (const auto& p : points_)
    if (p.value >= lo && p.value <= hi) m = std::max(m, p.opacity);
  return m;
}

ValueProfile profile_values(const Volume<float>& volume) {
  if (volume.empty()) throw InvalidInput("cannot profile an empty volume");
  ValueProfile p;
  std::tie(p.lo, p.hi) = value_range(volume);
  p.diagonal = glm::length(volume.to_world(Vec3(volume.dims() - 1)) - volume.origin());
  p.threshold = p.median = p.top = p.hi;
  if (!(p.hi > p.lo)) return p;
  // Otsu's histogram spans [lo, the 99th percentile], values above counting in its last bin: the long tail of a
  // skewed field, such as the metaballs' centres, would otherwise squeeze the rest into one bin. Percentiles are
  // numpy's "lower" ones (the element at floor(f (n - 1)) in sorted order), found by selection in a copy.
  std::vector<float> values(volume.voxels().begin(), volume.voxels().end());
  const auto percentile = [](std::vector<float>::iterator first, std::vector<float>::iterator last, double f) {
    const auto at = first + std::ptrdiff_t(f * double(last - first - 1));
    std::nth_element(first, at, last);
    return double(*at);
  };
  const double p99 = percentile(values.begin(), values.end(), 0.99);
  const double span_hi = p99 > p.lo ? p99 : p.hi;
  constexpr int kBins = 1024;
  const std::vector<uint64_t> counts = histogram(volume, kBins, p.lo, span_hi);
  // Otsu's method: the split of the histogram that maximizes the between-class variance w0 w1 (m0 - m1)^2.
  double total = 0, total_moment = 0;
  for (int b = 0; b < kBins; ++b) {
    total += double(counts[size_t(b)]);
    total_moment += double(b) * double(counts[size_t(b)]);
  }
  double w0 = 0, moment0 = 0, best = -1;
  int split = 0;  // the last bin of the background
  for (int b = 0; b + 1 < kBins; ++b) {
    w0 += double(counts[size_t(b)]);
    moment0 += double(b) * double(counts[size_t(b)]);
    const double w1 = total - w0;
    if (w0 == 0 || w1 == 0) continue;
    const double d = moment0 / w0 - (total_moment - moment0) / w1;
    const double variance = w0 * w1 * d * d;
    if (variance > best) best = variance, split = b;
  }
  p.threshold = p.lo + (split + 1) * (span_hi - p.lo) / kBins;
  // The object's median and top (99.5th percentile) among the values above the threshold.
  const auto object = std::partition(values.begin(), values.end(), [&](float x) { return !(x > p.threshold); });
  if (object != values.end()) {
    p.median = percentile(object, values.end(), 0.5);
    p.top = percentile(object, values.end(), 0.995);
  }
  return p;
}

namespace {

/// A control point on the object's scale of a profile: position s (ValueProfile::value_at), color, and opacity per
/// kReferenceDiagonal-th of the diagonal.
struct ScalePoint {
  double s;
  Vec3f color;
  double opacity;
};

/// The transfer function of scale points on a volume of profile `p`.
TransferFunction on_scale(const std::vector<ScalePoint>& points, const ValueProfile& p) {
  // Opacity per reference length -> per world unit: 1 - (1 - a)^(kReferenceDiagonal / diagonal).
  const double exponent = TransferFunction::kReferenceDiagonal / std::max(p.diagonal, 1e-30);
  std::vector<TransferFunction::Point> out;
  for (const auto& q : points)
    out.push_back({float(p.value_at(q.s)), q.color, float(std::clamp(1 - std::pow(1 - q.opacity, exponent), 0.0, 1.0))});
  return TransferFunction(std::move(out));
}

/// The presets on the object's scale. They were made for headsq (CT, 12-bit: threshold 644.8, top 2529) and the
/// clinical MRI head of the shared data (8-bit: 62.2, 255), where they give the values of the ramps first written for
/// them (bone from 1000 over 1150 to 2000, skin from 400 to 600 and 1100 to 1300, MRI from 40 to 90 and 255).
const std::vector<std::pair<std::string, std::vector<ScalePoint>>>& preset_table() {
  static const std::vector<std::pair<std::string, std::vector<ScalePoint>>> table = {
      {"ct-bone", {{0.19, {0.9f, 0.6f, 0.4f}, 0}, {0.27, {0.95f, 0.9f, 0.8f}, 0.6}, {0.72, {1, 1, 0.95f}, 0.9}}},
      {"ct-skin",
       {{-0.13, {0.8f, 0.5f, 0.4f}, 0}, {-0.02, {0.9f, 0.7f, 0.6f}, 0.15}, {0.24, {0.9f, 0.7f, 0.6f}, 0.15},
        {0.35, {1, 1, 0.95f}, 0.8}}},
      {"mri", {{-0.12, {0.5f, 0.3f, 0.3f}, 0}, {0.14, {0.9f, 0.75f, 0.6f}, 0.1}, {1.0, {1, 1, 1}, 0.5}}},
  };
  return table;
}

}  // namespace

const std::vector<std::string>& TransferFunction::preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, points] : preset_table()) n.push_back(name);
    return n;
  }();
  return names;
}

TransferFunction TransferFunction::preset(const std::string& name, const ValueProfile& profile) {
  for (const auto& [key, points] : preset_table()) {
    if (key != name) continue;
    if (!profile.separable())
      throw InvalidInput(fmt::format("preset '{}' cannot apply: every voxel has the value {}, so there is no tissue to "
                                     "tell from the background (use --tf or the default transfer function)",
                                     name, profile.lo));
    return on_scale(points, profile);
  }
  throw InvalidInput(fmt::format("unknown transfer-function preset '{}' ({})", name, fmt::join(preset_names(), ", ")));
}

TransferFunction TransferFunction::automatic(const ValueProfile& profile) {
  if (!profile.separable())  // a constant volume: its box as a light haze
    return on_scale({{0, {0.9f, 0.8f, 0.7f}, 0.02}}, profile);
  // On the object's scale, with its median in the middle of the ramp: skewed fields keep most of their object
  // translucent instead of crowding it into the ramp's first steps.
  const double median = (profile.median - profile.threshold) / (profile.top - profile.threshold);
  return on_scale({{0, {0.8f, 0.35f, 0.2f}, 0}, {median, {0.95f, 0.7f, 0.45f}, 0.05}, {1, {1, 0.97f, 0.92f}, 0.3}},
                  profile);
}

namespace {

/// A point from its five numbers (value, r, g, b, opacity) as parsed, refusing a value beyond float's range (its
/// conversion would be undefined) with a message naming `where`; the constructor checks the rest.
TransferFunction::Point point_of(const double (&v)[5], const std::string& where) {
  for (int k = 0; k < 5; ++k)
    if (!(std::fabs(v[k]) <= std::numeric_limits<float>::max()))
      throw InvalidInput(fmt::format("{}: {} does not fit a float", where, v[k]));
  return {float(v[0]), {float(v[1]), float(v[2]), float(v[3])}, float(v[4])};
}

}  // namespace

TransferFunction TransferFunction::from_json(const std::string& text, const std::string& name) {
  try {
    const auto j = nlohmann::json::parse(text);
    std::vector<Point> points;
    for (const auto& p : j.at("points")) {
      if (!p.is_array() || p.size() != 5) throw InvalidInput(fmt::format("{}: each point is [value, r, g, b, opacity]", name));
      const double v[5] = {p[0].get<double>(), p[1].get<double>(), p[2].get<double>(), p[3].get<double>(),
                           p[4].get<double>()};
      points.push_back(point_of(v, name));
    }
    return TransferFunction(std::move(points));
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(fmt::format("{}: {}", name, e.what()));
  }
}

TransferFunction TransferFunction::from_csv(const std::string& text, const std::string& name) {
  std::vector<Point> points;
  std::istringstream in(text);
  long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = at_line(name, line_no);
    const auto v = parse_doubles(t, 5, where);
    points.push_back(point_of({v[0], v[1], v[2], v[3], v[4]}, where));
  }
  return TransferFunction(std::move(points));
}

TransferFunction TransferFunction::load(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  return path.extension() == ".json" ? from_json(text, path.string()) : from_csv(text, path.string());
}

namespace {

using Corner = std::array<int16_t, 4>;  // quantized value, gradient x, y, z

/// Rounds to the nearest int16 (halves away from zero), saturating; NaN gives 0: no value reaching here converts
/// to an integer out of range or from a non-finite float (undefined behaviour).
int16_t quantize(double x) {
  if (!(x > -32768.5)) return x < 0 ? INT16_MIN : 0;
  if (!(x < 32767.5)) return INT16_MAX;
  return int16_t(int(x + (x >= 0 ? 0.5 : -0.5)));
}

/// The volume as the ray caster reads it: per voxel the value and the central-difference gradient (world units),
/// each quantized to 16 bits and interleaved, so that one 8-byte load per cell corner gives everything a shaded
/// sample needs (VTK's fixed-point mapper also works on 16-bit values with precomputed gradients). Built once per
/// VolumeRenderer instead of six extra trilinear samples per step.
///
/// The scales are in double: a float range below ~2e-34 makes 65535 / (hi - lo) overflow a float, and one beyond
/// float's limit (values of both signs near 3e38) makes hi - lo overflow; in double both are finite for any two
/// finite floats, so a tiny range spans the 65536 levels as a unit range does, and a huge one is not flattened.
struct PackedVolume {
  glm::ivec3 dims;
  size_t stride_y, stride_z;
  double value_scale;     ///< quantized = (v - lo) * value_scale - 32768
  double gradient_scale;  ///< quantized = g * gradient_scale (g in world units)
  RawVector<Corner> voxels;

  PackedVolume(const Volume<float>& v, double lo, double hi)
      : dims(v.dims()), stride_y(size_t(dims.x)), stride_z(size_t(dims.x) * size_t(dims.y)) {
    value_scale = hi > lo ? 65535.0 / (hi - lo) : 0.0;
    // No gradient component exceeds (hi - lo) / (smallest spacing) (a one-sided difference across the whole range):
    // that bound sets the gradient's scale, so no pass is spent finding the actual largest one. The differences are
    // multiplied by smallest spacing / (n spacing) (at most 1) and 32767 / (hi - lo): no product overflows, even
    // where the gradient itself would (huge values over tiny spacings).
    const Vec3 sp = v.spacing();
    const double min_spacing = std::min({sp.x, sp.y, sp.z});
    const double per_range = hi > lo ? 32767.0 / (hi - lo) : 0.0;
    gradient_scale = per_range * min_spacing;
    // 8 bytes a voxel beside the float volume's 4: checked against the memory budget before it is allocated.
    MemoryBudget::check(saturating_product({uint64_t(v.voxel_count()), sizeof(Corner)}),
                        fmt::format("volume render: values and gradients of {}x{}x{} voxels", dims.x, dims.y, dims.z));
    voxels.resize(v.voxel_count());
    // Per axis: the factor of a difference over n voxels is per_range * min_spacing / (n spacing).
    const Vec3 unit = per_range * (min_spacing / sp);
    parallel_for(0, dims.z, 1, [&](int64_t z0, int64_t z1) {
      for (int z = int(z0); z < int(z1); ++z)
        for (int y = 0; y < dims.y; ++y) pack_row(v, y, z, unit, lo, &voxels[v.index(0, y, z)]);
    });
  }

  /// Packs row (y, z): value and Volume::gradient (central differences, one-sided on the border) quantized, in one
  /// pass without Volume::gradient's per-voxel clamps (only the row's two ends are border voxels along x). `unit`
  /// is the quantized gradient of a difference of 1 across one voxel, per axis.
  void pack_row(const Volume<float>& v, int y, int z, const Vec3& unit, double lo, Corner* out) const {
    const glm::ivec3 d = v.dims();
    const float* row = &v(0, y, z);
    const int y0 = std::max(y - 1, 0), y1 = std::min(y + 1, d.y - 1), z0 = std::max(z - 1, 0), z1 = std::min(z + 1, d.z - 1);
    const float* ylo = &v(0, y0, z);
    const float* yhi = &v(0, y1, z);
    const float* zlo = &v(0, y, z0);
    const float* zhi = &v(0, y, z1);
    const double sy = y1 > y0 ? unit.y / (y1 - y0) : 0.0, sz = z1 > z0 ? unit.z / (z1 - z0) : 0.0;
    const auto pack = [&](int x, int x0, int x1, double sx) {
      const double level = (double(row[x]) - lo) * value_scale;  // in [0, 65535] for values in [lo, hi]
      out[x] = {int16_t(int(level >= 0 ? std::min(level, 65535.0) + 0.5 : 0.0) - 32768),
                quantize((double(row[x1]) - row[x0]) * sx), quantize((double(yhi[x]) - ylo[x]) * sy),
                quantize((double(zhi[x]) - zlo[x]) * sz)};
    };
    const auto border = [&](int x) {
      const int x0 = std::max(x - 1, 0), x1 = std::min(x + 1, d.x - 1);
      pack(x, x0, x1, x1 > x0 ? unit.x / (x1 - x0) : 0.0);
    };
    border(0);
    const double sx = unit.x / 2;
    for (int x = 1; x + 1 < d.x; ++x) pack(x, x - 1, x + 1, sx);
    if (d.x > 1) border(d.x - 1);
  }

  /// The cell holding voxel coordinates p (clamped to the grid; its lower corner) and p's offset in it.
  glm::ivec3 locate(const Vec3f& p, Vec3f& offset) const {
    const Vec3f q = glm::clamp(p, Vec3f(0.0f), Vec3f(dims - 1));
    const glm::ivec3 cell = glm::min(glm::ivec3(q), glm::max(dims - 2, 0));
    offset = q - Vec3f(cell);
    return cell;
  }
  /// Memory offsets of a cell's corners from its lower corner (0 along an axis of one voxel).
  glm::ivec3 corner_steps() const {
    return {dims.x > 1 ? 1 : 0, dims.y > 1 ? int(stride_y) : 0, dims.z > 1 ? int(stride_z) : 0};
  }

  /// Trilinear (value, gradient) in quantized units at `offset` in `cell`.
  Vec4f interpolate(const glm::ivec3& cell, const Vec3f& offset) const {
    const glm::ivec3 st = corner_steps();
    const size_t dx = size_t(st.x), dy = size_t(st.y), dz = size_t(st.z);
    const Corner* c = voxels.data() + size_t(cell.x) + stride_y * size_t(cell.y) + stride_z * size_t(cell.z);
#if defined(__SSE2__)
    // Four components at once: sign-extend the four int16 of a corner to floats, then seven lerps.
    const auto load = [](const Corner& a) {
      const __m128i x = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(a.data()));
      return _mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(x, x), 16));
    };
    const auto lerp = [](__m128 a, __m128 b, __m128 t) { return _mm_add_ps(a, _mm_mul_ps(t, _mm_sub_ps(b, a))); };
    const __m128 tx = _mm_set1_ps(offset.x), ty = _mm_set1_ps(offset.y), tz = _mm_set1_ps(offset.z);
    const __m128 c00 = lerp(load(c[0]), load(c[dx]), tx), c10 = lerp(load(c[dy]), load(c[dy + dx]), tx);
    const __m128 c01 = lerp(load(c[dz]), load(c[dz + dx]), tx), c11 = lerp(load(c[dz + dy]), load(c[dz + dy + dx]), tx);
    alignas(16) float out[4];
    _mm_store_ps(out, lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz));
    return Vec4f(out[0], out[1], out[2], out[3]);
#else
    const auto load = [](const Corner& a) { return Vec4f(a[0], a[1], a[2], a[3]); };
    const auto lerp = [](const Vec4f& a, const Vec4f& b, float t) { return a + t * (b - a); };
    const Vec4f c00 = lerp(load(c[0]), load(c[dx]), offset.x), c10 = lerp(load(c[dy]), load(c[dy + dx]), offset.x);
    const Vec4f c01 = lerp(load(c[dz]), load(c[dz + dx]), offset.x);
    const Vec4f c11 = lerp(load(c[dz + dy]), load(c[dz + dy + dx]), offset.x);
    return lerp(lerp(c00, c10, offset.y), lerp(c01, c11, offset.y), offset.z);
#endif
  }
};

/// The transfer function tabulated over the value range (16384 entries, the nearest one is used: 256 KiB, which
/// stays in the L2 cache, where a table per quantized value missed it), with each entry's opacity already corrected
/// to the step (alpha = 1 - (1 - opacity)^step): a sample costs one lookup instead of a search and a pow.
struct TransferTable {
  static constexpr int kSize = 16384;
  static constexpr float kScale = float(kSize - 1) / 65535.0f;  ///< entry = (quantized + 32768) * kScale, rounded
  std::vector<Vec4f> entries;    ///< rgb, alpha per step
  std::vector<int> lit_before;  ///< entries with a non-zero alpha before entry i (for any_lit)

  TransferTable(const TransferFunction& tf, double lo, double hi, float step) : entries(kSize), lit_before(kSize + 1, 0) {
    // In double: hi - lo of two finite floats can overflow a float; each entry's value lies in [lo, hi].
    const double span = hi > lo ? hi - lo : 0.0;
    for (int i = 0; i < kSize; ++i) {
      const Vec4f c = tf(float(lo + span * i / (kSize - 1)));
      // 1 - (1 - a)^step in double, as -expm1(step log1p(-a)): in float, 1 - pow rounds to 0 for small steps and
      // the volume would vanish.
      const double alpha = c.w >= 1 ? 1.0 : -std::expm1(double(step) * std::log1p(-double(c.w)));
      entries[size_t(i)] = Vec4f(Vec3f(c), float(alpha));
      lit_before[size_t(i) + 1] = lit_before[size_t(i)] + (entries[size_t(i)].w > 0);
    }
  }
  /// The entry of an interpolated quantized value (in [-32768, 32767]).
  static int index(float quantized) { return std::clamp(int((quantized + 32768.0f) * kScale + 0.5f), 0, kSize - 1); }
  const Vec4f& operator()(float quantized) const { return entries[size_t(index(quantized))]; }
  /// Whether some value in quantized [lo, hi] has a non-zero alpha (interpolated values stay in that range).
  bool any_lit(int lo, int hi) const { return lit_before[size_t(index(float(hi))) + 1] > lit_before[size_t(index(float(lo)))]; }
};

/// Empty flags per block of `block` cells per side: a block is empty when every table entry its voxels' quantized
/// range can reach has zero alpha, so skipping its samples leaves the image unchanged.
struct BlockGrid {
  int size;
  glm::ivec3 count;
  std::vector<int32_t> empty;                 ///< int32 so that 8 lanes can gather them
  std::array<std::vector<int32_t>, 3> of_cell;  ///< block coordinate of each cell coordinate, per axis

  BlockGrid(const PackedVolume& v, int block, const TransferTable& table) : size(block) {
    const glm::ivec3 d = v.dims;
    count = glm::max((d - 1 + block - 1) / block, glm::ivec3(1));
    empty.resize(size_t(count.x) * size_t(count.y) * size_t(count.z));
    parallel_for(0, count.z, 1, [&](int64_t b0, int64_t b1) {
      for (int bz = int(b0); bz < int(b1); ++bz)
        for (int by = 0; by < count.y; ++by)
          for (int bx = 0; bx < count.x; ++bx) {
            int lo = INT16_MAX, hi = INT16_MIN;
            for (int z = bz * block; z <= std::min((bz + 1) * block, d.z - 1); ++z)
              for (int y = by * block; y <= std::min((by + 1) * block, d.y - 1); ++y)
                for (int x = bx * block; x <= std::min((bx + 1) * block, d.x - 1); ++x) {
                  const int q = v.voxels[size_t(x) + v.stride_y * size_t(y) + v.stride_z * size_t(z)][0];
                  lo = std::min(lo, q);
                  hi = std::max(hi, q);
                }
            empty[index(glm::ivec3(bx, by, bz))] = !table.any_lit(lo, hi);
          }
    });
    for (int axis = 0; axis < 3; ++axis) {
      of_cell[size_t(axis)].resize(size_t(std::max(d[axis] - 1, 1)));
      for (int c = 0; c < int(of_cell[size_t(axis)].size()); ++c)
        of_cell[size_t(axis)][size_t(c)] = std::min(c / size, count[axis] - 1);
    }
  }
  size_t index(const glm::ivec3& b) const { return size_t(b.x) + size_t(count.x) * (size_t(b.y) + size_t(count.y) * size_t(b.z)); }
  /// The block of a cell (a table per axis: a division per axis and sample showed in the profile).
  glm::ivec3 block_of(const glm::ivec3& cell) const {
    return {of_cell[0][size_t(cell.x)], of_cell[1][size_t(cell.y)], of_cell[2][size_t(cell.z)]};
  }
  /// The sample parameter (in steps from `first`) where a ray first + s * delta leaves block b.
  float exit(const glm::ivec3& b, const Vec3f& first, const Vec3f& delta) const {
    float s = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
      if (delta[axis] > 0) s = std::min(s, (float((b[axis] + 1) * size) - first[axis]) / delta[axis]);
      if (delta[axis] < 0) s = std::min(s, (float(b[axis] * size) - first[axis]) / delta[axis]);
    }
    return s;
  }
};

/// c^shininess for c in [0, 1]: by repeated squaring when the exponent is a whole number up to 1024 (the usual
/// case), else from a table (the specular term is a pow per sample otherwise).
struct SpecularPower {
  static constexpr int kSize = 1024;
  int whole = 0;  ///< the exponent when it is a whole number in [1, 1024], else 0
  std::array<float, kSize + 1> values;
  explicit SpecularPower(float exponent) {
    if (exponent >= 1 && exponent <= 1024 && exponent == std::floor(exponent)) whole = int(exponent);
    for (int i = 0; i <= kSize; ++i) values[size_t(i)] = std::pow(float(i) / kSize, exponent);
  }
  float operator()(float c) const {
    c = std::clamp(c, 0.0f, 1.0f);
    if (whole) {
      float result = 1, base = c;
      for (int e = whole; e; e >>= 1, base *= base)
        if (e & 1) result *= base;
      return result;
    }
    const float s = c * kSize;
    const int i = std::min(int(s), kSize - 1);
    return values[size_t(i)] + (s - float(i)) * (values[size_t(i) + 1] - values[size_t(i)]);
  }
};

/// One ray's samples in voxel space: sample k < n is at first + k * delta, except that when the last segment is
/// shorter than a step (last_fraction < 1) the last sample is at the middle of that segment, `last_point`.
struct RaySamples {
  Vec3f first{0.0f}, delta{0.0f}, light{0.0f}, last_point{0.0f};
  int n = 0;
  float last_fraction = 0;  ///< the last segment's length in steps (at most 1)
  bool short_last() const { return last_fraction < 1; }
  /// Samples that are a whole step apart (the SIMD path marches these; the scalar one finishes the ray).
  int regular() const { return short_last() ? n - 1 : n; }
};

/// What every ray reads; march() is the scalar ray caster, march8 (AVX2) its eight-ray version.
struct Caster {
  const PackedVolume& volume;
  const TransferTable& table;
  const BlockGrid& blocks;
  const SpecularPower& power;
  const VolumeRenderOptions& options;
  float step;
  float min_gradient2;  ///< a gradient shorter than this (squared, quantized units) leaves the sample unshaded

  /// Composites samples k, k + 1, ... of `ray` onto (color, alpha) until the ray ends or is opaque.
  void march(const RaySamples& ray, int k, Vec3f& color, float& alpha) const {
    for (; k < ray.n && alpha < options.termination; ++k) {
      const bool last = k == ray.n - 1 && ray.short_last();
      const Vec3f p = last ? ray.last_point : ray.first + float(k) * ray.delta;
      Vec3f offset;
      const glm::ivec3 cell = volume.locate(p, offset);
      const glm::ivec3 b = blocks.block_of(cell);
      if (blocks.empty[blocks.index(b)]) {
        // Jump to the sample before the one where the ray leaves the block (the samples skipped are at least a
        // step inside it, so rounding cannot skip a sample of another block).
        const float exit = blocks.exit(b, ray.first, ray.delta);
        k = exit < float(ray.n) ? std::max(k, int(exit) - 1) : ray.n;
        continue;
      }
      // No branch on a clear sample (alpha 0 adds nothing): in noisy data its outcome is a coin toss.
      const Vec4f s = volume.interpolate(cell, offset);
      Vec4f c = table(s.x);
      if (last) c.w = float(-std::expm1(double(ray.last_fraction) * std::log1p(-double(c.w))));
      Vec3f rgb(c);
      if (options.shading) {
        const Vec3f g(s.y, s.z, s.w);
        const float len2 = glm::dot(g, g);
        const bool lit = len2 > min_gradient2;
        const float cosine = std::abs(glm::dot(g, ray.light)) / std::sqrt(lit ? len2 : 1.0f);  // Blinn: h = l
        const float shade = lit ? options.ambient + options.diffuse * cosine : 1.0f;
        const float highlight = lit ? options.specular * power(cosine) : 0.0f;
        rgb = rgb * shade + Vec3f(highlight);
      }
      color += (1 - alpha) * c.w * rgb;
      alpha += (1 - alpha) * c.w;
    }
  }
};

#if defined(__x86_64__) || defined(__i386__)
#define TESSERA_VOLUME_AVX2 1

[[gnu::target("avx2,fma")]] inline __m256 lerp(__m256 a, __m256 b, __m256 t) {
  return _mm256_fmadd_ps(t, _mm256_sub_ps(b, a), a);
}
/// The low and high int16 of each int32, as floats.
[[gnu::target("avx2,fma")]] inline __m256 low16(__m256i x) {
  return _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(x, 16), 16));
}
[[gnu::target("avx2,fma")]] inline __m256 high16(__m256i x) { return _mm256_cvtepi32_ps(_mm256_srai_epi32(x, 16)); }

/// march() for up to 8 rays at once (AVX2 + FMA): each lane keeps its own sample index, so empty-block jumps and
/// early termination stay per ray; the lanes' cell corners, table entries and block flags are gathered. Marches
/// the regular samples only and returns each lane's next sample in k[]; the caller finishes every ray with march()
/// (the shorter last segment). The same samples, skips and arithmetic as march(), up to rounding (FMA).
[[gnu::target("avx2,fma")]] void march8(const Caster& cast, const RaySamples* rays, int count, Vec3f* color,
                                        float* alpha, int* k_out) {
  alignas(32) float f[3][8] = {}, d[3][8] = {}, l[3][8] = {};
  alignas(32) int n[8] = {}, regular[8] = {};
  for (int i = 0; i < count; ++i) {
    for (int a = 0; a < 3; ++a) {
      f[a][i] = rays[i].first[a];
      d[a][i] = rays[i].delta[a];
      l[a][i] = rays[i].light[a];
    }
    n[i] = rays[i].n;
    regular[i] = rays[i].regular();
  }
  const PackedVolume& vol = cast.volume;
  const BlockGrid& blocks = cast.blocks;
  const VolumeRenderOptions& o = cast.options;
  __m256 first[3], delta[3], light[3], hi[3], inv_delta[3], forward[3], moving[3];
  __m256i max_cell[3];
  for (int a = 0; a < 3; ++a) {
    first[a] = _mm256_load_ps(f[a]);
    delta[a] = _mm256_load_ps(d[a]);
    inv_delta[a] = _mm256_div_ps(_mm256_set1_ps(1.0f), delta[a]);
    forward[a] = _mm256_and_ps(_mm256_cmp_ps(delta[a], _mm256_setzero_ps(), _CMP_GT_OQ), _mm256_set1_ps(1.0f));  // 1 or 0
    moving[a] = _mm256_cmp_ps(delta[a], _mm256_setzero_ps(), _CMP_NEQ_OQ);
    light[a] = _mm256_load_ps(l[a]);
    hi[a] = _mm256_set1_ps(float(vol.dims[a] - 1));
    max_cell[a] = _mm256_set1_epi32(std::max(vol.dims[a] - 2, 0));
  }
  const __m256i n_all = _mm256_load_si256(reinterpret_cast<const __m256i*>(n));
  const __m256i n_regular = _mm256_load_si256(reinterpret_cast<const __m256i*>(regular));
  const __m256 nf = _mm256_cvtepi32_ps(n_all);
  const glm::ivec3 steps = vol.corner_steps();
  // Corner offsets in voxels (a corner is 64 bits: value and gradient x, gradient y and z).
  const int corner[8] = {0, steps.x, steps.y, steps.y + steps.x, steps.z, steps.z + steps.x, steps.z + steps.y,
                         steps.z + steps.y + steps.x};
  const __m256i stride_y = _mm256_set1_epi32(int(vol.stride_y)), stride_z = _mm256_set1_epi32(int(vol.stride_z));
  const __m256i count_x = _mm256_set1_epi32(blocks.count.x), count_y = _mm256_set1_epi32(blocks.count.y);
  const __m256 block_size = _mm256_set1_ps(float(blocks.size)), inv_block = _mm256_set1_ps(1.0f / float(blocks.size));
  const __m256i last_block[3] = {_mm256_set1_epi32(blocks.count.x - 1), _mm256_set1_epi32(blocks.count.y - 1),
                                 _mm256_set1_epi32(blocks.count.z - 1)};
  // 64-bit gathers fill 4 lanes: gathering lanes (0, 1, 4, 5) and (2, 3, 6, 7) and interleaving the halves with
  // shufps gives the eight lanes in order.
  const __m256i halves = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
  const auto* voxels = reinterpret_cast<const long long*>(vol.voxels.data());
  const auto* table = reinterpret_cast<const long long*>(cast.table.entries.data());
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), termination = _mm256_set1_ps(o.termination);
  const __m256 infinity = _mm256_set1_ps(INFINITY);

  __m256i k = _mm256_setzero_si256();
  __m256 red = zero, green = zero, blue = zero, a_acc = zero;
  // The sample index of a lane does not wait for its opacity (a lane past termination keeps stepping and adds
  // nothing), so that the next positions do not depend on the previous sample's gathers and shading: the loop's
  // critical path is then only the empty-block jump.
  for (;;) {
    const __m256i marching = _mm256_cmpgt_epi32(n_regular, k);
    const __m256i active = _mm256_and_si256(marching, _mm256_castps_si256(_mm256_cmp_ps(a_acc, termination, _CMP_LT_OQ)));
    if (_mm256_testz_si256(active, active)) break;
    const __m256 kf = _mm256_cvtepi32_ps(k);
    __m256i cell[3], block[3];
    __m256 offset[3];
    for (int a = 0; a < 3; ++a) {
      const __m256 q = _mm256_min_ps(_mm256_max_ps(_mm256_fmadd_ps(kf, delta[a], first[a]), zero), hi[a]);
      cell[a] = _mm256_min_epi32(_mm256_cvttps_epi32(q), max_cell[a]);
      offset[a] = _mm256_sub_ps(q, _mm256_cvtepi32_ps(cell[a]));
      // cell / size: (cell + 0.5) / size is at least 0.5 / size from a whole number, far more than the rounding
      // (cells < 2^23), so truncating it is exact.
      const __m256 quotient = _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(cell[a]), _mm256_set1_ps(0.5f)), inv_block);
      block[a] = _mm256_min_epi32(_mm256_cvttps_epi32(quotient), last_block[a]);
    }
    const __m256i block_index =
        _mm256_add_epi32(block[0], _mm256_mullo_epi32(count_x, _mm256_add_epi32(block[1], _mm256_mullo_epi32(count_y, block[2]))));
    const __m256i is_empty = _mm256_cmpgt_epi32(_mm256_i32gather_epi32(blocks.empty.data(), block_index, 4), _mm256_setzero_si256());
    // Branchless: whether some lane jumps is a coin toss in noisy data.
    const __m256i skip = _mm256_and_si256(is_empty, marching);
    __m256 exit = infinity;
    for (int a = 0; a < 3; ++a) {
      const __m256 b = _mm256_cvtepi32_ps(block[a]);
      const __m256 bound = _mm256_mul_ps(_mm256_add_ps(b, forward[a]), block_size);  // the far side of the block
      exit = _mm256_min_ps(exit, _mm256_blendv_ps(infinity, _mm256_mul_ps(_mm256_sub_ps(bound, first[a]), inv_delta[a]), moving[a]));
    }
    const __m256i inside = _mm256_castps_si256(_mm256_cmp_ps(exit, nf, _CMP_LT_OQ));
    // Where the exit is beyond the ray, cvtt would overflow: those lanes take n instead.
    const __m256i jump = _mm256_max_epi32(k, _mm256_sub_epi32(_mm256_cvttps_epi32(_mm256_min_ps(exit, nf)), _mm256_set1_epi32(1)));
    k = _mm256_blendv_epi8(k, _mm256_blendv_epi8(n_all, jump, inside), skip);
    const __m256i sample = _mm256_andnot_si256(is_empty, active);
    if (!_mm256_testz_si256(sample, sample)) {
      const __m256i base = _mm256_permutevar8x32_epi32(
          _mm256_add_epi32(_mm256_add_epi32(cell[0], _mm256_mullo_epi32(cell[1], stride_y)), _mm256_mullo_epi32(cell[2], stride_z)),
          halves);
      const __m128i base_a = _mm256_castsi256_si128(base), base_b = _mm256_extracti128_si256(base, 1);
      __m256 x_lerped[4][4];  // [corner pair (y, z)][component]
      for (int pair = 0; pair < 4; ++pair) {
        __m256 c[2][4];
        for (int side = 0; side < 2; ++side) {
          const __m128i at = _mm_set1_epi32(corner[2 * pair + side]);
          const __m256i a = _mm256_i32gather_epi64(voxels, _mm_add_epi32(base_a, at), 8);
          const __m256i b = _mm256_i32gather_epi64(voxels, _mm_add_epi32(base_b, at), 8);
          const __m256i value_gx = _mm256_castps_si256(
              _mm256_shuffle_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _MM_SHUFFLE(2, 0, 2, 0)));
          const __m256i gy_gz = _mm256_castps_si256(
              _mm256_shuffle_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _MM_SHUFFLE(3, 1, 3, 1)));
          c[side][0] = low16(value_gx);
          c[side][1] = high16(value_gx);
          c[side][2] = low16(gy_gz);
          c[side][3] = high16(gy_gz);
        }
        for (int comp = 0; comp < 4; ++comp) x_lerped[pair][comp] = lerp(c[0][comp], c[1][comp], offset[0]);
      }
      __m256 s[4];
      for (int comp = 0; comp < 4; ++comp)
        s[comp] = lerp(lerp(x_lerped[0][comp], x_lerped[1][comp], offset[1]),
                       lerp(x_lerped[2][comp], x_lerped[3][comp], offset[1]), offset[2]);
      const __m256 position = _mm256_fmadd_ps(_mm256_add_ps(s[0], _mm256_set1_ps(32768.0f)),
                                              _mm256_set1_ps(TransferTable::kScale), _mm256_set1_ps(0.5f));
      // Entries are 16 bytes: (r, g) and (b, alpha) are 64-bit halves, gathered like the corners.
      const __m256i entry = _mm256_permutevar8x32_epi32(
          _mm256_slli_epi32(_mm256_min_epi32(_mm256_max_epi32(_mm256_cvttps_epi32(position), _mm256_setzero_si256()),
                                             _mm256_set1_epi32(TransferTable::kSize - 1)),
                            1),
          halves);
      const __m128i entry_a = _mm256_castsi256_si128(entry), entry_b = _mm256_extracti128_si256(entry, 1);
      const __m256 rg_a = _mm256_castsi256_ps(_mm256_i32gather_epi64(table, entry_a, 8));
      const __m256 rg_b = _mm256_castsi256_ps(_mm256_i32gather_epi64(table, entry_b, 8));
      const __m256 ba_a = _mm256_castsi256_ps(_mm256_i32gather_epi64(table + 1, entry_a, 8));
      const __m256 ba_b = _mm256_castsi256_ps(_mm256_i32gather_epi64(table + 1, entry_b, 8));
      __m256 r = _mm256_shuffle_ps(rg_a, rg_b, _MM_SHUFFLE(2, 0, 2, 0));
      __m256 g = _mm256_shuffle_ps(rg_a, rg_b, _MM_SHUFFLE(3, 1, 3, 1));
      __m256 b = _mm256_shuffle_ps(ba_a, ba_b, _MM_SHUFFLE(2, 0, 2, 0));
      const __m256 w = _mm256_and_ps(_mm256_shuffle_ps(ba_a, ba_b, _MM_SHUFFLE(3, 1, 3, 1)), _mm256_castsi256_ps(sample));
      if (o.shading) {
        const __m256 len2 = _mm256_fmadd_ps(s[1], s[1], _mm256_fmadd_ps(s[2], s[2], _mm256_mul_ps(s[3], s[3])));
        const __m256 lit = _mm256_cmp_ps(len2, _mm256_set1_ps(cast.min_gradient2), _CMP_GT_OQ);
        const __m256 dot = _mm256_fmadd_ps(s[1], light[0], _mm256_fmadd_ps(s[2], light[1], _mm256_mul_ps(s[3], light[2])));
        const __m256 abs_dot = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), dot);
        // 1 / |g| by rsqrt and one Newton step (relative error ~1e-7, shorter latency than sqrt and div).
        const __m256 len2_or_1 = _mm256_blendv_ps(one, len2, lit);
        const __m256 r0 = _mm256_rsqrt_ps(len2_or_1);
        const __m256 r1 = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.5f), r0),
                                        _mm256_fnmadd_ps(_mm256_mul_ps(len2_or_1, r0), r0, _mm256_set1_ps(3.0f)));
        const __m256 cosine = _mm256_mul_ps(abs_dot, r1);
        const __m256 clamped = _mm256_min_ps(_mm256_max_ps(cosine, zero), one);
        __m256 pw = one;
        if (cast.power.whole) {
          __m256 square = clamped;
          for (int e = cast.power.whole; e; e >>= 1, square = _mm256_mul_ps(square, square))
            if (e & 1) pw = _mm256_mul_ps(pw, square);
        } else {
          const __m256 ps = _mm256_mul_ps(clamped, _mm256_set1_ps(float(SpecularPower::kSize)));
          const __m256i pi = _mm256_min_epi32(_mm256_cvttps_epi32(ps), _mm256_set1_epi32(SpecularPower::kSize - 1));
          const __m256 p0 = _mm256_i32gather_ps(cast.power.values.data(), pi, 4);
          const __m256 p1 = _mm256_i32gather_ps(cast.power.values.data() + 1, pi, 4);
          pw = lerp(p0, p1, _mm256_sub_ps(ps, _mm256_cvtepi32_ps(pi)));
        }
        const __m256 shade = _mm256_blendv_ps(one, _mm256_fmadd_ps(_mm256_set1_ps(o.diffuse), cosine, _mm256_set1_ps(o.ambient)), lit);
        const __m256 highlight = _mm256_and_ps(_mm256_mul_ps(_mm256_set1_ps(o.specular), pw), lit);
        r = _mm256_fmadd_ps(r, shade, highlight);
        g = _mm256_fmadd_ps(g, shade, highlight);
        b = _mm256_fmadd_ps(b, shade, highlight);
      }
      const __m256 weight = _mm256_mul_ps(_mm256_sub_ps(one, a_acc), w);
      red = _mm256_fmadd_ps(weight, r, red);
      green = _mm256_fmadd_ps(weight, g, green);
      blue = _mm256_fmadd_ps(weight, b, blue);
      a_acc = _mm256_add_ps(a_acc, weight);
    }
    k = _mm256_sub_epi32(k, marching);  // marching lanes are all ones (-1): k + 1
  }
  alignas(32) float out[4][8];
  alignas(32) int ks[8];
  _mm256_store_ps(out[0], red);
  _mm256_store_ps(out[1], green);
  _mm256_store_ps(out[2], blue);
  _mm256_store_ps(out[3], a_acc);
  _mm256_store_si256(reinterpret_cast<__m256i*>(ks), k);
  for (int i = 0; i < count; ++i) {
    color[i] = {out[0][i], out[1][i], out[2][i]};
    alpha[i] = out[3][i];
    k_out[i] = ks[i];
  }
}
#endif

}  // namespace

namespace {

/// The sample distance of `options` on `volume` (options.step, or half the smallest spacing when 0). Throws
/// InvalidInput for a negative or non-finite step, or one giving more than kMaxSamplesPerRay samples across the box.
float sample_step(const Volume<float>& volume, const VolumeRenderOptions& options) {
  if (!(options.step >= 0) || !std::isfinite(options.step))
    throw InvalidInput(fmt::format("step {} must be a finite distance >= 0 (0: half the smallest spacing)", options.step));
  const Vec3 sp = volume.spacing();
  const double step = options.step > 0 ? double(options.step) : 0.5 * std::min({sp.x, sp.y, sp.z});
  const double diagonal = glm::length(volume.to_world(Vec3(volume.dims() - 1)) - volume.origin());
  const double samples = std::ceil(diagonal / step);
  if (!(samples <= double(VolumeRenderOptions::kMaxSamplesPerRay)))
    throw InvalidInput(fmt::format("step {} gives {:.3g} samples per ray across the volume's box (diagonal {:.6g}); at "
                                   "most {} are allowed: use a step of at least {:.3g}",
                                   float(step), samples, diagonal, VolumeRenderOptions::kMaxSamplesPerRay,
                                   diagonal / double(VolumeRenderOptions::kMaxSamplesPerRay)));
  return float(step);
}

/// The ray caster: MIP from the float volume, compositing from the prepared one (`packed`, unused for MIP).
ImageRGB cast_rays(const Volume<float>& volume, const VolumeRenderOptions& options, double vlo, double vhi,
                   const PackedVolume* packed_volume) {
  Camera camera = options.camera;
  camera.aspect = double(options.width) / double(options.height);
  const EyeRays rays(camera, options.width, options.height);
  const Vec3 sp = volume.spacing();
  const float step = sample_step(volume, options);
  AABB box;
  box.expand(Vec3f(volume.origin()));
  box.expand(Vec3f(volume.to_world(Vec3(volume.dims() - 1))));
  const Vec3f inv_spacing = Vec3f(1.0 / sp);
  const Vec3f origin = Vec3f(volume.origin());
  ImageRGB image(options.width, options.height, options.background);
  const auto report = [&](const Tile& tile) {
    if (options.progress) options.progress(int64_t(tile.x1 - tile.x0) * (tile.y1 - tile.y0));
  };
  if (options.mip) {
    parallel_tiles(options.width, options.height, 16, [&](const Tile& tile) {
      for (int j = tile.y0; j < tile.y1; ++j)
        for (int i = tile.x0; i < tile.x1; ++i) {
          const Ray ray = rays.ray(i, j);
          float t0 = 0, t1 = 0;
          if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) continue;
          float best = -INFINITY;
          // Sample k at t0 + (k + 1/2) step: an integer count always ends, where t += step stalls once step is
          // below half an ulp of t.
          const int n = int(std::ceil((t1 - t0) / step));
          for (int k = 0; k < n; ++k) {
            const float t = t0 + (float(k) + 0.5f) * step;
            if (t >= t1) break;
            best = std::max(best, volume.sample((ray.at(t) - origin) * inv_spacing));
          }
          // A range of any width, however tiny, spans black to white (the values are floats: vhi - vlo > 0 is
          // at least their smallest difference, and the quotient is in [0, 1]).
          if (best > -INFINITY) image(i, j) = Vec3f(vhi > vlo ? float((best - vlo) / (vhi - vlo)) : 0.0f);
        }
      report(tile);
    });
    return image;
  }
  const PackedVolume& packed = *packed_volume;
  const TransferTable table(options.transfer, vlo, vhi, step);
  // Without skipping one block covers the volume: it is "empty" only when every sample would be clear anyway.
  const BlockGrid blocks(packed, options.skip_empty ? std::max(1, options.block) : 1 << 20, table);
  const SpecularPower power(options.shininess);
  // A gradient shorter than 1e-6 world units, or than 1e-6 of the value range per smallest spacing where that is
  // shorter (a tiny value range, whose gradient_scale is huge), is left unshaded: a tiny range shades as the unit
  // range does, and the threshold stays finite.
  const float min_gradient = float(1e-6 * std::min(packed.gradient_scale, 32767.0));
  const Caster cast{packed, table, blocks, power, options, step, min_gradient * min_gradient};
  const auto setup = [&](int i, int j) {
    RaySamples r;
    const Ray ray = rays.ray(i, j);
    float t0 = 0, t1 = 0;
    if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) return r;
    // Sample k is at the middle of [t0 + k step, min(t1, t0 + (k + 1) step)].
    r.n = int(std::ceil((t1 - t0) / step));
    const float last_length = t1 - (t0 + float(r.n - 1) * step);
    r.last_fraction = last_length / step;
    r.first = (ray.at(t0 + 0.5f * step) - origin) * inv_spacing;
    r.delta = ray.dir * step * inv_spacing;
    r.last_point = (ray.at(t1 - 0.5f * last_length) - origin) * inv_spacing;
    r.light = -ray.dir;  // headlight: light and viewer at the eye
    return r;
  };
#if TESSERA_VOLUME_AVX2
  // The gathers index the packed voxels with int32, and march8 divides cells by the block size in float.
  const bool simd = options.simd && cpu_features().avx2 && cpu_features().fma &&
                    packed.voxels.size() < (size_t(1) << 31) && glm::all(glm::lessThan(packed.dims, glm::ivec3(1 << 23)));
#else
  const bool simd = false;
#endif
  parallel_tiles(options.width, options.height, 16, [&](const Tile& tile) {
    // Packets of 4 x 2 pixels: their rays stay closer together than a row of 8, so they share more cache lines.
    for (int j0 = tile.y0; j0 < tile.y1; j0 += 2)
      for (int i0 = tile.x0; i0 < tile.x1; i0 += 4) {
        glm::ivec2 pixel[8];
        int count = 0;
        for (int j = j0; j < std::min(j0 + 2, tile.y1); ++j)
          for (int i = i0; i < std::min(i0 + 4, tile.x1); ++i) pixel[count++] = {i, j};
        RaySamples r[8];
        Vec3f color[8];
        float alpha[8];
        int k[8] = {};
        for (int lane = 0; lane < count; ++lane) {
          r[lane] = setup(pixel[lane].x, pixel[lane].y);
          color[lane] = Vec3f(0.0f);
          alpha[lane] = 0;
        }
#if TESSERA_VOLUME_AVX2
        if (simd) march8(cast, r, count, color, alpha, k);
#endif
        for (int lane = 0; lane < count; ++lane) {
          cast.march(r[lane], k[lane], color[lane], alpha[lane]);
          image(pixel[lane].x, pixel[lane].y) = color[lane] + (1 - alpha[lane]) * options.background;
        }
      }
    report(tile);
  });
  return image;
}

}  // namespace

ImageRGB render_volume(const Volume<float>& volume, const VolumeRenderOptions& options) {
  if (volume.empty()) throw InvalidInput("cannot render an empty volume");
  if (options.width < 1 || options.height < 1) throw InvalidInput("image size must be positive");
  if (options.mip) {
    const auto [lo, hi] = value_range(volume);
    return cast_rays(volume, options, lo, hi, nullptr);
  }
  return VolumeRenderer(volume).render(options);
}

struct VolumeRenderer::Prepared {
  double lo, hi;  ///< the value range
  PackedVolume packed;
  Prepared(const Volume<float>& v, std::pair<double, double> range)
      : lo(range.first), hi(range.second), packed(v, range.first, range.second) {}
};

VolumeRenderer::VolumeRenderer(const Volume<float>& volume) : volume_(&volume) {
  if (volume.empty()) throw InvalidInput("cannot render an empty volume");
  prepared_ = std::make_unique<Prepared>(volume, value_range(volume));
}
VolumeRenderer::~VolumeRenderer() = default;
VolumeRenderer::VolumeRenderer(VolumeRenderer&&) noexcept = default;
VolumeRenderer& VolumeRenderer::operator=(VolumeRenderer&&) noexcept = default;

ImageRGB VolumeRenderer::render(const VolumeRenderOptions& options) const {
  if (options.width < 1 || options.height < 1) throw InvalidInput("image size must be positive");
  return cast_rays(*volume_, options, prepared_->lo, prepared_->hi, &prepared_->packed);
}

}  // namespace tessera
