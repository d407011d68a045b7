#pragma once
// The camera options shared by every 3D command (DESIGN.md section 4).
#include <string>

#include <CLI/CLI.hpp>

#include "tessera/core/parse.hpp"
#include "tessera/math/camera.hpp"

namespace tessera::cli {

/// The camera options shared by every 3D command (DESIGN.md section 4):
/// `--eye x,y,z --center x,y,z --up x,y,z --fovy DEG --near N --far F --size WxH`.
struct CameraOptions {
  std::string eye, center, up, size;
  double fovy = 45, near = 0, far = 0;  ///< near/far 0: chosen from the framed bounds

  /// Adds the options to `command`; `default_size` is the --size default ("WxH").
  void add(CLI::App& command, const std::string& default_size = "512x512");
  /// The image size from --size.
  Size2 image_size() const;
  /// The camera: options that were given win; the rest frame the bounding sphere of the box [lo, hi] from the +z side
  /// (eye on `view_dir` from the center, so that the sphere fills the view). The aspect is the image's.
  Camera camera(const Vec3& lo, const Vec3& hi, const Vec3& view_dir = {0, 0, 1}) const;
};

}  // namespace tessera::cli
