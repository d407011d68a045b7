// The viewer's volumes: an iso-surface by marching cubes (up and down move the iso value), or direct volume rendering
// through a transfer function's window (up and down move its level, left and right its width); Tab switches.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "mesh_display.hpp"
#include "tessera/sketch/input.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/volume_render.hpp"
#include "view_mode.hpp"

namespace tessera::detail {
namespace {

class VolumeMode final : public ViewMode {
 public:
  VolumeMode(const Viewable& v, const ViewerOptions& o)
      : display_(o),
        up_axis_(o.up_axis),
        name_(file_name(v.name)),
        volume_(v.volume),
        profile_(profile_values(*v.volume)) {
    // The iso value starts at Otsu's threshold (object from background), the window on the object's values.
    iso_ = profile_.threshold;
    const double top = profile_.separable() ? profile_.top : profile_.hi;
    width_ = std::max(top - profile_.threshold, (profile_.hi - profile_.lo) / 100);
    level_ = profile_.threshold + width_ / 2;
    if (!(width_ > 0)) width_ = 1;
    extract();
  }
  OrbitControl home(double aspect) const override {
    return frame_box(volume_->origin(), volume_->to_world(Vec3(volume_->dims() - 1)), aspect, up_axis_);
  }
  void render(const Camera& camera, bool, ImageRGBA8& out) override {
    if (!rendering_) {
      display_.render(camera, out);
      return;
    }
    if (!renderer_) renderer_.emplace(*volume_);
    VolumeRenderOptions options;
    options.camera = camera;
    options.width = out.width();
    options.height = out.height();
    options.transfer = window();
    options.background = kBackground;
    to_frame(renderer_->render(options), out);
  }
  bool key(int key, int key_code) override {
    const double span = profile_.hi - profile_.lo;
    const bool coded = key == Key::coded;
    if (key == Key::tab) {
      rendering_ = !rendering_;
    } else if (coded && (key_code == Key::up || key_code == Key::down)) {
      const double sign = key_code == Key::up ? 1 : -1;
      if (rendering_) {
        level_ += sign * width_ / 10;
      } else {
        iso_ = std::clamp(iso_ + sign * span / 64, profile_.lo, profile_.hi);
        extract();
      }
    } else if (coded && rendering_ && (key_code == Key::left || key_code == Key::right)) {
      width_ = std::max(width_ * (key_code == Key::right ? 1.25 : 0.8), span / 1000);
    } else {
      return !rendering_ && display_.key(key);
    }
    return true;
  }
  std::string describe() const override {
    const glm::ivec3 d = volume_->dims();
    if (rendering_)
      return fmt::format("{}: {}x{}x{} volume rendered, window {:.4g} to {:.4g}", name_, d.x, d.y, d.z,
                         level_ - width_ / 2, level_ + width_ / 2);
    return fmt::format("{}: {}x{}x{} iso-surface {:.4g}, {} triangles, {}", name_, d.x, d.y, d.z, iso_,
                       display_.triangles(), display_.describe());
  }
  size_t triangles() const override { return rendering_ ? 0 : display_.triangles(); }
  bool poll() override { return !rendering_ && display_.poll(); }

 private:
  void extract() { display_.set_mesh(marching_cubes(*volume_, MarchingCubesOptions{.iso = float(iso_)})); }

  /// The transfer function of the window [level - width/2, level + width/2]: clear below it, a warm color ramping to
  /// white and to opacity 0.3 per three-hundredth of the diagonal above it (as TransferFunction::automatic).
  TransferFunction window() const {
    const double exponent = TransferFunction::kReferenceDiagonal / std::max(profile_.diagonal, 1e-30);
    const auto opacity = [&](double per_reference) { return float(1 - std::pow(1 - per_reference, exponent)); };
    const auto at = [&](double s) { return float(level_ + (s - 0.5) * width_); };
    return TransferFunction({{at(0), {0.8f, 0.35f, 0.2f}, 0},
                             {at(0.5), {0.95f, 0.7f, 0.45f}, opacity(0.05)},
                             {at(1), {1, 0.97f, 0.92f}, opacity(0.3)}});
  }

  MeshDisplay display_;
  int up_axis_;
  std::string name_;
  std::shared_ptr<Volume<float>> volume_;
  ValueProfile profile_;
  std::optional<VolumeRenderer> renderer_;  // prepared when first asked for
  double iso_ = 0, level_ = 0, width_ = 1;
  bool rendering_ = false;
};

}  // namespace

std::unique_ptr<ViewMode> make_volume_mode(const Viewable& v, const ViewerOptions& o) {
  return std::make_unique<VolumeMode>(v, o);
}

}  // namespace tessera::detail
