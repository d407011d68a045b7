// The viewer's scenes: the scene rasterizer every frame, or (Tab) the ray tracer refining while the camera rests: each
// frame at rest traces a few more samples per pixel with a new seed and the picture is their running mean.
#include <fmt/format.h>

#include <optional>

#include "tessera/scene/raster.hpp"
#include "tessera/scene/trace.hpp"
#include "tessera/sketch/input.hpp"
#include "view_mode.hpp"

namespace tessera::detail {
namespace {

class SceneMode final : public ViewMode {
 public:
  SceneMode(const Viewable& v, const ViewerOptions& o)
      : scene_(*v.scene), home_(scene_.camera), samples_(o.trace_samples), max_passes_(o.trace_max_passes) {}
  OrbitControl home(double aspect) const override {
    // Near and far as the rasterizer's; the sphere orbited is the one about the look-at point reaching halfway to
    // the eye (it sets how far the zoom and pan go).
    const Camera camera = home_.camera(aspect, 0.05, 4000);
    return OrbitControl(camera, camera.center, 0.5 * glm::length(camera.eye - camera.center));
  }
  void render(const Camera& camera, bool moved, ImageRGBA8& out) override {
    const int w = out.width(), h = out.height();
    if (!tracing_) {
      scene_.camera.eye = camera.eye;  // the rest of the scene's camera (its lens) stays as loaded
      scene_.camera.center = camera.center;
      scene_.camera.up = camera.up;
      scene_.camera.ortho_height = camera.ortho_height;
      to_frame(rasterize_scene(scene_, w, h, RasterShadows::map, kShadowMapSize), out);
      return;
    }
    if (!ray_scene_) ray_scene_.emplace(to_ray_scene(scene_));
    if (moved || sum_.width() != w || sum_.height() != h) {
      sum_ = ImageRGB(w, h, Vec3f(0.0f));
      passes_ = 0;
    }
    ray_scene_->camera = camera;
    RenderSettings settings = render_settings(scene_);
    settings.width = w;
    settings.height = h;
    settings.samples = samples_;
    settings.seed = uint64_t(passes_);
    settings.progress = false;
    const ImageRGB pass = tessera::render(*ray_scene_, settings);
    ++passes_;
    for (size_t i = 0; i < sum_.pixels().size(); ++i) sum_.pixels()[i] += pass.pixels()[i];
    to_frame(sum_, out, float(passes_));  // the passes' mean
  }
  bool key(int key, int) override {
    if (key != Key::tab) return false;
    tracing_ = !tracing_;
    return true;
  }
  std::string describe() const override {
    if (tracing_) return fmt::format("{}: scene, ray traced, {} samples per pixel", scene_.name, passes_ * samples_);
    return fmt::format("{}: scene, {} objects, rasterized", scene_.name, scene_.objects.size());
  }
  bool refining() const override { return tracing_ && passes_ < max_passes_; }

 private:
  static constexpr int kShadowMapSize = 1024;  // half the still pictures' (each frame draws the maps again)
  Scene scene_;                                // its camera follows the view (the rasterizer's)
  const SceneCamera home_;                     // the scene's own camera
  std::optional<RayScene> ray_scene_;          // built when first asked for
  ImageRGB sum_;
  int samples_, max_passes_, passes_ = 0;
  bool tracing_ = false;
};

}  // namespace

std::unique_ptr<ViewMode> make_scene_mode(const Viewable& v, const ViewerOptions& o) {
  return std::make_unique<SceneMode>(v, o);
}

}  // namespace tessera::detail
