// Example 16: the notes' twisting vertex program ("Vertex Program – Twisting") as a C++ vertex shader:
// pos = MVP * vertex; angle = twist * length(pos.xy - center); pos.xy rotated counterclockwise by angle. Vertices
// farther from the center turn more, so a checkerboard swirls. Only vertices move (edges stay straight between
// them), which is why the board is finely tessellated: 48 x 48 squares, each with its own four corners and color.
// The pipeline is called directly with the shipped TwistVertexShader and ColorFragmentShader.
#include <vector>

#include "gallery.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace {

using namespace tessera;

struct Board {
  std::vector<Vec3f> positions, colors;
  std::vector<uint32_t> indices;
};

// [-1, 1]^2 in the z = 0 plane, n x n squares in a two-color checker with a warm-to-cool gradient.
Board checkerboard(int n) {
  Board b;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x0 = -1 + 2.0f * float(i) / float(n), x1 = -1 + 2.0f * float(i + 1) / float(n);
      const float y0 = -1 + 2.0f * float(j) / float(n), y1 = -1 + 2.0f * float(j + 1) / float(n);
      const float t = float(i + j) / float(2 * n);
      const Vec3f color =
          (i / 4 + j / 4) % 2 == 0 ? Vec3f(0.95f, 0.55f + 0.3f * t, 0.2f) : Vec3f(0.15f, 0.25f, 0.5f + 0.4f * t);
      const auto base = uint32_t(b.positions.size());
      for (const Vec3f& p : {Vec3f(x0, y0, 0), Vec3f(x1, y0, 0), Vec3f(x1, y1, 0), Vec3f(x0, y1, 0)}) {
        b.positions.push_back(p);
        b.colors.push_back(color);
      }
      b.indices.insert(b.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  return b;
}

ImageRGB twisted(const Board& board, float twist) {
  raster3d::Framebuffer framebuffer(300, 300);
  framebuffer.clear({1, 1, 1});
  raster3d::TwistVertexShader vs;
  vs.attributes.positions = board.positions.data();
  vs.attributes.colors = board.colors.data();
  vs.model_view_projection = Mat4f(ortho(-1.55, 1.55, -1.55, 1.55, -1, 1));
  vs.twist = twist;
  raster3d::draw_triangles(framebuffer, raster3d::RasterState{}, uint32_t(board.positions.size()), board.indices, vs,
                           raster3d::ColorFragmentShader{});
  return framebuffer.color_rgb();
}

}  // namespace

TESSERA_EXAMPLE(ex16_twist_shader, "16_twist_shader", "The twist vertex shader") {
  const Board board = checkerboard(48);
  gallery.add("16_twist_shader.png",
              examples::side_by_side({twisted(board, 0.0f), twisted(board, 1.2f), twisted(board, 2.6f)}),
              "The notes' twisting vertex program on a 48 x 48 checkerboard: twist = 0, 1.2 and 2.6 radians per "
              "clip-space unit from the center; vertices farther out turn more, counterclockwise.");
}
