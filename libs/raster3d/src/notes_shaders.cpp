#include "tessera/raster3d/notes_shaders.hpp"

#include <fmt/format.h>

#include "tessera/core/error.hpp"

namespace tessera::raster3d {
namespace {

void require_uvs(const VertexArrays& arrays) {
  if (arrays.uvs.size() != arrays.positions.size())
    throw InvalidInput(fmt::format("the notes' texture shaders need texture coordinates: {} uvs for {} vertices",
                                   arrays.uvs.size(), arrays.positions.size()));
}

}  // namespace

DrawStats draw_textured(Framebuffer& framebuffer, const RasterState& state, const VertexArrays& arrays,
                        const Mat4& model_view_projection, const Texture2D& texture) {
  require_uvs(arrays);
  const TextureVertexShader vs{arrays.attributes(), Mat4f(model_view_projection)};
  return draw_triangles(framebuffer, state, uint32_t(arrays.positions.size()), arrays.indices, vs,
                        TextureFragmentShader{&texture});
}

DrawStats draw_two_textured(Framebuffer& framebuffer, const RasterState& state, const VertexArrays& arrays,
                            const Mat4& model_view_projection, const Texture2D& left, const Texture2D* right,
                            Vec2f offset) {
  require_uvs(arrays);
  const TwoTextureVertexShader vs{arrays.attributes(), Mat4f(model_view_projection), offset};
  return draw_triangles(framebuffer, state, uint32_t(arrays.positions.size()), arrays.indices, vs,
                        TwoTextureFragmentShader{&left, right});
}

Texture2D disc_texture(int size, double radius, const Vec4f& disc, const Vec4f& background, Filter filter) {
  if (size < 1) throw InvalidInput(fmt::format("disc texture size must be >= 1, got {}", size));
  ImageRGBA image(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // Texel (x, y) of the image is texture coordinate ((x + 0.5) / size, 1 - (y + 0.5) / size) (texture.hpp).
      const double u = (x + 0.5) / size - 0.5, v = 0.5 - (y + 0.5) / size;
      image(x, y) = u * u + v * v < radius * radius ? disc : background;
    }
  return Texture2D(std::move(image), Sampler{.wrap_u = Wrap::clamp, .wrap_v = Wrap::clamp, .filter = filter});
}

}  // namespace tessera::raster3d
