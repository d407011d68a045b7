#pragma once
// The camera options shared by every 3D command (DESIGN.md section 4, docs/raster3d.md "The camera options").
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "tessera/core/parse.hpp"
#include "tessera/math/camera.hpp"

namespace tessera::cli {

/// Where the framed camera stands, as an azimuth about the model's up axis (0 = front, 90 = right) and an elevation
/// above its horizontal plane (90 = top). three_quarter is the default of raster and trace.
enum class View { three_quarter, front, back, left, right, top, bottom, iso };

/// The model's up axis (--up-axis): meshes are y-up by OpenGL's convention, CAD data and the teapot (.bpt) are z-up.
enum class UpAxis { x, y, z };

/// The direction the model's front faces (--front-axis): automatic is +z (glTF's and Blender's OBJ convention), or
/// -y for z-up models (Blender's front view).
enum class FrontAxis { automatic, pos_x, neg_x, pos_y, neg_y, pos_z, neg_z };

/// The camera options shared by every 3D command (DESIGN.md section 4): `--eye x,y,z --center x,y,z --up x,y,z
/// --fovy DEG --near N --far F --size WxH`, the framed views `--view NAME --azimuth DEG --elevation DEG --up-axis
/// x|y|z`, and `--ortho [--ortho-size H]`.
///
/// The model's frame: up U is the --up-axis, front F the --front-axis (by default +z, or -y for z-up: Blender's front
/// view), right R = U x F (+x for the defaults of y-up and z-up, -y for x-up), so that R x U = F. The framed eye lies
/// on cos(el) (cos(az) F + sin(az) R) + sin(el) U from the center; the image's up is that direction turned 90 degrees
/// up (U at elevation 0; -F on the top view: the front at the bottom of the image, as in Blender).
struct CameraOptions {
  std::string eye, center, up, size;
  double fovy = 45, near = 0, far = 0;       ///< near/far 0: chosen from the framed bounds
  View view = View::three_quarter;           ///< the default view: set before add() to change a command's default
  std::optional<double> azimuth, elevation;  ///< degrees; given, they replace the view's
  UpAxis up_axis = UpAxis::y;
  FrontAxis front_axis = FrontAxis::automatic;
  bool ortho = false;       ///< --ortho: parallel projection
  double ortho_size = 0;    ///< --ortho-size: the view's height in world units; 0 frames the bounds
  bool clip_planes = true;  ///< offer --near and --far (a rasterizer's clipping planes; ray casters have none)

  /// Adds the options to `command`; `default_size` is the --size default ("WxH"). Malformed sizes and vectors,
  /// unknown views, and --view/--azimuth/--elevation together with --eye are usage errors (exit 2).
  void add(CLI::App& command, const std::string& default_size = "512x512");
  /// The image size from --size.
  Size2 image_size() const;
  /// The view's azimuth and elevation in degrees (--azimuth and --elevation replace the view's own).
  double view_azimuth() const;
  double view_elevation() const;
  /// The camera: options that were given win; the rest frame the bounding sphere of the box [lo, hi] (radius r) from
  /// the view's direction at the distance where the sphere, grown by 10%, fills the narrower field of view; an
  /// orthographic camera's height is --ortho-size, or 2.2 r / min(1, aspect) so that the same sphere fits. The aspect
  /// is the image's.
  Camera camera(const Vec3& lo, const Vec3& hi) const;
};

/// Adds `--samples N` (anti-aliasing: N samples per pixel, 1 to 1024) to a command.
void add_samples_option(CLI::App& command, int& samples);

/// The vector x,y,z an option gives (`what` names it in the error). Throws InvalidInput unless three numbers.
Vec3 parse_vec3(const std::string& text, const char* what);

}  // namespace tessera::cli
