#include "tessera/volume/volume_render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {

TransferFunction::TransferFunction(std::vector<Point> points) : points_(std::move(points)) {
  if (points_.empty()) throw InvalidInput("a transfer function needs at least one point");
  for (const auto& p : points_)
    if (!(p.opacity >= 0 && p.opacity <= 1)) throw InvalidInput(fmt::format("opacity {} is outside [0, 1]", p.opacity));
  std::stable_sort(points_.begin(), points_.end(), [](const Point& a, const Point& b) { return a.value < b.value; });
}

Vec4f TransferFunction::operator()(float v) const {
  if (points_.empty()) return Vec4f(0.0f);
  if (v <= points_.front().value) return Vec4f(points_.front().color, points_.front().opacity);
  if (v >= points_.back().value) return Vec4f(points_.back().color, points_.back().opacity);
  const auto hi = std::upper_bound(points_.begin(), points_.end(), v, [](float x, const Point& p) { return x < p.value; });
  const auto lo = hi - 1;
  const float t = (v - lo->value) / (hi->value - lo->value);
  return Vec4f(glm::mix(lo->color, hi->color, t), lo->opacity + t * (hi->opacity - lo->opacity));
}

float TransferFunction::max_opacity(float lo, float hi) const {
  float m = std::max((*this)(lo).w, (*this)(hi).w);
  for (const auto& p : points_)
    if (p.value >= lo && p.value <= hi) m = std::max(m, p.opacity);
  return m;
}

TransferFunction TransferFunction::preset(const std::string& name) {
  if (name == "ct-bone")
    return TransferFunction({{0, {0, 0, 0}, 0}, {1000, {0.9f, 0.6f, 0.4f}, 0}, {1150, {0.95f, 0.9f, 0.8f}, 0.6f},
                             {2000, {1, 1, 0.95f}, 0.9f}});
  if (name == "ct-skin")
    return TransferFunction({{0, {0, 0, 0}, 0}, {400, {0.8f, 0.5f, 0.4f}, 0}, {600, {0.9f, 0.7f, 0.6f}, 0.15f},
                             {1100, {0.9f, 0.7f, 0.6f}, 0.15f}, {1300, {1, 1, 0.95f}, 0.8f}});
  if (name == "mri")
    return TransferFunction({{0, {0, 0, 0}, 0}, {40, {0.5f, 0.3f, 0.3f}, 0}, {90, {0.9f, 0.75f, 0.6f}, 0.1f},
                             {255, {1, 1, 1}, 0.5f}});
  throw InvalidInput(fmt::format("unknown transfer-function preset '{}' (ct-bone, ct-skin, mri)", name));
}

