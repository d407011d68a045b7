#pragma once
// How the viewer draws one kind of viewable (private to the view module): a mode renders a picture for a camera,
// handles the keys of its kind and says what it shows.
#include <filesystem>
#include <memory>
#include <string>

#include "tessera/image/image.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/view/arcball.hpp"
#include "tessera/view/viewable.hpp"
#include "tessera/view/viewer.hpp"

namespace tessera::detail {

class ViewMode {
 public:
  virtual ~ViewMode() = default;
  /// The orbit control to start from (the home camera and the sphere it orbits) for an image of aspect w / h.
  virtual OrbitControl home(double aspect) const = 0;
  /// Draws the view through `camera` into `out` (its size is the picture's). `moved`: the camera or the mode's state
  /// changed since the last call (a progressive renderer starts again).
  virtual void render(const Camera& camera, bool moved, ImageRGBA8& out) = 0;
  /// Handles a key (Sketch::key, key_code); true when it changed what is drawn.
  virtual bool key(int key, int key_code) = 0;
  /// What is shown, for the status line.
  virtual std::string describe() const = 0;
  /// Whether drawing again with nothing changed improves the picture (the progressive ray tracer).
  virtual bool refining() const { return false; }
  /// Looks for changes from outside (a shader file edited); true when the picture must be drawn again.
  virtual bool poll() { return false; }
  /// The triangles of the surface drawn (0 when none is).
  virtual size_t triangles() const { return 0; }
};

/// The background of the viewer's surfaces and volume renderings: a dark gray, so that black (unlit back faces,
/// shadows) stays visible.
inline const Vec3f kBackground{0.1f, 0.1f, 0.12f};

/// The last component of a viewable's path, as the status line names it.
inline std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

/// The orbit control framing the box [lo, hi]: its bounding sphere seen from 30 degrees right of and 20 above the
/// front, filling 1/1.1 of the view; `up_axis` 1 (y up, the front +z) or 2 (z up, the front -y).
OrbitControl frame_box(const Vec3& lo, const Vec3& hi, double aspect, int up_axis);

/// The modes of each kind (surface_modes.cpp, volume_mode.cpp, scene_mode.cpp).
std::unique_ptr<ViewMode> make_mesh_mode(const Viewable& v, const ViewerOptions& o);
std::unique_ptr<ViewMode> make_patch_mode(const Viewable& v, const ViewerOptions& o);
std::unique_ptr<ViewMode> make_volume_mode(const Viewable& v, const ViewerOptions& o);
std::unique_ptr<ViewMode> make_scene_mode(const Viewable& v, const ViewerOptions& o);

/// The mode of `viewable`'s kind, the up axis resolved (ViewerOptions::up_axis). Throws as the preparation does
/// (subdivision, marching cubes, texture reading).
std::unique_ptr<ViewMode> make_view_mode(const Viewable& viewable, ViewerOptions options);

/// Converts a linear RGB picture, each color divided by `divisor` (a sum of that many pictures: their mean), to the
/// 8-bit frame (clamped and rounded as the framebuffer, no gamma).
void to_frame(const ImageRGB& picture, ImageRGBA8& out, float divisor = 1.0f);

}  // namespace tessera::detail
