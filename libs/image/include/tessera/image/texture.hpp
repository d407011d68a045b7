#pragma once
// Textures for texture and environment mapping (the notes, "Texture Mapping"): Texture2D with wrap modes and
// nearest / bilinear / trilinear (MIPmap) filtering, EnvironmentMap for lat-long images and CubeMap for six faces.
//
// Texture coordinates follow OpenGL: (u, v) = (0, 0) is the bottom-left corner of the image and (1, 1) its top-right
// corner, so v grows upward while image rows grow downward (row 0 is the top). Texel (i, j), counted from the
// bottom-left, covers [i, i+1)/width x [j, j+1)/height in (u, v) and its center is ((i + 0.5)/width,
// (j + 0.5)/height); it is image pixel (i, height - 1 - j). Values are filtered as stored (no gamma).
#include <array>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "tessera/image/image.hpp"

namespace tessera {

/// What a coordinate outside [0, 1] reads (OpenGL's GL_REPEAT, GL_CLAMP_TO_EDGE, GL_MIRRORED_REPEAT).
enum class Wrap { repeat, clamp, mirror };

/// How a sample is reconstructed from texels.
enum class Filter {
  nearest,    ///< the texel containing (u, v) on level 0 (GL_NEAREST)
  bilinear,   ///< the notes' weighted average of the 4 nearest texels on level 0 (GL_LINEAR)
  trilinear,  ///< bilinear on the two MIPmap levels around lod, blended linearly (GL_LINEAR_MIPMAP_LINEAR)
};

/// Sampling state of a texture, as a GL sampler object.
struct Sampler {
  Wrap wrap_u = Wrap::repeat;        ///< wrap mode along u (image x)
  Wrap wrap_v = Wrap::repeat;        ///< wrap mode along v (image y, upward)
  Filter filter = Filter::bilinear;  ///< reconstruction filter
};

/// A 2D texture: an RGBA image, its MIPmap pyramid, and a Sampler.
class Texture2D {
 public:
  /// Builds the texture and its MIPmap pyramid (see build_mipmaps). Throws InvalidInput for an empty image.
  explicit Texture2D(ImageRGBA image, const Sampler& sampler = {});

  /// Size of level 0 in texels.
  int width() const { return levels_.front().width(); }
  int height() const { return levels_.front().height(); }
  /// Number of MIPmap levels, 1 + floor(log2(max(width, height))).
  int levels() const { return int(levels_.size()); }
  /// MIPmap level `i` (0 is the full image); throws InvalidInput when i is not in [0, levels()).
  const ImageRGBA& level(int i) const;
  /// The sampling state.
  const Sampler& sampler() const { return sampler_; }
  void set_sampler(const Sampler& sampler) { sampler_ = sampler; }

  /// Samples at (u, v) with the sampler's filter at level of detail 0.
  glm::vec4 sample(glm::vec2 uv) const { return sample(uv, 0.f); }
  /// Samples at (u, v) with the sampler's filter; only trilinear uses lod (clamped to [0, levels() - 1]).
  glm::vec4 sample(glm::vec2 uv, float lod) const;
  /// Samples with the level of detail given by screen-space derivatives of (u, v) (see lod()).
  glm::vec4 sample(glm::vec2 uv, glm::vec2 duv_dx, glm::vec2 duv_dy) const { return sample(uv, lod(duv_dx, duv_dy)); }
  /// The level of detail of a pixel footprint: log2 of the longer of the two derivative vectors measured in texels,
  /// rho = max(|duv_dx * size|, |duv_dy * size|) (OpenGL 4.6, section 8.14.1). -infinity for a zero footprint.
  float lod(glm::vec2 duv_dx, glm::vec2 duv_dy) const;

  /// Level `level`'s texel containing (u, v), after wrapping (nearest filtering). Precondition: level is valid.
  glm::vec4 nearest(glm::vec2 uv, int level) const;
  /// The notes' bilinear interpolation on level `level`: with t00, t10, t01, t11 the texels around (u, v) (bottom
  /// left, bottom right, top left, top right) and a, b the offsets of (u, v) from t00's center in texels,
  /// lerp(lerp(t00, t10, a), lerp(t01, t11, a), b). Precondition: level is valid.
  glm::vec4 bilinear(glm::vec2 uv, int level) const;

 private:
  glm::vec4 texel(const ImageRGBA& image, long long i, long long j) const;

