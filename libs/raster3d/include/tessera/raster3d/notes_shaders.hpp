#pragma once
// The notes' texture programs ("GPUs and GLSL": "Fragment Program – Texture" and "Vertex/Fragment Program – Two
// Textures") as C++ shaders for the pipeline (shaders.hpp explains the contract).
//
// The texture pair: the vertex program passes the texture coordinates through (textureCoord = gl_MultiTexCoord0), the
// fragment program is gl_FragColor = texture2D(myTexture, textureCoord).
//
// The two-texture pair: the vertex program makes two coordinates from one, leftCoord = textureCoord + (-0.2, 0) and
// rightCoord = textureCoord + (0.2, 0) ("on [0, 1] scale"); the fragment program samples the texture at both and
// averages them, gl_FragColor = 0.5 * (texture2D(myTexture, leftCoord) + texture2D(myTexture, rightCoord)). On a
// texture of one circle this draws two overlapping circles at half strength, full strength where they overlap: the
// notes' Venn diagram. The notes' listing is sketchy (one line samples both coordinates); this is its evident meaning.
// The fragment shader may sample a second texture at rightCoord (the title's "two textures"); by default both
// coordinates read the same one, as in the notes' code.
//
// texture2D in GLSL picks the MIPmap level from the coordinates' screen-space derivatives; these fragment shaders do
// the same (Texture2D::sample with the derivatives; only trilinear filtering reads them). Colors are RGBA: the
// texture's alpha is the fragment's alpha (blending reads it).
#include <cstdint>

#include "tessera/image/texture.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/pipeline.hpp"
#include "tessera/raster3d/shaders.hpp"

namespace tessera::raster3d {

/// The texture pair's varyings: the texture coordinates (the notes' textureCoord).
struct TexCoordVaryings {
  Vec2f uv;
};

/// The notes' texture vertex program: gl_Position = MVP * gl_Vertex, textureCoord = gl_MultiTexCoord0.
struct TextureVertexShader {
  VertexAttributes attributes;  ///< positions and uvs (uvs required)
  Mat4f model_view_projection{1.0f};

  VertexOut<TexCoordVaryings> operator()(uint32_t i) const {
    return {model_view_projection * Vec4f(attributes.positions[i], 1.0f), {attributes.uvs[i]}};
  }
};

/// The notes' texture fragment program: gl_FragColor = texture2D(myTexture, textureCoord).
struct TextureFragmentShader {
  const Texture2D* texture = nullptr;  ///< myTexture; required

  bool operator()(const TexCoordVaryings& in, const TexCoordVaryings& ddx, const TexCoordVaryings& ddy,
                  Vec4f& color) const {
    color = texture->sample(in.uv, ddx.uv, ddy.uv);
    return true;
  }
};

/// The two-texture pair's varyings: the notes' leftCoord and rightCoord.
struct TwoTexCoordVaryings {
  Vec2f left;
  Vec2f right;
};

/// The notes' two-texture vertex program: gl_Position = MVP * gl_Vertex, leftCoord = textureCoord - offset,
/// rightCoord = textureCoord + offset, with the notes' offset (0.2, 0).
struct TwoTextureVertexShader {
  VertexAttributes attributes;  ///< positions and uvs (uvs required)
  Mat4f model_view_projection{1.0f};
  Vec2f offset{0.2f, 0.0f};

  VertexOut<TwoTexCoordVaryings> operator()(uint32_t i) const {
    const Vec2f uv = attributes.uvs[i];
    return {model_view_projection * Vec4f(attributes.positions[i], 1.0f), {uv - offset, uv + offset}};
  }
};

/// The notes' two-texture fragment program: gl_FragColor = 0.5 * (texture2D(left, leftCoord) + texture2D(right,
/// rightCoord)); `right` null reads `left` at both (the notes' single myTexture).
struct TwoTextureFragmentShader {
  const Texture2D* left = nullptr;   ///< required
  const Texture2D* right = nullptr;  ///< or null: `left`

  bool operator()(const TwoTexCoordVaryings& in, const TwoTexCoordVaryings& ddx, const TwoTexCoordVaryings& ddy,
                  Vec4f& color) const {
    const Texture2D& second = right ? *right : *left;
    color = 0.5f * (left->sample(in.left, ddx.left, ddy.left) + second.sample(in.right, ddx.right, ddy.right));
    return true;
  }
};

/// Draws the triangles of `arrays` (uvs required) through the texture pair with `model_view_projection`. Throws
/// InvalidInput when `arrays` has no uvs (or as draw_triangles).
DrawStats draw_textured(Framebuffer& framebuffer, const RasterState& state, const VertexArrays& arrays,
                        const Mat4& model_view_projection, const Texture2D& texture);

/// Draws the triangles of `arrays` (uvs required) through the two-texture pair: coordinates shifted by -offset
/// (sampling `left`) and +offset (sampling `right`, or `left` when null), averaged. Throws as draw_textured.
DrawStats draw_two_textured(Framebuffer& framebuffer, const RasterState& state, const VertexArrays& arrays,
                            const Mat4& model_view_projection, const Texture2D& left, const Texture2D* right = nullptr,
                            Vec2f offset = {0.2f, 0.0f});

/// A size x size texture of one disc, the notes' Venn picture's circle: `disc` inside the circle of radius
/// `radius` (in texture coordinates, centered at (0.5, 0.5)), `background` outside, one sample per texel center
/// (no antialiasing, so that sampled values are exactly one or the other). Clamped at the edges (Wrap::clamp), so
/// that shifted coordinates read the background beyond them. Throws InvalidInput when size < 1.
Texture2D disc_texture(int size, double radius, const Vec4f& disc, const Vec4f& background,
                       Filter filter = Filter::bilinear);

}  // namespace tessera::raster3d
