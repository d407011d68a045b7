#pragma once
// A renderer-neutral scene: image settings, camera, ambient light, lights, named materials and objects (shapes or
// triangle meshes under transforms, optionally moving), read from the JSON format of docs/scene-format.md. The
// built-in scenes (scenes/*.json in the source tree) are embedded in the library.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/accel/shapes.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raytrace/light.hpp"
#include "tessera/raytrace/material.hpp"
#include "tessera/raytrace/world.hpp"

namespace tessera {

/// The picture to make.
struct SceneImage {
  int width = 640, height = 480;
  static constexpr int kMaxSamples = 1 << 16;  ///< the most samples per pixel a scene (or --spp) may ask for
  int samples = 1;                             ///< samples per pixel
  int max_depth = 5;                           ///< recursion depth (1 = eye rays only)
  Vec3f background{0.0f};                      ///< color of rays that leave the scene
};

/// A pinhole or thin-lens camera, perspective or orthographic.
struct SceneCamera {
  Vec3 eye{0, 0, 5}, center{0, 0, 0}, up{0, 1, 0};
  double fovy = 45;           ///< vertical field of view in degrees (perspective)
  double aperture = 0;        ///< lens radius; 0 = pinhole
  double focal_distance = 0;  ///< distance to the plane in focus; 0 = |center - eye|
  bool orthographic = false;  ///< parallel projection along the gaze (no foreshortening)
  /// Orthographic: the view's height in world units (its width follows the image's aspect). The loader sets it
  /// (a scene that gives none gets the perspective view's height at the center, 2 |center - eye| tan(fovy / 2)).
  double ortho_height = 2;

  /// The camera as tessera::Camera for an image of the given aspect (width / height), fovy in radians, with the
  /// near and far planes given.
  Camera camera(double aspect, double near, double far) const;
};

/// One object: a shape or a mesh, its material's name, its placement and motion.
struct SceneObject {
  std::optional<Shape> shape;           ///< set for shapes
  std::shared_ptr<const TriMesh> mesh;  ///< set for meshes (loaded or generated at load time)
  std::string material;
  Mat4 transform{1.0};  ///< object to world
  Motion motion;        ///< velocity and/or the end transform
  bool casts_shadows = true;
};

/// A whole scene.
struct Scene {
  std::string name;  ///< file name or built-in name (for messages)
  SceneImage image;
  SceneCamera camera;
  Vec3f ambient{0.1f};
  std::vector<Light> lights;
  std::map<std::string, Material> materials;
  /// GLSL programs of materials that name one ("shader": {"vertex", "fragment", "uniforms", "textures"}), by material
  /// name: the rasterizer draws those materials' objects through them (their built-ins bound from the material and
  /// the lights); the ray tracer shades the material's own terms.
  std::map<std::string, std::shared_ptr<raster3d::ContextProgram>> shaders;
  std::vector<SceneObject> objects;
};

/// Parses scene JSON. `name` prefixes error messages; mesh and texture paths are relative to `base_dir`. Throws
/// InvalidInput "name: objects[3].radius: expected a positive number" (the JSON path of the bad value), or
/// "name: byte N: ..." for malformed JSON; IoError for a mesh or texture file that cannot be read. A scene with keyed
/// values (AnimatedScene) gives its first frame.
Scene parse_scene(std::string_view json, const std::string& name, const std::filesystem::path& base_dir);

/// A scene's time line ("animation" in docs/scene-format.md).
struct SceneAnimation {
  int first = 0, last = 0;  ///< the frames it spans, both included (a scene without "animation" has frame 0 only)
  double fps = 24;          ///< frames per second (for movies made of the frames)
  /// The fraction of a frame the shutter is open: an object whose placement is keyed moves over [frame, frame +
  /// shutter] (motion blur, with more than one sample per pixel). 0.5 (a 180-degree shutter) by default, 0 for none.
  double shutter = 0.5;
};

/// Scene JSON in which any number or array of numbers may be keyed, {"keys": [[frame, value], ...],
/// "interpolation": "linear" | "smooth" | "step"}: camera, placements, materials, lights. at(frame) makes the Scene
/// of one frame, so every frame (and every tile of one) is made independently, as a render farm's tasks need.
class AnimatedScene {
 public:
  /// Parses the JSON and checks its "animation" and every keyed value (throws as parse_scene); frames are made by
  /// at(), which loads meshes and textures.
  AnimatedScene(std::string_view json, std::string name, std::filesystem::path base_dir);
  AnimatedScene(AnimatedScene&&) noexcept;
  AnimatedScene& operator=(AnimatedScene&&) noexcept;
  ~AnimatedScene();

  /// The frame range, rate and shutter.
  const SceneAnimation& animation() const;
  /// True when some value is keyed (the frames differ).
  bool keyed() const;
  /// The scene at `frame`: each keyed value interpolated there (held before its first key and after its last); an
  /// object whose transform is keyed gets transform_end at frame + shutter. Throws InvalidInput for a frame outside
  /// [first, last], and as parse_scene for values that are invalid at that frame.
  Scene at(int frame) const;

 private:
  struct Data;
  static Scene frame_scene(const Data& data, int frame);
  std::unique_ptr<Data> data_;
};

/// The scene file (paths inside are relative to its folder), or a built-in scene when `name_or_path` names one and no
/// such file exists, with its time line. Throws as load_scene_or_builtin.
AnimatedScene load_animated_scene(const std::string& name_or_path);

/// Reads a scene file (paths inside are relative to its folder). Throws as parse_scene, IoError when unreadable.
Scene load_scene(const std::filesystem::path& path);

/// The names of the built-in scenes, sorted ("cornell", "mesh", "motion-blur", "whitted", ...).
std::vector<std::string> builtin_scene_names();
/// The JSON text of a built-in scene. Throws InvalidInput listing the names for an unknown one.
std::string_view builtin_scene_text(const std::string& name);
/// A built-in scene, parsed.
Scene builtin_scene(const std::string& name);

/// A built-in scene when `name_or_path` names one and no such file exists, else the file.
Scene load_scene_or_builtin(const std::string& name_or_path);

}  // namespace tessera
