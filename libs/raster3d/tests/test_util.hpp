#pragma once
// Shared fixtures of the raster3d tests: shaders that place vertices directly in GL window coordinates, or through a
// matrix with one flat color.
#include <vector>

#include "tessera/raster3d/lighting.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d::testing {

/// A vertex in GL window coordinates (origin bottom-left, y up, z in [0, 1]) with a color.
struct WindowVertexIn {
  Vec3f window;
  Vec3f color{1, 1, 1};
};

/// Maps window coordinates on a width x height framebuffer to clip space (w = `w`, so the divide undoes it).
/// For power-of-two sizes and coordinates on a 1/256 grid the round trip is exact.
struct WindowShader {
  const std::vector<WindowVertexIn>* vertices;
  float width, height, w = 1.0f;

  VertexOut<ColorVaryings> operator()(uint32_t i) const {
    const WindowVertexIn& v = (*vertices)[i];
    return {Vec4f(2 * v.window.x / width - 1, 2 * v.window.y / height - 1, 2 * v.window.z - 1, 1.0f) * w, {v.color}};
  }
};

/// Positions through a float32 model-view-projection as OpenGL forms and applies it (gl_transform); no varyings.
struct FlatVertexShader {
  const Vec3f* positions = nullptr;
  Mat4f model_view_projection{1.0f};
  VertexOut<NoVaryings> operator()(uint32_t i) const { return {gl_transform(model_view_projection, positions[i]), {}}; }
};

/// One constant color for every fragment.
struct FlatFragmentShader {
  Vec3f color{1, 1, 1};
  bool operator()(const NoVaryings&, Vec3f& c) const {
    c = color;
    return true;
  }
};

/// Draws triangles given in window coordinates (white unless colored), depth test off.
inline void draw_window_triangles(Framebuffer& fb, const std::vector<WindowVertexIn>& vertices,
                                  const std::vector<uint32_t>& indices, RasterState state = {}) {
  state.depth_test = false;
  draw_triangles(fb, state, uint32_t(vertices.size()), indices,
                 WindowShader{&vertices, float(fb.width()), float(fb.height())}, ColorFragmentShader{});
}

/// True where the pixel (image coordinates, row 0 on top) differs from black.
inline std::vector<int> covered(const Framebuffer& fb) {
  std::vector<int> out(size_t(fb.width()) * fb.height());
  for (int y = 0; y < fb.height(); ++y)
    for (int x = 0; x < fb.width(); ++x) {
      const auto c = fb.color()(x, y);
      out[size_t(y) * fb.width() + x] = (c.x | c.y | c.z) != 0;
    }
  return out;
}

/// Whether GL pixel (i, j) (y up) is covered.
inline bool covered_gl(const Framebuffer& fb, int i, int j) {
  const auto c = fb.color()(i, fb.height() - 1 - j);
  return (c.x | c.y | c.z) != 0;
}

}  // namespace tessera::raster3d::testing
