// Example 28: the notes' texture programs (raster3d/notes_shaders.hpp). The texture pair, gl_FragColor =
// texture2D(myTexture, textureCoord), on a checkered square seen in perspective (trilinear: texture2D's level of
// detail from the coordinates' derivatives) and on a face-on square with one circle; then the two-texture pair, which
// samples at textureCoord -+ (0.2, 0) and averages: the circle becomes two half-strength circles 0.4 apart, full
// strength where they overlap (the notes' Venn diagram); and the same with a different texture at each coordinate.
#include "gallery.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/notes_shaders.hpp"

namespace {

using namespace tessera;

constexpr int kSize = 240;

// The square [-1, 1]^2 in the z = 0 plane facing +z, uv (0, 0) at its bottom left.
raster3d::VertexArrays square() {
  raster3d::VertexArrays q;
  q.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  q.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  q.indices = {0, 1, 2, 0, 2, 3};
  return q;
}

// 8 x 8 checks, warm and cool, on a 256-texel texture.
Texture2D checks() {
  ImageRGBA image(256, 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      image(x, y) = (x / 32 + y / 32) % 2 ? Vec4f(0.95f, 0.85f, 0.55f, 1) : Vec4f(0.2f, 0.35f, 0.65f, 1);
  return Texture2D(image, Sampler{.filter = Filter::trilinear});
}

// The square face-on, filling the picture.
const Mat4 kFaceOn = ortho(-1, 1, -1, 1, -1, 1);

template <class Draw>
ImageRGB picture(Draw draw) {
  raster3d::Framebuffer fb(kSize, kSize);
  fb.clear({1, 1, 1});
  draw(fb);
  return fb.color_rgb();
}

}  // namespace

TESSERA_EXAMPLE(ex28_notes_texture_shaders, "28_notes_texture_shaders",
                "The notes' texture shader and two-texture shader (the Venn diagram)") {
  const raster3d::VertexArrays quad = square();
  const Texture2D board = checks();
  const Mat4 tilted = perspective(radians(45), 1, 0.1, 20) * look_at({0, 1.1, 2.2}, {0, -0.2, 0}, {0, 1, 0}) *
                      rotate_x(radians(-70)) * scale(1.6, 1.6, 1);
  const Texture2D disc = raster3d::disc_texture(256, 0.25, {0.95f, 0.45f, 0.1f, 1}, Vec4f(1));
  gallery.add(
      "28_texture_shader.png",
      examples::side_by_side({picture([&](auto& fb) { raster3d::draw_textured(fb, {}, quad, tilted, board); }),
                              picture([&](auto& fb) { raster3d::draw_textured(fb, {}, quad, kFaceOn, disc); })}),
      "The notes' texture shader, gl_FragColor = texture2D(myTexture, textureCoord): a checkered square in "
      "perspective (trilinear MIPmapping: the far checks blur to their mean instead of aliasing), and the "
      "one-circle texture drawn face-on.");

  const Texture2D red = raster3d::disc_texture(256, 0.25, {0.9f, 0.1f, 0.1f, 1}, Vec4f(1));
  const Texture2D blue = raster3d::disc_texture(256, 0.25, {0.1f, 0.2f, 0.9f, 1}, Vec4f(1));
  gallery.add("28_two_texture_shader.png",
              examples::side_by_side(
                  {picture([&](auto& fb) { raster3d::draw_two_textured(fb, {}, quad, kFaceOn, disc); }),
                   picture([&](auto& fb) { raster3d::draw_two_textured(fb, {}, quad, kFaceOn, red, &blue); })}),
              "The notes' two-texture shader: leftCoord = textureCoord - (0.2, 0), rightCoord = textureCoord + (0.2, "
              "0), gl_FragColor = 0.5 (texture2D(leftCoord) + texture2D(rightCoord)). Left, the notes' one orange "
              "circle: two pale half-strength copies 0.4 apart, full orange where they overlap (the Venn diagram). "
              "Right, a red circle read at leftCoord (so it appears shifted right) and a blue one at rightCoord "
              "(shifted left): purple in the overlap.");
}