TransferFunction TransferFunction::from_json(const std::string& text, const std::string& name) {
  try {
    const auto j = nlohmann::json::parse(text);
    std::vector<Point> points;
    for (const auto& p : j.at("points")) {
      if (!p.is_array() || p.size() != 5) throw InvalidInput(fmt::format("{}: each point is [value, r, g, b, opacity]", name));
      points.push_back({p[0].get<float>(), {p[1].get<float>(), p[2].get<float>(), p[3].get<float>()}, p[4].get<float>()});
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
    const auto v = parse_doubles(t, 5, at_line(name, line_no));
    points.push_back({float(v[0]), {float(v[1]), float(v[2]), float(v[3])}, float(v[4])});
  }
  return TransferFunction(std::move(points));
}

TransferFunction TransferFunction::load(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  return path.extension() == ".json" ? from_json(text, path.string()) : from_csv(text, path.string());
}

namespace {

/// The volume as the ray caster reads it: per voxel the value and the central-difference gradient (world units),
/// each quantized to 16 bits and interleaved, so that one 8-byte load per cell corner gives everything a shaded
/// sample needs (VTK's fixed-point mapper also works on 16-bit values with precomputed gradients). Built once per
/// render instead of six extra trilinear samples per step.
struct PackedVolume {
  glm::ivec3 dims;
  size_t stride_y, stride_z;
  float value_lo, value_scale;  ///< quantized = (v - value_lo) * value_scale - 32768
  float gradient_scale;         ///< quantized = g * gradient_scale
  RawVector<std::array<int16_t, 4>> voxels;

  PackedVolume(const Volume<float>& v, float lo, float hi, bool with_gradient)
      : dims(v.dims()), stride_y(size_t(dims.x)), stride_z(size_t(dims.x) * size_t(dims.y)), value_lo(lo) {
    value_scale = hi > lo ? 65535.0f / (hi - lo) : 0.0f;
    // The largest gradient component (a max, so the same for any thread count) sets the gradient's scale.
    std::vector<float> slab_max(size_t(dims.z), 0.0f);
    if (with_gradient)
      parallel_for(0, dims.z, 1, [&](int64_t z0, int64_t z1) {
        for (int z = int(z0); z < int(z1); ++z)
          for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
              const Vec3f g = v.gradient(x, y, z);
              slab_max[size_t(z)] = std::max({slab_max[size_t(z)], std::abs(g.x), std::abs(g.y), std::abs(g.z)});
            }
      });
    const float gmax = *std::max_element(slab_max.begin(), slab_max.end());
    gradient_scale = gmax > 0 ? 32767.0f / gmax : 0.0f;
    voxels.resize(v.voxel_count());
    parallel_for(0, dims.z, 1, [&](int64_t z0, int64_t z1) {
      for (int z = int(z0); z < int(z1); ++z)
        for (int y = 0; y < dims.y; ++y)
          for (int x = 0; x < dims.x; ++x) {
            const Vec3f g = with_gradient ? v.gradient(x, y, z) * gradient_scale : Vec3f(0.0f);
            voxels[v.index(x, y, z)] = {int16_t(std::lround((v(x, y, z) - lo) * value_scale) - 32768),
                                        int16_t(std::lround(g.x)), int16_t(std::lround(g.y)), int16_t(std::lround(g.z))};
          }
    });
  }

  /// The cell holding voxel coordinates p (clamped to the grid; its lower corner) and p's offset in it.
  glm::ivec3 locate(const Vec3f& p, Vec3f& offset) const {
    const Vec3f q = glm::clamp(p, Vec3f(0.0f), Vec3f(dims - 1));
    const glm::ivec3 cell = glm::min(glm::ivec3(q), glm::max(dims - 2, 0));
    offset = q - Vec3f(cell);
    return cell;
  }

  /// Trilinear (value, gradient) in quantized units at `offset` in `cell`.
  Vec4f interpolate(const glm::ivec3& cell, const Vec3f& offset) const {
    const size_t dx = dims.x > 1 ? 1 : 0, dy = dims.y > 1 ? stride_y : 0, dz = dims.z > 1 ? stride_z : 0;
    const std::array<int16_t, 4>* c = voxels.data() + size_t(cell.x) + stride_y * size_t(cell.y) + stride_z * size_t(cell.z);
#if defined(__SSE2__)
    // Four components at once: sign-extend the four int16 of a corner to floats, then seven lerps.
    const auto load = [](const std::array<int16_t, 4>& a) {
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
    const auto load = [](const std::array<int16_t, 4>& a) { return Vec4f(a[0], a[1], a[2], a[3]); };
    const auto lerp = [](const Vec4f& a, const Vec4f& b, float t) { return a + t * (b - a); };
    const Vec4f c00 = lerp(load(c[0]), load(c[dx]), offset.x), c10 = lerp(load(c[dy]), load(c[dy + dx]), offset.x);
    const Vec4f c01 = lerp(load(c[dz]), load(c[dz + dx]), offset.x);
    const Vec4f c11 = lerp(load(c[dz + dy]), load(c[dz + dy + dx]), offset.x);
    return lerp(lerp(c00, c10, offset.y), lerp(c01, c11, offset.y), offset.z);
#endif
  }
};

/// The transfer function tabulated over the quantized value range, with each entry's opacity already corrected to
/// the step (alpha = 1 - (1 - opacity)^step), so a sample costs a table lerp instead of a search and a pow.
struct TransferTable {
  static constexpr int kSize = 4096;
  std::vector<Vec4f> entries;  ///< rgb, alpha per step
  float index_scale;           ///< table position = (quantized + 32768) * index_scale

  TransferTable(const TransferFunction& tf, float lo, float hi, float step) : entries(kSize) {
    index_scale = float(kSize - 1) / 65535.0f;
    const float span = hi > lo ? hi - lo : 0.0f;
    for (int i = 0; i < kSize; ++i) {
      const Vec4f c = tf(lo + span * float(i) / float(kSize - 1));
      entries[size_t(i)] = Vec4f(Vec3f(c), 1.0f - std::pow(1.0f - c.w, step));
    }
  }
  Vec4f operator()(float quantized) const {
    const float s = std::clamp((quantized + 32768.0f) * index_scale, 0.0f, float(kSize - 1));
    const int i = std::min(int(s), kSize - 2);
    return entries[size_t(i)] + (s - float(i)) * (entries[size_t(i) + 1] - entries[size_t(i)]);
  }
  /// The largest alpha over quantized values [lo, hi]: every table entry a lerp in that range can touch.
  float max_alpha(float lo, float hi) const {
    const int a = std::clamp(int((lo + 32768.0f) * index_scale) - 1, 0, kSize - 1);  // - 1: rounding below lo
    const int b = std::clamp(int((hi + 32768.0f) * index_scale) + 1, 0, kSize - 1);
    float m = 0;
    for (int i = a; i <= b; ++i) m = std::max(m, entries[size_t(i)].w);
    return m;
  }
};

/// Empty flags per block of `block` cells per side: a block is empty when no table lerp over its voxels' quantized
/// range gives a non-zero alpha, so skipping its samples leaves the image unchanged.
struct BlockGrid {
  int size;
  glm::ivec3 count;
  std::vector<uint8_t> empty;

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
            empty[index(glm::ivec3(bx, by, bz))] = table.max_alpha(float(lo), float(hi)) <= 0.0f;
          }
    });
    for (int axis = 0; axis < 3; ++axis) {
      of_cell[axis].resize(size_t(std::max(d[axis] - 1, 1)));
      for (int c = 0; c < int(of_cell[axis].size()); ++c) of_cell[axis][size_t(c)] = std::min(c / size, count[axis] - 1);
    }
  }
  size_t index(const glm::ivec3& b) const { return size_t(b.x) + size_t(count.x) * (size_t(b.y) + size_t(count.y) * size_t(b.z)); }
  /// The block of a cell (a table per axis: a division per axis and sample showed in the profile).
  glm::ivec3 block_of(const glm::ivec3& cell) const {
    return {of_cell[0][size_t(cell.x)], of_cell[1][size_t(cell.y)], of_cell[2][size_t(cell.z)]};
  }
  std::array<std::vector<int>, 3> of_cell;
};