  std::vector<ImageRGBA> levels_;
  Sampler sampler_;
};

/// The MIPmap pyramid of an image (the notes: average every square of 4 pixels to make 1 pixel). Each level halves
/// each size, rounding down, to 1 at least (OpenGL's rule). An even size averages pairs; an odd size 2n+1 -> n uses
/// the three-tap box of width (2n+1)/n, weights (n - i, n, i + 1)/(2n + 1), so every level keeps the image's mean
/// exactly. Throws InvalidInput for an empty image.
std::vector<ImageRGBA> build_mipmaps(ImageRGBA image);

/// Lat-long (equirectangular) mapping of unit directions, right-handed, y up: the image center (0.5, 0.5) looks
/// down -z, u grows with the azimuth toward +x (u = 0.75 is +x, u = 0 and 1 are +z), v = 1 is +y (top row) and v = 0
/// is -y. u = 0.5 + atan2(x, -z) / 2pi, v = 0.5 + asin(y) / pi. `direction` need not be normalized but nonzero.
glm::vec2 latlong_uv(glm::vec3 direction);
/// The unit direction of lat-long coordinates (u, v), the inverse of latlong_uv.
glm::vec3 latlong_direction(glm::vec2 uv);

/// An environment map (Blinn and Newell 1976; the notes: look up the reflected direction R) stored as one lat-long
/// image: u repeats, v clamps at the poles.
class EnvironmentMap {
 public:
  /// Wraps a lat-long image (any aspect; 2:1 is usual). Throws InvalidInput for an empty image.
  explicit EnvironmentMap(ImageRGBA latlong, Filter filter = Filter::bilinear);
  /// The color seen in `direction` (nonzero, need not be normalized), at level of detail lod (trilinear only).
  glm::vec4 lookup(glm::vec3 direction, float lod = 0.f) const;
  /// The underlying texture.
  const Texture2D& texture() const { return texture_; }

 private:
  Texture2D texture_;
};

/// Cube-map faces in OpenGL order: GL_TEXTURE_CUBE_MAP_POSITIVE_X + face.
enum class CubeFace { pos_x, neg_x, pos_y, neg_y, pos_z, neg_z };

/// A face and the (s, t) coordinates on it, both in [0, 1].
struct CubeCoord {
  CubeFace face;
  glm::vec2 st;
};

/// OpenGL's cube-map selection (4.6, section 8.13, table 8.19): the major axis of `direction` picks the face and
/// s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2 with (sc, tc) = +X (-z, -y), -X (z, -y), +Y (x, z), -Y (x, -z), +Z (x, -y),
/// -Z (-x, -y). Ties go to x, then y. A zero direction gives the center of +X.
CubeCoord cube_coord(glm::vec3 direction);
/// The point on the cube [-1, 1]^3 that face coordinates name: the inverse of cube_coord up to length.
glm::vec3 cube_direction(const CubeCoord& coord);

/// A cube map of six square RGBA faces. Face images follow OpenGL's layout when a top-row-first image file is
/// uploaded as is: image pixel (x, y) of a face sits at s = (x + 0.5)/size, t = (y + 0.5)/size, so t = 0 is row 0.
/// Filtering clamps at face edges (no seamless filtering across faces).
class CubeMap {
 public:
  /// Takes the faces in CubeFace order. Throws InvalidInput unless all six are square, nonempty and equal in size.
  explicit CubeMap(std::array<ImageRGBA, 6> faces, Filter filter = Filter::bilinear);
  /// Fills each size x size face by evaluating `radiance` at the direction through every texel center (e.g. a
  /// lat-long EnvironmentMap's lookup: the notes' "render scene 6 times, eye at center of cube"). Throws
  /// InvalidInput for size < 1.
  static CubeMap from_function(int size, const std::function<glm::vec4(glm::vec3)>& radiance,
                               Filter filter = Filter::bilinear);

  /// The color seen in `direction` (nonzero, need not be normalized), at level of detail lod (trilinear only).
  glm::vec4 lookup(glm::vec3 direction, float lod = 0.f) const;
  /// Face `face`'s texture.
  const Texture2D& face(CubeFace face) const { return faces_[size_t(face)]; }
  /// Edge length of each face in texels.
  int size() const { return faces_[0].width(); }

 private:
  std::vector<Texture2D> faces_;
};

}  // namespace tessera
