// The recursive (Whitted) and distribution ray tracer and the tile renderer.
#include "tessera/raytrace/render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/frame.hpp"
#include "tessera/raytrace/sampling.hpp"

namespace tessera {
namespace {

/// The sample dimensions that are stratified across a pixel's samples (deeper bounces use the pixel's Rng).
enum Dimension : uint32_t { kPixel, kLens, kTime, kLight, kGloss, kDimensions };

/// Samples per block of stratified numbers drawn together.
constexpr uint32_t kBlock = 16;

/// A pixel's stratified numbers of one dimension for sample counts up to kBlock, with StratifiedPattern's layout
/// (correlated multi-jittering: an m x rows grid, one column and one row permutation that stratify both 1D
/// projections, the samples in shuffled order), its permutations and jitters drawn from the pixel's Rng instead of
/// Kensler's hashes: a dozen PCG steps for 4 samples instead of a dozen long hash chains. The same statistics, another
/// noise pattern.
class SmallPattern {
 public:
  explicit SmallPattern(uint32_t n) : n_(n) {
    TESSERA_CHECK(n >= 1 && n <= kBlock);
    m_ = uint32_t(std::ceil(std::sqrt(double(n))));
    rows_ = (n + m_ - 1) / m_;
    for (uint32_t s = 0; s < n; ++s) {
      column_of_[s] = s % m_;
      row_of_[s] = s / m_;
    }
    inv_cells_ = 1.0f / float(m_ * rows_);
  }

  /// The n numbers of one pixel, in [0, 1)^2.
  void draw(Rng& rng, std::span<Vec2f, kBlock> out) const {
    uint32_t order[kBlock], columns[kBlock], rows[kBlock];
    shuffle(rng, order, n_);
    shuffle(rng, columns, m_);
    shuffle(rng, rows, rows_);
    for (uint32_t i = 0; i < n_; ++i) {
      // Cell (col, row) of the m x rows grid, and within it sub-cell rows[row] of rows across, columns[col] of m down:
      // x = (col + (rows[row] + jx) / rows) / m, y = (row + (columns[col] + jy) / m) / rows.
      const uint32_t s = order[i], col = column_of_[s], row = row_of_[s];
      const float jx = rng.uniform(), jy = rng.uniform();
      out[i] = {std::min((float(col * rows_ + rows[row]) + jx) * inv_cells_, 0x1.fffffep-1f),
                std::min((float(row * m_ + columns[col]) + jy) * inv_cells_, 0x1.fffffep-1f)};
    }
  }

 private:
  /// A uniformly random permutation of [0, k) (Fisher-Yates).
  static void shuffle(Rng& rng, uint32_t* a, uint32_t k) {
    for (uint32_t i = 0; i < k; ++i) a[i] = i;
    for (uint32_t i = k; i > 1; --i) std::swap(a[i - 1], a[rng.below(i)]);
  }

  uint32_t n_, m_ = 1, rows_ = 1;
  uint32_t column_of_[kBlock] = {}, row_of_[kBlock] = {};  // sample s's grid cell: s % m, s / m
  float inv_cells_ = 1.0f;                                 // 1 / (m rows)
};

/// Stratified numbers of one pixel sample for the first hit; null at deeper bounces.
struct PrimaryNumbers {
  Vec2f light, gloss;
};

/// How far a ray origin moves off the surface at p along the geometric normal: relative to the point's magnitude.
float offset_scale(const Vec3f& p) { return 2e-4f * (1.0f + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)})); }

/// True when nothing blocks the segment from p toward the light sample at `time` (the notes' visible(P, L); moving
/// objects cast their shadows where they are at the time of the path's eye ray).
bool visible(const World& world, const Vec3f& p, const LightSample& ls, float time, uint64_t& rays) {
  ++rays;
  Ray shadow;
  shadow.origin = p;
  shadow.dir = ls.dir;
  shadow.time = time;
  shadow.tmax = std::isinf(ls.distance) ? ls.distance : ls.distance * (1.0f - 1e-4f);
  return !world.occluded(shadow);
}

