// The recursive (Whitted) and distribution ray tracer and the tile renderer.
#include "tessera/raytrace/render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>

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

/// Stratified numbers of one pixel sample for the first hit; null at deeper bounces.
struct PrimaryNumbers {
  Vec2f light, gloss;
};

/// Moves a ray origin off the surface along the geometric normal, relative to the point's magnitude.
Vec3f offset_point(const Vec3f& p, const Vec3f& n) {
  const float scale = 1.0f + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return p + (2e-4f * scale) * n;
}

/// True when nothing blocks the segment from p toward the light sample (the notes' visible(P, L)).
bool visible(const World& world, const Vec3f& p, const LightSample& ls, uint64_t& rays) {
  ++rays;
  Ray shadow;
  shadow.origin = p;
  shadow.dir = ls.dir;
  shadow.tmax = std::isinf(ls.distance) ? ls.distance : ls.distance * (1.0f - 1e-4f);
  return !world.occluded(shadow);
}

float max_component(const Vec3f& v) { return std::max({v.x, v.y, v.z}); }

/// The surface color C_r at a hit: the diffuse color or the checkerboard's, times the texture.
Vec3f surface_color(const Material& m, const SurfaceHit& h) {
  Vec3f c = m.diffuse;
  if (m.checker > 0.0f) {
    const Vec3f cell = glm::floor(h.hit.point / m.checker + 1e-4f);
    if ((int64_t(cell.x) + int64_t(cell.y) + int64_t(cell.z)) & 1) c = m.checker_color;
  }
  if (m.texture) c *= Vec3f(m.texture->sample(h.uv));
  return c;
}

class Tracer {
 public:
  Tracer(const RayScene& scene, const RenderSettings& settings) : scene_(scene), settings_(settings) {}

  /// The color along `ray` at recursion depth `depth` (1 = eye ray); `weight` is the product of the K's so far.
  Vec3f radiance(const Ray& ray, int depth, const Vec3f& weight, Rng& rng, const PrimaryNumbers* primary,
                 uint64_t& rays) const {
    ++rays;
    Ray r = ray;
    SurfaceHit h;
    if (!scene_.world.intersect(r, h)) return scene_.background;
    const Material& m = scene_.materials[size_t(scene_.world.material(h.object))];

    // Face the normals toward the incoming ray; remember which side of the surface the ray came from.
    const Vec3f d = glm::normalize(ray.dir);
    const bool entering = glm::dot(d, h.hit.normal) < 0.0f;
    const Vec3f ng = entering ? h.hit.normal : -h.hit.normal;
    Vec3f n = entering ? h.shading_normal : -h.shading_normal;
    if (glm::dot(n, -d) <= 0.0f) n = ng;  // an interpolated normal facing away from the viewer
    const Vec3f e = -d;
    const Vec3f p = h.hit.point;
    const Vec3f above = offset_point(p, ng), below = offset_point(p, -ng);

    const Vec3f cr = surface_color(m, h);
    Vec3f c = m.emission + cr * m.ambient * scene_.ambient;
    if (cr != Vec3f(0.0f) || m.specular != Vec3f(0.0f))
      c += direct_light(m, cr, above, n, ng, e, rng, primary, depth, rays);

    // Split K_trans into reflection and transmission (total internal reflection, optional Fresnel).
    Vec3f k_refl = m.reflection, k_trans = m.transmission;
    std::optional<Vec3f> t_dir;
    if (k_trans != Vec3f(0.0f)) {
      const float n1 = entering ? ior::kVacuum : m.ior, n2 = entering ? m.ior : ior::kVacuum;
      t_dir = refract_dir(d, n, n1 / n2);
      const float f = !t_dir ? 1.0f : m.fresnel ? schlick_fresnel(glm::dot(n, e), n1, n2) : 0.0f;
      k_refl += f * k_trans;
      k_trans *= 1.0f - f;
    }
    if (depth >= settings_.max_depth) return c;
    if (k_refl != Vec3f(0.0f) && max_component(weight * k_refl) >= settings_.min_contribution) {
      Ray refl;
      refl.origin = above;
      refl.dir = reflect_dir(e, n);
      refl.time = ray.time;
      if (m.glossiness > 0.0f) {
        // The notes' glossy reflection: the mirror direction spread in a Phong lobe (1/n sum K_refl C_Ri over the
        // pixel's samples); a direction below the surface falls back to the mirror direction.
        const Vec3f g = Frame::from_normal(refl.dir).to_world(sample_phong_lobe(
            primary ? primary->gloss : Vec2f(rng.uniform(), rng.uniform()), glossy_exponent(m.glossiness)));
        if (glm::dot(g, ng) > 0.0f) refl.dir = g;
      }
      c += k_refl * radiance(refl, depth + 1, weight * k_refl, rng, nullptr, rays);
    }
    if (t_dir && k_trans != Vec3f(0.0f) && max_component(weight * k_trans) >= settings_.min_contribution) {
      Ray trans;
      trans.origin = below;
      trans.dir = *t_dir;
      trans.time = ray.time;
      c += k_trans * radiance(trans, depth + 1, weight * k_trans, rng, nullptr, rays);
    }
    return c;
  }

