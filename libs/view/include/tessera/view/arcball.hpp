#pragma once
// The viewer's camera control: Shoemake's arcball for orbiting (K. Shoemake, "ARCBALL: A User Interface for Specifying
// Three-Dimensional Orientation Using a Mouse", Graphics Interface 1992), panning in the view plane and zooming by
// distance, around a bounding sphere framed by a home camera.
#include <glm/gtc/quaternion.hpp>

#include "tessera/math/camera.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// A rotation as a unit quaternion (double precision, as the cameras).
using Quat = glm::dquat;

/// The point of the arcball's virtual unit sphere under window position (x, y) of a width x height window (pixels, row
/// 0 at the top): the ball fills the circle of radius min(width, height) / 2 about the window's center; a position
/// inside it maps to (px, py, sqrt(1 - px^2 - py^2)) with px right and py up in ball radii, one outside to the nearest
/// point of the rim (z = 0). x is right, y up, z toward the viewer (eye coordinates).
Vec3 arcball_point(double x, double y, int width, int height);

/// Shoemake's quaternion of a drag from `from` to `to` (unit vectors on the ball): q = [from . to, from x to], the
/// rotation about from x to by twice the angle between them (a drag across the ball's whole diameter is a full turn).
/// The result depends only on the two points, so dragging back to the start restores the orientation.
Quat arcball_rotation(const Vec3& from, const Vec3& to);

/// Orbit, pan and zoom around a sphere (center, radius) seen by a home camera: the orientation is the rotation applied
/// to the scene in eye coordinates (what the arcball's drags build), the pan moves the scene in the view plane and the
/// zoom scales the distance from the eye to the center.
class OrbitControl {
 public:
  OrbitControl() = default;
  /// Control around the sphere (center, radius) starting from `home` (its fovy, projection and aspect are kept).
  /// Throws InvalidInput for a radius that is not positive and finite or a degenerate home camera.
  OrbitControl(const Camera& home, const Vec3& center, double radius);

  /// The camera of the current orientation, pan and zoom for an image of aspect width / height: the home camera
  /// turned about the center by the inverse of the scene's rotation, moved by the pan, at the zoomed distance, its
  /// near and far planes 1.5 radii either side of the center (near at least 1/1000 of the distance).
  Camera camera(double aspect) const;

  /// Starts an arcball drag at window position (x, y).
  void begin_rotate(double x, double y, int width, int height);
  /// Continues the drag: the orientation becomes arcball_rotation(start, now) times the orientation at the start.
  void rotate_to(double x, double y, int width, int height);
  /// Starts a pan at window position (x, y).
  void begin_pan(double x, double y);
  /// Continues the pan: the point under the start position at the center's depth follows the pointer.
  void pan_to(double x, double y, int height);
  /// Zooms by `steps` wheel steps: the distance is multiplied by 1.1^steps (positive: farther), clamped to
  /// [radius / 100, 100 radii from the home distance].
  void zoom(double steps);
  /// The rotation in eye coordinates by `angle` (radians) about the home camera's up vector: a turntable's turn
  /// about the world's vertical (counterclockwise seen from above for a positive angle).
  Quat turn_about_up(double angle) const;
  /// Back to the home camera (no rotation, pan or zoom).
  void reset();

  /// The scene's rotation in eye coordinates.
  const Quat& orientation() const { return orientation_; }
  /// Replaces the scene's rotation (the turntable's frames).
  void set_orientation(const Quat& q) { orientation_ = glm::normalize(q); }
  /// The pan: the scene's offset in the view plane, world units along the home camera's right and up.
  const Vec2& pan() const { return pan_; }
  /// The eye's distance from the (panned) center.
  double distance() const { return distance_; }
  /// The framed sphere.
  const Vec3& center() const { return center_; }
  double radius() const { return radius_; }

 private:
  Camera home_;
  Vec3 center_{0.0};
  double radius_ = 1, home_distance_ = 1, distance_ = 1;
  Quat orientation_{1, 0, 0, 0}, drag_start_orientation_{1, 0, 0, 0};
  Vec3 drag_start_{0, 0, 1};
  Vec2 pan_{0.0}, pan_start_{0.0}, pan_pointer_{0.0};
};

}  // namespace tessera