float max_component(const Vec3f& v) { return std::max({v.x, v.y, v.z}); }

/// x^p for the highlight, x in [0, 1]: by repeated squaring when p is a whole number up to 1024 (the usual shininess;
/// a few multiplications instead of powf, equal to it within float rounding), else std::pow. The tracer calls it only
/// above highlight_floor(p), where x^p >= 2^-32, so no squaring step goes subnormal (a hundred cycles each).
float highlight_power(float x, float p) {
  if (!(p >= 0.0f && p <= 1024.0f) || p != std::floor(p)) return std::pow(x, p);
  float result = 1.0f;
  for (auto k = uint32_t(p); k != 0; k >>= 1) {
    if (k & 1) result *= x;
    x *= x;
  }
  return result;
}

/// The cosine 2^(-32 / p) below which a highlight cos^p is under 2^-32 and adds nothing: most shading points of a
/// shiny surface lie below it and skip the power (and, when nothing else lights them, the shadow ray).
float highlight_floor(float p) { return p > 0.0f ? std::exp2(-32.0f / p) : 0.0f; }

/// The surface color C_r at a hit of `ray`: the diffuse color or the checkerboard's, times the texture.
Vec3f surface_color(const World& world, const Material& m, const Ray& ray, const SurfaceHit& h) {
  Vec3f c = m.diffuse;
  if (m.checker > 0.0f) {
    const Vec3f cell = glm::floor(h.hit.point * (1.0f / m.checker) + 1e-4f);
    if ((int64_t(cell.x) + int64_t(cell.y) + int64_t(cell.z)) & 1) c = m.checker_color;
  }
  if (m.texture) c *= Vec3f(m.texture->sample(world.texture_uv(ray, h)));
  return c;
}

/// The notes' eye rays (u = (2 (i + dx) / w - 1) aspect, v = 1 - 2 (j + dy) / h, direction -d w + u u + v v) as an
/// affine function of the image position, set up once in double and evaluated in float, and the thin lens. An
/// orthographic camera moves the origin instead (eye + (h/2)(u u + v v), h its ortho_height) and aims every ray along
/// the gaze -w, as EyeRays does.
class CameraRays {
 public:
  CameraRays(const RayScene& scene, int width, int height)
      : orthographic_(scene.camera.orthographic), aperture_(scene.aperture) {
    Camera camera = scene.camera;
    camera.aspect = double(width) / double(height);
    const EyeRays check(camera, width, height);  // validates the size, field of view and view height
    Vec3 u, v, w;
    camera.frame(u, v, w);
    // The view plane's point for the image position: at focal length d in front of the eye (perspective), or in the
    // eye's plane, scaled to the view's height (orthographic).
    const double d = orthographic_ ? 0.0 : check.focal_length(), s = orthographic_ ? 0.5 * camera.ortho_height : 1.0;
    origin_ = Vec3f(camera.eye);
    corner_ = Vec3f(-d * w - s * camera.aspect * u + s * v);  // for perspective (s = 1) bit for bit the notes' sum
    step_x_ = Vec3f((2.0 * s * camera.aspect / width) * u);
    step_y_ = Vec3f((-2.0 * s / height) * v);
    lens_u_ = Vec3f(u);
    lens_v_ = Vec3f(v);
    forward_ = Vec3f(-w);
    focus_ = scene.focal_distance > 0.0f ? scene.focal_distance : float(glm::length(camera.center - camera.eye));
  }

  /// The eye ray through image position (x + offset.x, y + offset.y) at `time`; with an aperture, from the lens point
  /// `lens` (in [0, 1)^2, mapped onto the aperture disk) toward the pinhole ray's point on the focal plane.
  Ray ray(int x, int y, const Vec2f& offset, const Vec2f& lens, float time) const {
    const Vec3f at = corner_ + (float(x) + offset.x) * step_x_ + (float(y) + offset.y) * step_y_;
    Ray r;
    r.origin = orthographic_ ? origin_ + at : origin_;
    r.dir = orthographic_ ? forward_ : glm::normalize(at);
    r.time = time;
    if (aperture_ > 0.0f) {
      const Vec3f focal_point = r.origin + (focus_ / glm::dot(r.dir, forward_)) * r.dir;
      const Vec2f l = aperture_ * sample_disk(lens);
      r.origin += l.x * lens_u_ + l.y * lens_v_;
      r.dir = glm::normalize(focal_point - r.origin);
    }
    return r;
  }

