#pragma once
// Shadow mapping, the notes' "2-pass z-buffer" (Williams 1978): pass 1 renders the scene's depth as seen from the
// light; pass 2, the camera's, takes each visible point P to the light's window space, P' = L V^-1 P, and compares
// its depth z' with the depth the light saw there. The notes write "z' < z_light(x', y') -> shadow"; the test is the
// other way round: P is in shadow when something lies nearer to the light, z' > z_light(x', y').
//
// The comparison needs a bias, or a lit surface shadows itself ("shadow acne": the map stores the depth at texel
// centers, P lies anywhere in its texel). Here the bias follows the receiver: the depth of P's tangent plane is
// predicted at each texel center it is compared with (receiver-plane depth bias, Isidoro 2006), with an allowance
// of one texel's depth change along that plane (as glPolygonOffset(1, 1) gives the caster) for a mesh's facets
// turning within the filter's reach, and a small constant for the map's 24-bit rounding. With pcf > 0 the comparison is
// made at the (2 pcf + 1)^2 texels around P' and the visibility is the fraction that pass (percentage-closer filtering,
// Reeves, Salesin and Cook 1987): soft, antialiased shadow edges.
#include <cstdint>
#include <vector>

#include "tessera/math/types.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/framebuffer.hpp"

namespace tessera::raster3d {

/// A light's depth map and the test of pass 2: one view (a directional light's, or a spot's), or six around a point
/// light (an omnidirectional map: the faces of a cube centered on the light, as for an environment cube map).
class ShadowMap {
 public:
  /// An empty map (everything lit) of size x size texels, seen through `light_view_projection` (world space to the
  /// light's clip space; see directional() and spot()). Throws InvalidInput unless 1 <= size <= kMaxSize.
  ShadowMap(int size, const Mat4& light_view_projection);
  /// The largest size a map may have (texels along a side).
  static constexpr int kMaxSize = 16384;

  /// The view-projection of a directional light shining along -to_light: orthographic, its box holding the sphere
  /// around [lo, hi]. Throws InvalidInput for a zero direction or an empty box.
  static Mat4 directional(const Vec3& to_light, const Vec3& lo, const Vec3& hi);
  /// The view-projection of a point light at `position` aimed at the center of [lo, hi]: a perspective whose cone
  /// holds the sphere around the box. Throws InvalidInput when the light lies inside that sphere (one map cannot see
  /// all around it) or the box is empty.
  static Mat4 spot(const Vec3& position, const Vec3& lo, const Vec3& hi);
  /// An empty map for a point light at `position` and casters in [lo, hi], wherever the light is: one spot view
  /// (size x size) when the light lies outside the casters' bounding sphere, else six faces of size/2 x size/2
  /// around it (an omnidirectional map, 1.5 times the texels of one view). Each face sees a little more than its 90
  /// degrees, so that a filter of up to 7 x 7 texels (pcf 3) stays in the face a point falls in. Casters nearer to
  /// the light than 1% of the sphere's radius are missed (the faces' near plane). Throws InvalidInput for a bad size
  /// or an empty box.
  static ShadowMap point(int size, const Vec3& position, const Vec3& lo, const Vec3& hi);

  /// Pass 1: renders the depth of the triangles of `arrays` (positions after `model`, object to world) into every
  /// face.
  void draw(const VertexArrays& arrays, const Mat4& model = Mat4(1.0));
  /// Clears the map (everything lit again).
  void clear();

  /// Pass 2: the fraction of the light that reaches world point p on a surface with unit world normal n, 1 lit,
  /// 0 in shadow; pcf is the filter radius in texels (0: one texel, a hard edge). Points outside the light's view
  /// or nearer than its near plane are lit, points beyond its far plane in shadow wherever the map holds something
  /// (so a map need only be fitted to the shadow casters); a surface seen edge-on by the light is in its own
  /// (attached) shadow. An omnidirectional map looks p up in the face toward it (the largest coordinate of p minus
  /// the light). Throws InvalidInput for a negative pcf.
  float visibility(const Vec3f& p, const Vec3f& n, int pcf = 1) const;

  /// Texels along each side of a face.
  int size() const { return faces_[0].depth.width(); }
  /// 1, or 6 for an omnidirectional map (faces +x, -x, +y, -y, +z, -z of the cube around the light).
  int face_count() const { return int(faces_.size()); }
  /// World to the light's clip space (of a face).
  const Mat4f& light_view_projection(int face = 0) const { return faces_.at(size_t(face)).light; }
  /// The stored depths of a face, window z in [0, 1] (1 where nothing was drawn), row 0 at the top.
  DepthImage depth_image(int face = 0) const { return faces_.at(size_t(face)).depth.depth_image(); }

 private:
  struct Face {
    Framebuffer depth;  // depth_only
    Mat4f light;
  };
  ShadowMap() = default;
  /// The visibility of p through one face.
  static float visibility(const Face& face, const Vec3f& p, const Vec3f& n, int pcf);

  std::vector<Face> faces_;
  Vec3f center_{0};  // an omnidirectional map's light
};

}  // namespace tessera::raster3d
