#pragma once
// Textures for texture and environment mapping (the notes, "Texture Mapping"): Texture2D with wrap modes and
// nearest / bilinear / trilinear (MIPmap) filtering, EnvironmentMap for lat-long images and CubeMap for six faces.
//
// Texture coordinates follow OpenGL: (u, v) = (0, 0) is the bottom-left corner of the image and (1, 1) its top-right
// corner, so v grows upward while image rows grow downward (row 0 is the top). Texel (i, j), counted from the
// bottom-left, covers [i, i+1)/width x [j, j+1)/height in (u, v) and its center is ((i + 0.5)/width,
// (j + 0.5)/height); it is image pixel (i, height - 1 - j). Values are filtered as stored (no gamma).
//
// A texture keeps the precision of its image, as an OpenGL texture keeps its internal format: from ImageRGBA8 (an
// 8-bit file, load_texture) every level is 8-bit RGBA (GL_RGBA8, 4 bytes per texel), from ImageRGBA float RGBA
// (GL_RGBA32F, 16 bytes). Sampling returns float either way: an 8-bit texel reads v/255, the value read_image gives,
// so nearest and bilinear samples of level 0 are the float texture's bit for bit.
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

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

/// How a texture stores its texels (OpenGL's internal formats of the same names).
enum class TexelFormat {
  rgba8,    ///< 8-bit RGBA, 4 bytes per texel; a texel reads v/255
  rgba32f,  ///< float RGBA, 16 bytes per texel
};

/// A 2D texture: an RGBA image, its MIPmap pyramid, and a Sampler.
class Texture2D {
 public:
  /// Builds a float texture and its MIPmap pyramid (see build_mipmaps). Throws InvalidInput for an empty image.
  explicit Texture2D(ImageRGBA image, const Sampler& sampler = {});
  /// Builds an 8-bit texture (TexelFormat::rgba8) and its 8-bit MIPmap pyramid, as OpenGL keeps a GL_RGBA8
  /// texture's generated levels 8-bit (see build_mipmaps). Throws InvalidInput for an empty image.
  explicit Texture2D(ImageRGBA8 image, const Sampler& sampler = {});

  /// Size of level 0 in texels.
  int width() const { return width_; }
  int height() const { return height_; }
  /// Number of MIPmap levels, 1 + floor(log2(max(width, height))).
  int levels() const { return int(rgba8_ ? levels8_.size() : levels_.size()); }
  /// How the texels are stored, and the bytes of one texel (4 for rgba8, 16 for rgba32f).
  TexelFormat format() const { return rgba8_ ? TexelFormat::rgba8 : TexelFormat::rgba32f; }
  size_t bytes_per_texel() const { return rgba8_ ? sizeof(ImageRGBA8::Pixel) : sizeof(ImageRGBA::Pixel); }
  /// The bytes that all levels' texels hold.
  size_t bytes() const;
  /// MIPmap level `i` (0 is the full image) as float RGBA: a copy, 8-bit texels as v/255. Throws InvalidInput when
  /// i is not in [0, levels()).
  ImageRGBA level(int i) const;
  /// MIPmap level `i` of an rgba8 texture as stored. Throws InvalidInput for a float texture or a bad i.
  const ImageRGBA8& level_rgba8(int i) const;
  /// The sampling state.
  const Sampler& sampler() const { return sampler_; }
  void set_sampler(const Sampler& sampler) { sampler_ = sampler; }

  /// Samples at (u, v) with the sampler's filter at level of detail 0.
  glm::vec4 sample(glm::vec2 uv) const { return sample(uv, 0.f); }
  /// Samples at (u, v) with the sampler's filter; only trilinear uses lod (clamped to [0, levels() - 1]).
  glm::vec4 sample(glm::vec2 uv, float lod) const;
  /// sample(uv, lod) of `count` points at once (a SIMD fragment stage's lanes): (u[k], v[k]) at level of detail
  /// lod[k] (read by trilinear filtering only) into out[0][k] to out[3][k] (RGBA). An 8-bit texture filtered
  /// bilinearly or trilinearly with repeat or clamp wrapping is sampled eight points at a time with AVX2 gathers
  /// where the CPU has them (src/texture_avx2.cpp): its coordinates are then float rather than double, which moves a
  /// sample by at most a rounding of its weights (within 1/255 of sample()'s). Every other texture: sample() per point.
  void sample_lanes(const float* u, const float* v, const float* lod, float* const out[4], int count) const;
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
  void check_level(int i) const;

  int width_ = 0, height_ = 0;
  bool rgba8_ = false;
  std::vector<ImageRGBA> levels_;    // rgba32f
  std::vector<ImageRGBA8> levels8_;  // rgba8
  Sampler sampler_;
};

/// The MIPmap pyramid of an image (the notes: average every square of 4 pixels to make 1 pixel). Each level halves
/// each size, rounding down, to 1 at least (OpenGL's rule). An even size averages pairs; an odd size 2n+1 -> n uses
/// the three-tap box of width (2n+1)/n, weights (n - i, n, i + 1)/(2n + 1), so every level keeps the image's mean
/// exactly. Throws InvalidInput for an empty image.
std::vector<ImageRGBA> build_mipmaps(ImageRGBA image);
/// The 8-bit pyramid: each level is the same filter evaluated in float on the 8-bit level above, rounded to the
/// nearest 8-bit value (halves up), as OpenGL builds a GL_RGBA8 texture's levels from the level above as stored.
/// A level is within 0.5/255 of the exact filter of the level above; level k within k x 0.5/255 of the float
/// pyramid of the same image (docs/image.md).
std::vector<ImageRGBA8> build_mipmaps(ImageRGBA8 image);

/// Reads an image file as a texture without a float copy of an 8-bit file (read_image_native): 8-bit PNG, JPG, BMP,
/// TGA and PPM/PGM with maxval 255 give an rgba8 texture (4 bytes per texel and a third more for the MIPmaps,
/// instead of 16 and a third), 16-bit, HDR and PFM files a float one. Level 0 reads exactly read_image's values.
/// Throws as read_image (the memory budget included).
Texture2D load_texture(const std::filesystem::path& path, const Sampler& sampler = {});

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
  /// Wraps a lat-long image (any aspect; 2:1 is usual), float or 8-bit (see Texture2D). Throws InvalidInput for an
  /// empty image.
  explicit EnvironmentMap(ImageRGBA latlong, Filter filter = Filter::bilinear);
  explicit EnvironmentMap(ImageRGBA8 latlong, Filter filter = Filter::bilinear);
  /// The color seen in `direction` (nonzero, need not be normalized), at level of detail lod (trilinear only).
  glm::vec4 lookup(glm::vec3 direction, float lod = 0.f) const;
  /// The underlying texture.
  const Texture2D& texture() const { return texture_; }

 private:
  Texture2D texture_;
};

/// Reads a lat-long image file as an environment map, 8-bit files staying 8-bit (as load_texture).
EnvironmentMap load_environment_map(const std::filesystem::path& path, Filter filter = Filter::bilinear);

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