 private:
  Vec3f origin_, corner_, step_x_, step_y_, lens_u_, lens_v_, forward_;
  bool orthographic_;
  float aperture_, focus_;
};

class Tracer {
 public:
  Tracer(const RayScene& scene, const RenderSettings& settings) : scene_(scene), settings_(settings) {
    for (size_t li = 0; li < scene.lights.size(); ++li) {
      const Light& light = scene.lights[li];
      LightInfo info;
      info.count = light.is_area() ? std::max(1, light.samples) : 1;
      if (light.type == LightType::directional) info.direction = -glm::normalize(light.direction);
      if (info.count > 1)
        for (int depth = 1; depth <= settings.max_depth; ++depth)
          info.patterns.emplace_back(uint32_t(info.count), hash_u32(li, uint64_t(depth)));
      lights_.push_back(std::move(info));
    }
    for (const Material& m : scene.materials) highlight_floors_.push_back(highlight_floor(m.shininess));
  }

  /// The color along the ray from `origin` in unit direction `dir` at `time`, at recursion depth `depth` (1 = eye
  /// ray); `weight` is the product of the K's so far. The ray comes in registers (two vectors and the time): passed as
  /// a Ray in memory, its copy here read back 16 bytes the caller had just stored piecewise, and stalled on store
  /// forwarding.
  Vec3f radiance(Vec3f origin, Vec3f dir, float time, int depth, const Vec3f& weight, Rng& rng,
                 const PrimaryNumbers* primary, uint64_t& rays) const {
    ++rays;
    Ray ray;
    ray.origin = origin;
    ray.dir = dir;
    ray.time = time;
    SurfaceHit h;
    if (!scene_.world.intersect(ray, h)) return scene_.background;
    const auto material = size_t(scene_.world.material(h.object));
    const Material& m = scene_.materials[material];

    // Face the normals toward the incoming ray; remember which side of the surface the ray came from.
    const bool entering = glm::dot(dir, h.hit.normal) < 0.0f;
    const Vec3f ng = entering ? h.hit.normal : -h.hit.normal;
    Vec3f n = entering ? h.shading_normal : -h.shading_normal;
    if (glm::dot(n, -dir) <= 0.0f) n = ng;  // an interpolated normal facing away from the viewer
    const Vec3f e = -dir;
    const Vec3f p = h.hit.point;
    const float offset = offset_scale(p);

    const Vec3f cr = surface_color(scene_.world, m, ray, h);
    Vec3f c = m.emission + cr * m.ambient * scene_.ambient;
    if (cr != Vec3f(0.0f) || m.specular != Vec3f(0.0f))
      c += direct_light(material, cr, p + offset * ng, n, ng, e, time, rng, primary, depth, rays);

    // Split K_trans into reflection and transmission (total internal reflection, optional Fresnel).
    Vec3f k_refl = m.reflection, k_trans = m.transmission;
    std::optional<Vec3f> t_dir;
    if (k_trans != Vec3f(0.0f)) {
      const float n1 = entering ? ior::kVacuum : m.ior, n2 = entering ? m.ior : ior::kVacuum;
      t_dir = refract_dir(dir, n, n1 / n2);
      const float f = !t_dir ? 1.0f : m.fresnel ? schlick_fresnel(glm::dot(n, e), n1, n2) : 0.0f;
      k_refl += f * k_trans;
      k_trans *= 1.0f - f;
    }
    if (depth >= settings_.max_depth) return c;
    if (k_refl != Vec3f(0.0f) && max_component(weight * k_refl) >= settings_.min_contribution) {
      Vec3f refl = reflect_dir(e, n);
      if (m.glossiness > 0.0f) {
        // The notes' glossy reflection: the mirror direction spread in a Phong lobe (1/n sum K_refl C_Ri over the
        // pixel's samples); a direction below the surface falls back to the mirror direction.
        const Vec3f g = Frame::from_normal(refl).to_world(sample_phong_lobe(
            primary ? primary->gloss : Vec2f(rng.uniform(), rng.uniform()), glossy_exponent(m.glossiness)));
        if (glm::dot(g, ng) > 0.0f) refl = g;
      }
      c += k_refl * radiance(p + offset * ng, refl, time, depth + 1, weight * k_refl, rng, nullptr, rays);
    }
    if (t_dir && k_trans != Vec3f(0.0f) && max_component(weight * k_trans) >= settings_.min_contribution)
      c += k_trans * radiance(p - offset * ng, *t_dir, time, depth + 1, weight * k_trans, rng, nullptr, rays);
    return c;
  }