 private:
  /// The sum over lights of C_L (C_r (N . L) + highlight) visible(P, L), area lights averaged over their samples.
  Vec3f direct_light(const Material& m, const Vec3f& cr, const Vec3f& p, const Vec3f& n, const Vec3f& ng,
                     const Vec3f& e, Rng& rng, const PrimaryNumbers* primary, int depth, uint64_t& rays) const {
    Vec3f sum(0.0f);
    for (size_t li = 0; li < scene_.lights.size(); ++li) {
      const Light& light = scene_.lights[li];
      const int count = light.is_area() ? std::max(1, light.samples) : 1;
      // An area light's stratified set for this hit, rotated by the pixel sample's number (Cranley-Patterson) so
      // that the sets of a pixel's samples interleave. Point and directional lights need no numbers.
      Vec2f rotation(0.0f);
      if (light.is_area()) rotation = primary ? primary->light : Vec2f(rng.uniform(), rng.uniform());
      const uint32_t pattern = count > 1 ? hash_u32(li, uint64_t(depth)) : 0;
      Vec3f light_sum(0.0f);
      for (int k = 0; k < count; ++k) {
        const Vec2f u =
            count > 1 ? glm::fract(stratified_sample(uint32_t(k), uint32_t(count), pattern) + rotation) : rotation;
        const LightSample ls = sample_light(light, p, u);
        const float nl = glm::dot(n, ls.dir);
        if (nl <= 0.0f || glm::dot(ng, ls.dir) <= 0.0f || ls.color == Vec3f(0.0f)) continue;
        if (!visible(scene_.world, p, ls, rays)) continue;
        float highlight = 0.0f;
        if (m.specular != Vec3f(0.0f)) {
          const float cos_h = m.model == SpecularModel::phong ? glm::dot(e, reflect_dir(ls.dir, n))
                                                              : glm::dot(n, glm::normalize(ls.dir + e));
          highlight = std::pow(std::max(0.0f, cos_h), m.shininess);
        }
        light_sum += ls.color * (cr * nl + m.specular * highlight);
      }
      sum += light_sum / float(count);
    }
    return sum;
  }

  const RayScene& scene_;
  const RenderSettings& settings_;
};

void check_settings(const RayScene& scene, const RenderSettings& s) {
  if (s.width <= 0 || s.height <= 0) throw InvalidInput(fmt::format("render: bad image size {}x{}", s.width, s.height));
  if (s.samples <= 0) throw InvalidInput(fmt::format("render: samples must be positive, got {}", s.samples));
  if (s.max_depth <= 0) throw InvalidInput(fmt::format("render: max depth must be positive, got {}", s.max_depth));
  if (s.tile_size <= 0) throw InvalidInput("render: tile size must be positive");
  for (int i = 0; i < scene.world.size(); ++i)
    if (scene.world.material(i) < 0 || size_t(scene.world.material(i)) >= scene.materials.size())
      throw InvalidInput(
          fmt::format("render: object {} has material {} of {}", i, scene.world.material(i), scene.materials.size()));
}

}  // namespace

void add_light_surfaces(RayScene& scene) {
  for (const Light& light : scene.lights) {
    if (!light.is_area() || !light.visible) continue;
    Material glow;
    glow.diffuse = Vec3f(0.0f);
    glow.emission = light.color;
    scene.materials.push_back(glow);
    const int material = int(scene.materials.size()) - 1;
    Shape shape;
    if (light.type == LightType::rect) {
      const Vec3f a = light.position;
      shape = Polygon{{a, a + light.edge_u, a + light.edge_u + light.edge_v, a + light.edge_v}};
    } else if (light.type == LightType::disk) {
      shape = Disk{light.position, glm::normalize(light.direction), light.radius};
    } else {
      shape = Sphere{light.position, light.radius};
    }
    scene.world.set_casts_shadows(scene.world.add_shape(shape, Mat4(1.0), material), false);
  }
}

