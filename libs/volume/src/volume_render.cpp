#include "tessera/volume/volume_render.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tessera/core/atomic_file.hpp"
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

/// Min/max per block of `block` cells per side (including the far voxel layer, so trilinear samples inside a block
/// read only the block's voxels).
struct BlockGrid {
  glm::ivec3 count;
  int size;
  std::vector<uint8_t> empty;

  BlockGrid(const Volume<float>& v, int block, const TransferFunction& tf) : size(block) {
    const glm::ivec3 d = v.dims();
    count = glm::max((d - 1 + block - 1) / block, glm::ivec3(1));
    empty.resize(size_t(count.x) * size_t(count.y) * size_t(count.z));
    parallel_for(0, count.z, 1, [&](int64_t b0, int64_t b1) {
      for (int bz = int(b0); bz < int(b1); ++bz)
        for (int by = 0; by < count.y; ++by)
          for (int bx = 0; bx < count.x; ++bx) {
            float lo = INFINITY, hi = -INFINITY;
            for (int z = bz * block; z <= std::min((bz + 1) * block, d.z - 1); ++z)
              for (int y = by * block; y <= std::min((by + 1) * block, d.y - 1); ++y)
                for (int x = bx * block; x <= std::min((bx + 1) * block, d.x - 1); ++x) {
                  lo = std::min(lo, v(x, y, z));
                  hi = std::max(hi, v(x, y, z));
                }
            empty[index(bx, by, bz)] = tf.max_opacity(lo, hi) <= 0.0f;
          }
    });
  }
  size_t index(int x, int y, int z) const { return size_t(x) + size_t(count.x) * (size_t(y) + size_t(count.y) * size_t(z)); }
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
  const bool skip = options.skip_empty && !options.mip;
  const BlockGrid blocks = skip ? BlockGrid(volume, std::max(1, options.block), options.transfer) : BlockGrid(volume, 1 << 20, options.transfer);
  const Vec3f inv_spacing = Vec3f(1.0 / sp);
  const Vec3f origin = Vec3f(volume.origin());
  ImageRGB image(options.width, options.height, options.background);
  parallel_tiles(options.width, options.height, 16, [&](const Tile& tile) {
    for (int j = tile.y0; j < tile.y1; ++j)
      for (int i = tile.x0; i < tile.x1; ++i) {
        const Ray ray = rays.ray(i, j);
        float t0 = 0, t1 = 0;
        if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) continue;
        const auto voxel_at = [&](float t) { return (ray.at(t) - origin) * inv_spacing; };
        if (options.mip) {
          float best = -INFINITY;
          for (float t = t0 + 0.5f * step; t < t1; t += step) best = std::max(best, volume.sample(voxel_at(t)));
          if (best > -INFINITY) image(i, j) = Vec3f(float((best - vlo) / std::max(vhi - vlo, 1e-12)));
          continue;
        }
        Vec3f color(0.0f);
        float alpha = 0;
        const int n = int(std::ceil((t1 - t0) / step));
        for (int k = 0; k < n && alpha < options.termination; ++k) {
          const float a = t0 + float(k) * step, b = std::min(t1, a + step), t = 0.5f * (a + b);
          const Vec3f p = voxel_at(t);
          if (skip) {
            const glm::ivec3 bi = glm::clamp(glm::ivec3(p / float(blocks.size)), glm::ivec3(0), blocks.count - 1);
            if (blocks.empty[blocks.index(bi.x, bi.y, bi.z)]) continue;
          }
          const Vec4f c = options.transfer(volume.sample(p));
          if (c.w <= 0) continue;
          const float sample_alpha = 1.0f - std::pow(1.0f - c.w, b - a);
          Vec3f rgb(c);
          if (options.shading) {
            const float h = 0.5f;
            Vec3f g(volume.sample(p + Vec3f(h, 0, 0)) - volume.sample(p - Vec3f(h, 0, 0)),
                    volume.sample(p + Vec3f(0, h, 0)) - volume.sample(p - Vec3f(0, h, 0)),
                    volume.sample(p + Vec3f(0, 0, h)) - volume.sample(p - Vec3f(0, 0, h)));
            g *= inv_spacing;
            const float len = glm::length(g);
            if (len > 1e-6f) {
              const Vec3f nrm = g / len, l = -ray.dir;  // headlight: light and viewer at the eye
              const float diffuse = std::abs(glm::dot(nrm, l));
              const float spec = std::pow(std::abs(glm::dot(nrm, l)), options.shininess);  // Blinn: h = l for a headlight
              rgb = rgb * (options.ambient + options.diffuse * diffuse) + Vec3f(options.specular * spec);
            }
          }
          color += (1 - alpha) * sample_alpha * rgb;
          alpha += (1 - alpha) * sample_alpha;
        }
        image(i, j) = color + (1 - alpha) * options.background;
      }
  });
  return image;
}

}  // namespace tessera
