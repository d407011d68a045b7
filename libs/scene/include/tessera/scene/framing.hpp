#pragma once
// Framing a model: the camera that shows a bounding box from a named view (front, top, three-quarter, ...) or an
// azimuth and elevation about the model's up axis, as every 3D command of the CLI and the Python package frame it
// (docs/raster3d.md "The camera options").
//
// The model's frame: up U is the up axis, front F the front axis (by default +z, or -y for z-up models: Blender's front
// view), right R = U x F (+x for the defaults of y-up and z-up, -y for x-up), so that R x U = F. The framed eye lies
// on cos(el) (cos(az) F + sin(az) R) + sin(el) U from the center; the image's up is that direction turned 90 degrees
// up (U at elevation 0; -F on the top view: the front at the bottom of the image, as in Blender).
#include <array>
#include <optional>
#include <string_view>
#include <utility>

#include "tessera/math/camera.hpp"

namespace tessera {

/// The named views. three_quarter (30 degrees right of the front, 20 above) is the default of raster and trace; iso
/// looks down the cube's diagonal.
enum class FramedView { three_quarter, front, back, left, right, top, bottom, iso };

/// The model's up axis: meshes are y-up by OpenGL's convention, CAD data and the teapot (.bpt) are z-up.
enum class UpAxis { x, y, z };

/// The direction the model's front faces: automatic is +z (glTF's and Blender's OBJ convention), or -y for z-up models.
enum class FrontAxis { automatic, pos_x, neg_x, pos_y, neg_y, pos_z, neg_z };

/// The names the command line (--view, --up-axis, --front-axis) and the Python package give the views and axes.
inline constexpr std::array<std::pair<std::string_view, FramedView>, 8> kFramedViewNames = {{
    {"three-quarter", FramedView::three_quarter},
    {"front", FramedView::front},
    {"back", FramedView::back},
    {"left", FramedView::left},
    {"right", FramedView::right},
    {"top", FramedView::top},
    {"bottom", FramedView::bottom},
    {"iso", FramedView::iso},
}};
inline constexpr std::array<std::pair<std::string_view, UpAxis>, 3> kUpAxisNames = {{
    {"x", UpAxis::x},
    {"y", UpAxis::y},
    {"z", UpAxis::z},
}};
inline constexpr std::array<std::pair<std::string_view, FrontAxis>, 7> kFrontAxisNames = {{
    {"auto", FrontAxis::automatic},
    {"+x", FrontAxis::pos_x},
    {"-x", FrontAxis::neg_x},
    {"+y", FrontAxis::pos_y},
    {"-y", FrontAxis::neg_y},
    {"+z", FrontAxis::pos_z},
    {"-z", FrontAxis::neg_z},
}};

/// A view's azimuth about the up axis (0 = front, 90 = right) and elevation above the horizontal plane (90 = top),
/// degrees.
struct ViewAngles {
  double azimuth, elevation;
};

/// The named view's angles.
ViewAngles view_angles(FramedView view);

/// How to frame a box. What is given wins; the rest is chosen from the box.
struct Framing {
  ViewAngles angles = view_angles(FramedView::three_quarter);
  UpAxis up_axis = UpAxis::y;
  FrontAxis front_axis = FrontAxis::automatic;
  double fovy = 45;                     ///< vertical field of view, degrees, in (0, 180)
  bool ortho = false;                   ///< parallel projection
  double ortho_size = 0;                ///< the orthographic view's height in world units; 0 frames the box
  std::optional<Vec3> eye, center, up;  ///< given, they replace the framed ones (center: the box's middle)
  double near = 0, far = 0;             ///< clipping distances; 0 = chosen from the box
};

/// The camera of `framing` for the box [lo, hi] and an image of the given aspect (width / height): the box's bounding
/// sphere (radius r, a unit sphere for a single point), grown by 10%, fills the narrower field of view from the view's
/// direction; an orthographic camera's height is ortho_size, or 2.2 r / min(1, aspect) so that the same sphere fits;
/// near and far enclose the sphere. Throws InvalidInput for a field of view outside (0, 180), a front axis along the up
/// axis, or near >= far.
Camera frame_camera(const Framing& framing, const Vec3& lo, const Vec3& hi, double aspect);

}  // namespace tessera
