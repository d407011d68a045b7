#pragma once
// A camera: the notes' camera(eye, center, up), a perspective (pinhole) or orthographic projection, and eye rays.
#include "tessera/math/ray.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// Where a camera stands and what it sees. Defaults match DESIGN.md: right-handed, y up, looking down -z.
struct Camera {
  Vec3 eye{0, 0, 5};
  Vec3 center{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fovy = radians(45);  ///< vertical field of view, radians
  double aspect = 1;          ///< width / height of the image
  double near = 0.1;          ///< distance to the near plane (> 0)
  double far = 100;           ///< distance to the far plane (> near)
  bool orthographic = false;  ///< parallel projection: lines of sight all along the gaze, no foreshortening
  double ortho_height = 2;    ///< orthographic: the view's height in world units (its width is aspect times it)

  /// The view matrix look_at(eye, center, up). Throws InvalidInput for a degenerate camera.
  Mat4 view() const;
  /// perspective(fovy, aspect, near, far), or for an orthographic camera ortho(-w/2, w/2, -h/2, h/2, near, far) with
  /// h = ortho_height and w = aspect h. Throws InvalidInput for a degenerate projection.
  Mat4 projection() const;
  /// The orthonormal camera frame u (right), v (up), w (backward, opposite the gaze), as rows of view().
  void frame(Vec3& u, Vec3& v, Vec3& w) const;
};

/// Generates the notes' eye rays for a width x height image: for pixel (i, j) (row 0 at the top) and a sample offset
/// (dx, dy) in [0,1)^2 (0.5, 0.5 is the pixel center), u = (2(i+dx)/W - 1) * aspect, v = 1 - 2(j+dy)/H, and the ray
/// leaves the eye along -d w + u u + v v with focal length d = 1/tan(fovy/2) (so the view plane spans v in [-1, 1]).
/// For an orthographic camera every ray runs along the gaze -w, from eye + (h/2)(u u + v v) with h = ortho_height.
class EyeRays {
 public:
  EyeRays(const Camera& camera, int width, int height);
  /// The normalized-direction eye ray through image position (i + dx, j + dy).
  Ray ray(double i, double j, double dx = 0.5, double dy = 0.5) const;
  /// The focal length d = 1 / tan(fovy / 2).
  double focal_length() const { return d_; }

 private:
  Vec3 eye_, u_, v_, w_;
  double d_, aspect_;
  double ortho_half_ = 0;  ///< orthographic: half the view's height; 0 for perspective
  int width_, height_;
};

}  // namespace tessera
