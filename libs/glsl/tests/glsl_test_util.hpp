#pragma once
// The GLSL tests' shared parts: a program drawn over the whole framebuffer, and reading a pixel back.
#include <string>
#include <vector>

#include "tessera/glsl/program.hpp"

namespace tessera::glsl::testing {

/// The pass-through vertex shader of full_screen: clip position from gl_Vertex, gl_MultiTexCoord0 into
/// gl_TexCoord[0] (uv 0 at the left and bottom edges, 1 at the right and top).
inline const char* const kFullScreenVertex = R"(
void main() {
  gl_TexCoord[0] = gl_MultiTexCoord0;
  gl_Position = gl_Vertex;
}
)";

/// Compiles `fragment` with kFullScreenVertex (or `vertex`).
inline Program compile(const std::string& fragment, const std::string& vertex = kFullScreenVertex) {
  return Program::compile({vertex, "test.vert"}, {fragment, "test.frag"});
}

/// Draws two triangles covering a size x size framebuffer (cleared to black) through `program`.
inline raster3d::Framebuffer full_screen(const Program& program, int size = 32) {
  raster3d::Framebuffer fb(size, size);
  fb.clear_color(Vec3f(0));
  const std::vector<Vec3f> positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<Vec2f> uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  ProgramInputs in;
  in.positions = positions;
  in.uvs = uvs;
  program.draw_triangles(fb, raster3d::RasterState{}, in, std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
  return fb;
}

/// The color at GL pixel (i, j) (y up) in [0, 1].
inline Vec4f pixel(const raster3d::Framebuffer& fb, int i, int j) {
  return Vec4f(fb.color()(i, fb.height() - 1 - j)) / 255.0f;
}

}  // namespace tessera::glsl::testing
