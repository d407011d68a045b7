// libFuzzer target for GLSL fragment shaders (`tessera raster --fragment-shader`, scene-file and viewer shaders): the
// input is the fragment shader, linked with a fixed vertex shader (full-screen, texture coordinates and color). A
// source that glslang or Tessera's compiler refuses must end in tessera::Error (CompileError); one that compiles is
// drawn on a 16 x 16 framebuffer with a texture and a cube map bound, and must end normally or in tessera::Error (an
// endless loop's guard). A crash, a hang or an exception of another kind is a bug.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "tessera/core/error.hpp"
#include "tessera/glsl/program.hpp"

namespace {

using namespace tessera;

const char* const kVertex = R"(
varying vec3 normal;
void main() {
  gl_TexCoord[0] = gl_MultiTexCoord0;
  gl_FrontColor = gl_Color;
  normal = gl_Normal;
  gl_Position = gl_Vertex;
}
)";

struct Fixture {
  std::shared_ptr<Texture2D> texture;
  std::shared_ptr<CubeMap> cube;
  Fixture() {
    ImageRGBA8 image(8, 8);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) image(x, y) = glm::u8vec4(x * 30, y * 30, 128, 255);
    texture = std::make_shared<Texture2D>(image, Sampler{.filter = Filter::trilinear});
    std::array<ImageRGBA, 6> faces;
    for (auto& f : faces) f = ImageRGBA(4, 4, Vec4f(0.5f, 0.25f, 1.0f, 1.0f));
    cube = std::make_shared<CubeMap>(faces);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Fixture fixture;
  const std::string fragment(reinterpret_cast<const char*>(data), size);
  try {
    glsl::Program p = glsl::Program::compile({kVertex, "fuzz.vert"}, {fragment, "fuzz.frag"});
    for (int unit = 0; unit < 4; ++unit) {
      p.bind_texture(unit, fixture.texture);
      p.bind_cube_map(unit + 4, fixture.cube);
    }
    raster3d::Framebuffer fb(16, 16);
    const std::vector<Vec3f> positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    const std::vector<Vec3f> normals(4, Vec3f(0, 0, 1));
    const std::vector<Vec2f> uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    glsl::ProgramInputs in;
    in.positions = positions;
    in.normals = normals;
    in.uvs = uvs;
    p.draw_triangles(fb, raster3d::RasterState{}, in, std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
  } catch (const tessera::Error&) {
  }
  return 0;
}
