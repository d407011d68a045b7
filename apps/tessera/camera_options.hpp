#pragma once
// The camera options shared by every 3D command (DESIGN.md section 4, docs/raster3d.md "The camera options").
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "tessera/core/parse.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/scene/framing.hpp"

namespace tessera::cli {

/// The framed views and model axes are the library's (tessera/scene/framing.hpp), named for the options.
using View = FramedView;
using tessera::FrontAxis;
using tessera::UpAxis;

/// The camera options shared by every 3D command (DESIGN.md section 4): `--eye x,y,z --center x,y,z --up x,y,z
/// --fovy DEG --near N --far F --size WxH`, the framed views `--view NAME --azimuth DEG --elevation DEG --up-axis
/// x|y|z --front-axis AXIS`, and `--ortho [--ortho-size H]`; framed by the library's frame_camera (framing.hpp).
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
  /// The camera framing the box [lo, hi] (frame_camera) with the options given; the aspect is the image's.
  Camera camera(const Vec3& lo, const Vec3& hi) const;
};

/// Adds `--samples N` (anti-aliasing: N samples per pixel, 1 to 1024) to a command.
void add_samples_option(CLI::App& command, int& samples);

/// The vector x,y,z an option gives (`what` names it in the error). Throws InvalidInput unless three numbers.
Vec3 parse_vec3(const std::string& text, const char* what);

}  // namespace tessera::cli
