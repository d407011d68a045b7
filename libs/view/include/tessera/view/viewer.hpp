#pragma once
// The interactive viewer (`tessera view FILE`, docs/view.md): a 3D sketch run by the sketch runner (libs/sketch), so
// that it opens a window, runs headless, takes scripted input and records animations as every sketch does. It shows
// a mesh, a scene, a volume or Bezier patches (viewable.hpp), turned with the arcball, panned and zoomed (arcball.hpp),
// drawn through the one library mesh renderer (scene's MeshView), the scene rasterizer, the progressive ray tracer
// or the volume ray caster, with a one-line status text at the bottom.
//
// Mouse: left drag orbits (Shoemake's arcball), right or middle drag pans, the wheel zooms.
// Keys: 1-6 unlit, flat, Gouraud, Phong, wireframe, normals; w edges over the surface; + and - the subdivision level
// (meshes: Catmull-Clark, or Loop for triangle meshes, creases kept; patches: the tessellation); d shadows (with a
// floor); t texture (the given image, or a checkerboard of the uvs); Tab the renderer (scenes: rasterizer or
// progressive ray tracer; volumes: iso-surface or volume rendering); up and down the iso value or the transfer
// function's window level, left and right its width; s a screenshot; r the home view; h help; Escape quits.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/sketch/sketch.hpp"
#include "tessera/view/arcball.hpp"
#include "tessera/view/viewable.hpp"

namespace tessera {

namespace detail {
class ViewMode;  // how one kind of viewable is drawn (src/view_mode.hpp)
}

/// How the viewer shades a surface (keys 1 to 6).
enum class ViewShading { unlit, flat, gouraud, phong, wireframe, normals };

/// The shading's name as the status line and --shading spell it ("unlit", ..., "normals").
std::string_view shading_name(ViewShading shading);

/// Settings of a Viewer (`tessera view`'s options).
struct ViewerOptions {
  int width = 1280, height = 720;  ///< the sketch's size (the runner's --size replaces it)
  /// Above 0: a turntable, frame k (1, 2, ...) turned (k - 1) / orbit_frames of a full turn about the home view's up
  /// vector, on top of what the mouse did.
  int orbit_frames = 0;
  ViewShading shading = ViewShading::gouraud;  ///< the first shading of a surface
  /// The model's up axis (1 y, 2 z; -1: z for Bezier patches, whose data sets are z-up as Newell's teapot, else y):
  /// the home view's vertical, the turntable's axis and the floor's normal.
  int up_axis = -1;
  std::string texture;  ///< a texture image for surfaces with uvs ("" = a checkerboard)
  /// A GLSL program drawing the surfaces instead of the shading (both files, or neither; docs/shaders.md), its
  /// uniforms ("name=v1,v2,...") and `texture` (when given) on texture unit 0.
  std::string vertex_shader, fragment_shader;
  std::vector<std::string> uniforms;
  /// Compile the program again when its files change on disk, checked every frame (the window keeps drawing).
  bool watch_shaders = false;
  bool status_line = true;  ///< the one-line text at the bottom
  /// The status line shows the last frame's render time (in a window; headless pictures stay deterministic).
  bool frame_time = false;
  int trace_samples = 2;                             ///< the progressive ray tracer's samples per pixel per frame
  int trace_max_passes = 64;                         ///< it stops refining after this many frames at rest
  std::string screenshot = "tessera-view-####.png";  ///< where `s` saves the frame (#### = the frame number)
};

/// What the viewer has drawn, for --stats.
struct ViewerStats {
  size_t triangles = 0;       ///< triangles of the surface last drawn (0 for volume and ray-traced pictures)
  int renders = 0;            ///< pictures rendered
  double render_seconds = 0;  ///< time spent rendering them
};

/// The viewer as a sketch: hand it to run_sketch() (runner.hpp).
class Viewer : public Sketch {
 public:
  /// A viewer of `viewable` (read_viewable). The renderers are prepared in setup(). Throws InvalidInput for bad
  /// options (a size or trace samples below 1).
  Viewer(Viewable viewable, ViewerOptions options);
  ~Viewer() override;

  void setup() override;
  void draw() override;
  void mouse_pressed() override;
  void mouse_dragged() override;
  void mouse_wheel(double delta) override;
  void key_pressed() override;

  /// The status line's text as last drawn (without the frame time when frame_time is off).
  const std::string& status() const { return status_; }
  /// The camera control (orbit, pan, zoom).
  const OrbitControl& control() const { return control_; }
  /// Figures for --stats.
  const ViewerStats& stats() const { return stats_; }
  /// The help text `h` shows (one line per control).
  static std::vector<std::string> help_lines();

 private:
  Camera current_camera() const;
  void changed() {
    moved_ = true;
    redraw();
  }

  Viewable viewable_;
  ViewerOptions options_;
  std::unique_ptr<detail::ViewMode> mode_;
  OrbitControl control_;
  ViewerStats stats_;
  std::string status_;
  std::string screenshot_;  // where the next draw() saves its picture ("" = nowhere)
  std::string note_;        // a message for the next status line
  bool moved_ = true, help_ = false;
  double last_seconds_ = 0;
};

}  // namespace tessera