/// c^shininess for c in [0, 1], tabulated (the specular term is a pow per sample otherwise).
struct PowerTable {
  static constexpr int kSize = 1024;
  std::array<float, kSize + 1> values;
  explicit PowerTable(float exponent) {
    for (int i = 0; i <= kSize; ++i) values[size_t(i)] = std::pow(float(i) / kSize, exponent);
  }
  float operator()(float c) const {
    const float s = std::clamp(c, 0.0f, 1.0f) * kSize;
    const int i = std::min(int(s), kSize - 1);
    return values[size_t(i)] + (s - float(i)) * (values[size_t(i) + 1] - values[size_t(i)]);
  }
};

}  // namespace

ImageRGB render_volume(const Volume<float>& volume, const VolumeRenderOptions& options) {
  if (volume.empty()) throw InvalidInput("cannot render an empty volume");
  if (options.width < 1 || options.height < 1) throw InvalidInput("image size must be positive");
  Camera camera = options.camera;
  camera.aspect = double(options.width) / double(options.height);
  const EyeRays rays(camera, options.width, options.height);
  const Vec3 sp = volume.spacing();
  const float step = options.step > 0 ? options.step : float(0.5 * std::min({sp.x, sp.y, sp.z}));
  AABB box;
  box.expand(Vec3f(volume.origin()));
  box.expand(Vec3f(volume.to_world(Vec3(volume.dims() - 1))));
  const auto [vlo, vhi] = value_range(volume);
  const Vec3f inv_spacing = Vec3f(1.0 / sp);
  const Vec3f origin = Vec3f(volume.origin());
  ImageRGB image(options.width, options.height, options.background);
  if (options.mip) {
    parallel_tiles(options.width, options.height, 16, [&](const Tile& tile) {
      for (int j = tile.y0; j < tile.y1; ++j)
        for (int i = tile.x0; i < tile.x1; ++i) {
          const Ray ray = rays.ray(i, j);
          float t0 = 0, t1 = 0;
          if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) continue;
          float best = -INFINITY;
          for (float t = t0 + 0.5f * step; t < t1; t += step)
            best = std::max(best, volume.sample((ray.at(t) - origin) * inv_spacing));
          if (best > -INFINITY) image(i, j) = Vec3f(float((best - vlo) / std::max(vhi - vlo, 1e-12)));
        }
    });
    return image;
  }
  const PackedVolume packed(volume, float(vlo), float(vhi), options.shading);
  const TransferTable table(options.transfer, float(vlo), float(vhi), step);
  // Without skipping one block covers the volume: it is "empty" only when every sample would be clear anyway.
  const BlockGrid blocks(packed, options.skip_empty ? std::max(1, options.block) : 1 << 20, table);
  const PowerTable specular_power(options.shininess);
  // A gradient shorter than this (world units) leaves the sample unshaded.
  const float min_gradient2 = (1e-6f * packed.gradient_scale) * (1e-6f * packed.gradient_scale);
  parallel_tiles(options.width, options.height, 16, [&](const Tile& tile) {
    for (int j = tile.y0; j < tile.y1; ++j)
      for (int i = tile.x0; i < tile.x1; ++i) {
        const Ray ray = rays.ray(i, j);
        float t0 = 0, t1 = 0;
        if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) continue;
        // Sample k is at the middle of [t0 + k step, min(t1, t0 + (k + 1) step)]: in voxel space first + k * delta,
        // except the last, shorter segment's.
        const int n = int(std::ceil((t1 - t0) / step));
        const float last_length = t1 - (t0 + float(n - 1) * step);
        const Vec3f first = (ray.at(t0 + 0.5f * step) - origin) * inv_spacing;
        const Vec3f delta = ray.dir * step * inv_spacing;
        const Vec3f light = -ray.dir;  // headlight: light and viewer at the eye
        Vec3f color(0.0f);
        float alpha = 0;
        for (int k = 0; k < n && alpha < options.termination; ++k) {
          const bool last = k == n - 1 && last_length < step;
          const Vec3f p = last ? (ray.at(t1 - 0.5f * last_length) - origin) * inv_spacing : first + float(k) * delta;
          Vec3f offset;
          const glm::ivec3 cell = packed.locate(p, offset);
          const glm::ivec3 b = blocks.block_of(cell);
          if (blocks.empty[blocks.index(b)]) {
            // Jump to the sample before the one where the ray leaves the block (the samples skipped are at least a
            // step inside it, so rounding cannot skip a sample of another block).
            float exit = INFINITY;
            for (int axis = 0; axis < 3; ++axis) {
              if (delta[axis] > 0) exit = std::min(exit, (float((b[axis] + 1) * blocks.size) - first[axis]) / delta[axis]);
              if (delta[axis] < 0) exit = std::min(exit, (float(b[axis] * blocks.size) - first[axis]) / delta[axis]);
            }
            k = exit < float(n) ? std::max(k, int(exit) - 1) : n;
            continue;
          }
          const Vec4f s = packed.interpolate(cell, offset);
          Vec4f c = table(s.x);
          if (c.w <= 0) continue;
          if (last) c.w = 1.0f - std::pow(1.0f - c.w, last_length / step);
          Vec3f rgb(c);
          if (options.shading) {
            const Vec3f g(s.y, s.z, s.w);
            const float len2 = glm::dot(g, g);
            if (len2 > min_gradient2) {
              const float cosine = std::abs(glm::dot(g, light)) / std::sqrt(len2);  // Blinn: h = l for a headlight
              rgb = rgb * (options.ambient + options.diffuse * cosine) + Vec3f(options.specular * specular_power(cosine));
            }
          }
          color += (1 - alpha) * c.w * rgb;
          alpha += (1 - alpha) * c.w;
        }
        image(i, j) = color + (1 - alpha) * options.background;
      }
  });
  return image;
}

}  // namespace tessera
