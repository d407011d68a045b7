#pragma once
// The scenes of the notes' four GLSL programs (examples/shaders/notes_*), shared by the gallery's example 29 (drawn
// by Tessera) and the glsl tests' comparison of that picture with Mesa's (libs/glsl/tests/osmesa_glsl_test.cpp):
// each draw's arrays, matrices, light, uniforms and texture, in the terms both renderers take.
#include <cmath>
#include <string>
#include <vector>

#include "tessera/glsl/program.hpp"
#include "tessera/image/image.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"

namespace tessera::examples {

/// One draw of a notes program.
struct NotesScene {
  std::string program;  ///< the file stem in examples/shaders ("notes_diffuse")
  std::vector<Vec3f> positions, normals, colors;
  std::vector<Vec2f> uvs;
  std::vector<uint32_t> indices;
  Mat4f model_view{1.0f}, projection{1.0f};
  Vec4f light_position{0, 0, 1, 0};  ///< gl_LightSource[0].position, eye space
  std::vector<std::pair<std::string, std::vector<float>>> float_uniforms;
  std::vector<std::pair<std::string, std::vector<int>>> int_uniforms;
  ImageRGBA8 texture;  ///< on unit 0 when not empty (top row first)
  Filter filter = Filter::bilinear;
  Wrap wrap = Wrap::repeat;
};

/// Draws `scene` through Tessera's GLSL executor with the program's sources: the picture, RGBA8.
ImageRGBA8 draw_with_tessera(const NotesScene& scene, const std::string& vertex, const std::string& fragment);

/// The picture size of each scene.
inline constexpr int kNotesSceneSize = 240;

/// The four scenes: the diffuse program on a torus lit by a point light just above its front; the twisting program
/// on a finely divided colored square; the texture program on a checkered square in perspective (trilinear
/// MIPmaps); the two-texture program on a texture of one disc (the notes' Venn diagram).
inline std::vector<NotesScene> notes_scenes() {
  std::vector<NotesScene> scenes;
  const Mat4f projection = Mat4f(perspective(radians(40), 1, 1, 10));
  const auto add_mesh = [](NotesScene& s, const TriMesh& m) {
    for (size_t i = 0; i < m.positions.size(); ++i) {
      s.positions.push_back(Vec3f(m.positions[i]));
      if (!m.normals.empty()) s.normals.push_back(Vec3f(m.normals[i]));
      if (!m.uvs.empty()) s.uvs.push_back(Vec2f(m.uvs[i]));
    }
    s.indices = m.indices;
  };
  {
    NotesScene s{"notes_diffuse"};
    add_mesh(s, to_tri_mesh(make_torus(1.0, 0.4, 48, 24)));
    const Mat4 view = look_at({0, 2.2, 3.2}, {0, 0, 0}, {0, 1, 0});
    s.model_view = Mat4f(view);
    s.projection = projection;
    s.light_position = Vec4f(Vec3f(transform_point(view, {0.6, 0.75, 0.9})), 1);
    scenes.push_back(std::move(s));
  }
  {
    NotesScene s{"notes_twist"};
    add_mesh(s, to_tri_mesh(make_grid(48, 48)));  // the xz plane: seen from above
    for (const Vec3f& p : s.positions) s.colors.push_back(Vec3f(0.5f + 0.5f * p.x, 0.4f, 0.5f - 0.5f * p.z));
    s.model_view = Mat4f(look_at({0, 3, 0.001}, {0, 0, 0}, {0, 1, 0}));
    s.projection = projection;
    s.float_uniforms = {{"twist", {0.3f}}};
    scenes.push_back(std::move(s));
  }
  const auto square = [](NotesScene& s) {
    s.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    s.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    s.indices = {0, 1, 2, 0, 2, 3};
  };
  {
    NotesScene s{"notes_texture"};
    square(s);
    for (Vec2f& uv : s.uvs) uv *= 4.0f;
    s.model_view = Mat4f(look_at({0, -2.2, 1.1}, {0, 0.3, 0}, {0, 1, 0}));
    s.projection = projection;
    s.int_uniforms = {{"myTexture", {0}}};
    s.texture = ImageRGBA8(128, 128);
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x)
        s.texture(x, y) = (x / 16 + y / 16) % 2 ? glm::u8vec4(242, 217, 140, 255) : glm::u8vec4(51, 89, 166, 255);
    s.filter = Filter::trilinear;
    scenes.push_back(std::move(s));
  }
  {
    NotesScene s{"notes_two_textures"};
    square(s);
    s.projection = Mat4f(ortho(-1, 1, -1, 1, -1, 1));
    s.int_uniforms = {{"myTexture", {0}}};
    s.texture = ImageRGBA8(128, 128);
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x) {
        const float dx = (float(x) + 0.5f) / 128 - 0.5f, dy = (float(y) + 0.5f) / 128 - 0.5f;
        s.texture(x, y) = dx * dx + dy * dy < 0.09f ? glm::u8vec4(230, 60, 50, 255) : glm::u8vec4(20, 20, 30, 255);
      }
    s.wrap = Wrap::clamp;
    scenes.push_back(std::move(s));
  }
  return scenes;
}

inline ImageRGBA8 draw_with_tessera(const NotesScene& scene, const std::string& vertex, const std::string& fragment) {
  glsl::Program p = glsl::Program::compile({vertex, scene.program + ".vert"}, {fragment, scene.program + ".frag"});
  glsl::FixedFunctionState state;
  state.model_view = scene.model_view;
  state.projection = scene.projection;
  state.lights[0].position = scene.light_position;
  p.set_fixed_function(state);
  for (const auto& [name, values] : scene.float_uniforms) p.set_uniform(name, values);
  for (const auto& [name, values] : scene.int_uniforms) p.set_uniform(name, values);
  if (!scene.texture.empty()) {
    Sampler sampler;
    sampler.filter = scene.filter;
    sampler.wrap_u = sampler.wrap_v = scene.wrap;
    p.bind_texture(0, std::make_shared<Texture2D>(scene.texture, sampler));
  }
  raster3d::Framebuffer fb(kNotesSceneSize, kNotesSceneSize);
  fb.clear_color(Vec3f(0.05f, 0.05f, 0.08f));
  glsl::ProgramInputs in;
  in.positions = scene.positions;
  in.normals = scene.normals;
  in.colors = scene.colors;
  in.uvs = scene.uvs;
  p.draw_triangles(fb, raster3d::RasterState{}, in, scene.indices);
  return fb.color();
}

}  // namespace tessera::examples