 private:
  /// What the shading of every hit needs of a light, computed once per render.
  struct LightInfo {
    int count = 1;                            // shadow rays per shading point
    Vec3f direction{0.0f};                    // directional lights: unit direction toward the light
    std::vector<StratifiedPattern> patterns;  // several shadow rays: the stratified set of each depth 1, 2, ...
  };

  /// C_L (C_r (N . L) + highlight) visible(P, L) for one sample of a light, the highlight only above the material's
  /// `cutoff` cosine (highlight_floor). The shadow ray last, and only for a term that adds something (a black surface
  /// away from its highlight, e.g. glass, needs none).
  Vec3f sample_term(const Material& m, float cutoff, const Vec3f& cr, const Vec3f& p, const Vec3f& n, const Vec3f& ng,
                    const Vec3f& e, const LightSample& ls, float time, uint64_t& rays) const {
    const float nl = glm::dot(n, ls.dir);
    if (nl <= 0.0f || glm::dot(ng, ls.dir) <= 0.0f || ls.color == Vec3f(0.0f)) return Vec3f(0.0f);
    float highlight = 0.0f;
    if (m.specular != Vec3f(0.0f)) {
      const float cos_h = m.model == SpecularModel::phong ? glm::dot(e, reflect_dir(ls.dir, n))
                                                          : glm::dot(n, glm::normalize(ls.dir + e));
      if (cos_h > cutoff) highlight = highlight_power(cos_h, m.shininess);
    }
    const Vec3f term = ls.color * (cr * nl + m.specular * highlight);
    return term != Vec3f(0.0f) && visible(scene_.world, p, ls, time, rays) ? term : Vec3f(0.0f);
  }

  /// The sum over lights of C_L (C_r (N . L) + highlight) visible(P, L), area lights averaged over their samples; the
  /// shadow rays at the path's `time`.
  Vec3f direct_light(size_t material, const Vec3f& cr, const Vec3f& p, const Vec3f& n, const Vec3f& ng, const Vec3f& e,
                     float time, Rng& rng, const PrimaryNumbers* primary, int depth, uint64_t& rays) const {
    const Material& m = scene_.materials[material];
    const float cutoff = highlight_floors_[material];
    Vec3f sum(0.0f);
    for (size_t li = 0; li < lights_.size(); ++li) {
      const Light& light = scene_.lights[li];
      const LightInfo& info = lights_[li];
      if (light.type == LightType::point) {
        // A light behind the surface is culled before the square root (N . (q - p) has the sign of N . L).
        const Vec3f to = light.position - p;
        if (glm::dot(n, to) > 0.0f && glm::dot(ng, to) > 0.0f)
          sum += sample_term(m, cutoff, cr, p, n, ng, e, light_toward(light.position, p, light.color), time, rays);
      } else if (light.type == LightType::directional) {
        const LightSample ls{info.direction, std::numeric_limits<float>::infinity(), light.color};
        sum += sample_term(m, cutoff, cr, p, n, ng, e, ls, time, rays);
      } else {
        // The area light's stratified set of this depth, rotated by the pixel sample's number (Cranley-Patterson) so
        // that the sets of a pixel's samples interleave.
        const Vec2f rotation = primary ? primary->light : Vec2f(rng.uniform(), rng.uniform());
        Vec3f light_sum(0.0f);
        for (int k = 0; k < info.count; ++k) {
          const Vec2f u =
              info.count > 1 ? glm::fract(info.patterns[size_t(depth - 1)].sample(uint32_t(k)) + rotation) : rotation;
          light_sum += sample_term(m, cutoff, cr, p, n, ng, e, sample_light(light, p, u), time, rays);
        }
        sum += info.count > 1 ? light_sum / float(info.count) : light_sum;
      }
    }
    return sum;
  }