Ray eye_ray(const RayScene& scene, const EyeRays& rays, int x, int y, const Vec2f& offset, const Vec2f& lens,
            float time) {
  Ray ray = rays.ray(x, y, offset.x, offset.y);
  ray.time = time;
  if (scene.aperture > 0.0f) {
    Vec3 u, v, w;
    scene.camera.frame(u, v, w);
    const float focus =
        scene.focal_distance > 0.0f ? scene.focal_distance : float(glm::length(scene.camera.center - scene.camera.eye));
    const Vec3f focal_point = ray.origin + (focus / glm::dot(ray.dir, -Vec3f(w))) * ray.dir;
    const Vec2f l = scene.aperture * sample_disk(lens);
    ray.origin += l.x * Vec3f(u) + l.y * Vec3f(v);
    ray.dir = glm::normalize(focal_point - ray.origin);
  }
  return ray;
}

float visible_fraction(const RayScene& scene, const Vec3f& p, const Light& light, int n, uint32_t pattern) {
  uint64_t rays = 0;
  int seen = 0;
  for (int k = 0; k < n; ++k) {
    const LightSample ls = sample_light(light, p, stratified_sample(uint32_t(k), uint32_t(n), pattern));
    seen += visible(scene.world, p, ls, rays) ? 1 : 0;
  }
  return float(seen) / float(n);
}

Vec3f trace_ray(const RayScene& scene, const RenderSettings& settings, const Ray& ray, uint64_t rng_sequence) {
  check_settings(scene, settings);
  Rng rng(rng_sequence, settings.seed);
  uint64_t rays = 0;
  return Tracer(scene, settings).radiance(ray, 1, Vec3f(1.0f), rng, nullptr, rays);
}

ImageRGB render(const RayScene& scene, const RenderSettings& settings, RenderStats* stats) {
  check_settings(scene, settings);
  const auto start = std::chrono::steady_clock::now();
  const int w = settings.width, h = settings.height;
  Camera camera = scene.camera;
  camera.aspect = double(w) / double(h);
  const EyeRays eye_rays(camera, w, h);
  const Tracer tracer(scene, settings);
  ImageRGB image(w, h);
  const auto spp = uint32_t(settings.samples);
  const int tiles_x = (w + settings.tile_size - 1) / settings.tile_size;
  const int tiles_y = (h + settings.tile_size - 1) / settings.tile_size;
  std::unique_ptr<Progress> progress;
  if (settings.progress) progress = std::make_unique<Progress>("render", int64_t(tiles_x) * tiles_y);
  std::atomic<uint64_t> total_rays{0};
  const bool distributed_pixel = spp > 1;
  const bool uses_time = scene.world.has_motion();
  const bool uses_light =
      std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) { return l.is_area(); });
  const bool uses_gloss = std::any_of(scene.materials.begin(), scene.materials.end(),
                                      [](const Material& m) { return m.glossiness > 0.0f; });
  parallel_tiles(w, h, settings.tile_size, [&](const Tile& tile) {
    uint64_t rays = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
        Rng rng(pixel, settings.seed);
        uint32_t pattern[kDimensions];
        for (uint32_t dim = 0; dim < kDimensions; ++dim) pattern[dim] = hash_u32(pixel, dim, settings.seed);
        Vec3f sum(0.0f);
        for (uint32_t s = 0; s < spp; ++s) {
          // Only the dimensions the scene uses are drawn (each is its own pattern, so skipping one changes no other).
          // With one sample the eye ray goes through the pixel center at mid-shutter.
          const auto draw = [&](Dimension dim, bool used) {
            return used ? stratified_sample(s, spp, pattern[dim]) : Vec2f(0.5f);
          };
          const Vec2f offset = draw(kPixel, distributed_pixel);
          const float time = draw(kTime, uses_time && distributed_pixel).x;
          const PrimaryNumbers primary{draw(kLight, uses_light), draw(kGloss, uses_gloss)};
          const Ray ray = eye_ray(scene, eye_rays, x, y, offset, draw(kLens, scene.aperture > 0.0f), time);
          sum += tracer.radiance(ray, 1, Vec3f(1.0f), rng, &primary, rays);
        }
        image(x, y) = sum / float(spp);
      }
    total_rays += rays;
    if (progress) progress->advance();
  });
  if (progress) progress->done();
  if (stats) {
    stats->eye_rays = uint64_t(w) * uint64_t(h) * spp;
    stats->rays = total_rays;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return image;
}

}  // namespace tessera