  const RayScene& scene_;
  const RenderSettings& settings_;
  std::vector<LightInfo> lights_;
  std::vector<float> highlight_floors_;  // per material: highlight_floor(shininess)
};

void check_settings(const RayScene& scene, const RenderSettings& s) {
  if (s.width <= 0 || s.height <= 0) throw InvalidInput(fmt::format("render: bad image size {}x{}", s.width, s.height));
  if (s.samples <= 0) throw InvalidInput(fmt::format("render: samples must be positive, got {}", s.samples));
  if (s.max_depth < 1 || s.max_depth > RenderSettings::kMaxDepth)
    throw InvalidInput(
        fmt::format("render: max depth must be in [1, {}], got {}", RenderSettings::kMaxDepth, s.max_depth));
  if (s.tile_size <= 0) throw InvalidInput("render: tile size must be positive");
  if (const auto& w = s.window;
      w && !(0 <= w->x0 && w->x0 < w->x1 && w->x1 <= s.width && 0 <= w->y0 && w->y0 < w->y1 && w->y1 <= s.height))
    throw InvalidInput(fmt::format("render: window [{}, {}) x [{}, {}) is empty or outside the {}x{} frame", w->x0,
                                   w->x1, w->y0, w->y1, s.width, s.height));
  for (int i = 0; i < scene.world.size(); ++i)
    if (scene.world.material(i) < 0 || size_t(scene.world.material(i)) >= scene.materials.size())
      throw InvalidInput(
          fmt::format("render: object {} has material {} of {}", i, scene.world.material(i), scene.materials.size()));
}

}  // namespace

Shape light_surface(const Light& light) {
  const Vec3f a = light.position;
  switch (light.type) {
    case LightType::rect:
      return Polygon{{a, a + light.edge_u, a + light.edge_u + light.edge_v, a + light.edge_v}};
    case LightType::disk:
      return Disk{a, glm::normalize(light.direction), light.radius};
    case LightType::sphere:
      return Sphere{a, light.radius};
    default:
      throw InvalidInput("light_surface: a point or directional light has no surface");
  }
}

void add_light_surfaces(RayScene& scene) {
  for (const Light& light : scene.lights) {
    if (!light.is_area() || !light.visible) continue;
    Material glow;
    glow.diffuse = Vec3f(0.0f);
    glow.emission = light.color;
    scene.materials.push_back(glow);
    const int material = int(scene.materials.size()) - 1;
    scene.world.set_casts_shadows(scene.world.add_shape(light_surface(light), Mat4(1.0), material), false);
  }
}

Ray eye_ray(const RayScene& scene, int width, int height, int x, int y, const Vec2f& offset, const Vec2f& lens,
            float time) {
  return CameraRays(scene, width, height).ray(x, y, offset, lens, time);
}

float visible_fraction(const RayScene& scene, const Vec3f& p, const Light& light, int n, uint32_t pattern) {
  uint64_t rays = 0;
  int seen = 0;
  const StratifiedPattern samples(uint32_t(n), pattern);
  for (int k = 0; k < n; ++k) {
    const LightSample ls = sample_light(light, p, samples.sample(uint32_t(k)));
    seen += visible(scene.world, p, ls, 0.0f, rays) ? 1 : 0;
  }
  return float(seen) / float(n);
}

Vec3f trace_ray(const RayScene& scene, const RenderSettings& settings, const Ray& ray, uint64_t rng_sequence) {
  check_settings(scene, settings);
  Rng rng(rng_sequence, settings.seed);
  uint64_t rays = 0;
  return Tracer(scene, settings)
      .radiance(ray.origin, glm::normalize(ray.dir), ray.time, 1, Vec3f(1.0f), rng, nullptr, rays);
}

ImageRGB render(const RayScene& scene, const RenderSettings& settings, RenderStats* stats) {
  check_settings(scene, settings);
  const auto start = std::chrono::steady_clock::now();
  const int w = settings.width, h = settings.height;
  const RenderSettings::Window window = settings.window.value_or(RenderSettings::Window{0, 0, w, h});
  const CameraRays camera(scene, w, h);
  const Tracer tracer(scene, settings);
  ImageRGB image(window.x1 - window.x0, window.y1 - window.y0);
  const auto spp = uint32_t(settings.samples);
  const int tiles_x = (image.width() + settings.tile_size - 1) / settings.tile_size;
  const int tiles_y = (image.height() + settings.tile_size - 1) / settings.tile_size;
  std::unique_ptr<Progress> progress;
  if (settings.progress) progress = std::make_unique<Progress>("render", int64_t(tiles_x) * tiles_y);
  std::atomic<uint64_t> total_rays{0};
  bool used[kDimensions];
  used[kPixel] = spp > 1;
  used[kTime] = spp > 1 && scene.world.has_motion();
  used[kLight] = std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) { return l.is_area(); });
  used[kGloss] = std::any_of(scene.materials.begin(), scene.materials.end(),
                             [](const Material& m) { return m.glossiness > 0.0f; });
  used[kLens] = scene.aperture > 0.0f;
  std::optional<SmallPattern> small;
  if (spp <= kBlock) small.emplace(spp);
  parallel_tiles(image.width(), image.height(), settings.tile_size, [&](const Tile& tile) {
    uint64_t rays = 0;
    // The hashed patterns beyond kBlock samples, set per pixel; declared per tile so that pixels with few samples
    // don't pay for clearing them.
    std::optional<StratifiedPattern> pattern[kDimensions];
    for (int y = tile.y0 + window.y0; y < tile.y1 + window.y0; ++y)
      for (int x = tile.x0 + window.x0; x < tile.x1 + window.x0; ++x) {
        const uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
        Rng rng(pixel, settings.seed);
        // Only the dimensions the scene uses are drawn (each is its own pattern, so skipping one changes no other).
        // With one sample the eye ray goes through the pixel center at mid-shutter. Up to kBlock samples the
        // numbers come from the pixel's Rng (before any bounce uses it), beyond from per-dimension hashed patterns.
        if (!small)
          for (uint32_t dim = 0; dim < kDimensions; ++dim)
            if (used[dim]) pattern[dim].emplace(spp, hash_u32(pixel, dim, settings.seed));
        Vec3f sum(0.0f);
        // The numbers of a block of samples first (cheaper together), then their rays.
        Vec2f numbers[kDimensions][kBlock];
        for (uint32_t first = 0; first < spp; first += kBlock) {
          const uint32_t count = std::min(kBlock, spp - first);
          for (uint32_t dim = 0; dim < kDimensions; ++dim) {
            if (small && used[dim])
              small->draw(rng, numbers[dim]);
            else if (pattern[dim])
              pattern[dim]->samples(first, std::span(numbers[dim], count));
            else
              std::fill_n(numbers[dim], count, Vec2f(0.5f));
          }
          for (uint32_t i = 0; i < count; ++i) {
            const PrimaryNumbers primary{numbers[kLight][i], numbers[kGloss][i]};
            const Ray ray = camera.ray(x, y, numbers[kPixel][i], numbers[kLens][i], numbers[kTime][i].x);
            sum += tracer.radiance(ray.origin, ray.dir, ray.time, 1, Vec3f(1.0f), rng, &primary, rays);
          }
        }
        image(x - window.x0, y - window.y0) = sum / float(spp);
      }
    total_rays += rays;
    if (progress) progress->advance();
  });
  if (progress) progress->done();
  if (stats) {
    stats->eye_rays = uint64_t(image.width()) * uint64_t(image.height()) * spp;
    stats->rays = total_rays;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return image;
}

}  // namespace tessera
