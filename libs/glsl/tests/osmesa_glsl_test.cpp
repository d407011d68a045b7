// The same GLSL programs through Mesa (OSMesa's llvmpipe, a compatibility context) and through Tessera: the shipped
// examples (examples/shaders: the notes' four programs, Phong, Blinn, toon, bricks with discard, normal mapping with
// a cube map, loops and branches on uniforms, GLSL 3.30, derivatives, a minified MIPmapped texture). Coverage must be
// identical and the color within 2/255 on at least 99.9% of the covered pixels.
#include "osmesa_glsl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <memory>

#include "glsl_notes_scenes.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/glsl/program.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/transform.hpp"

namespace tessera::glsl {
namespace {

using reference::GlslDraw;
using reference::GlslUniform;

constexpr int kSize = 192;

struct Mesh {
  std::vector<Vec3f> positions, normals, colors, tangents;
  std::vector<Vec2f> uvs;
  std::vector<uint32_t> indices;
};

// A UV sphere of radius 1: normals, uvs (u around, v up), colors from the position, tangents along u.
Mesh sphere(int rings, int segments) {
  Mesh m;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = float(M_PI) * float(r) / float(rings), phi = 2 * float(M_PI) * float(s) / float(segments);
      const Vec3f p(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.push_back(p);
      m.normals.push_back(p);
      m.colors.push_back(0.5f * p + 0.5f);
      m.tangents.push_back(Vec3f(-std::sin(phi), 0, -std::cos(phi)));
      m.uvs.push_back(Vec2f(float(s) / float(segments), 1 - float(r) / float(rings)));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const auto a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments) + 1;
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  return m;
}

// A floor receding from the camera (y = -1, z from 2 to -30), uvs 0..1 across, 0..16 along: a minified texture.
Mesh floor_plane() {
  Mesh m;
  for (const auto& [x, z] : {std::pair{-3.0f, 2.0f}, {3.0f, 2.0f}, {3.0f, -30.0f}, {-3.0f, -30.0f}}) {
    m.positions.push_back(Vec3f(x, -1, z));
    m.normals.push_back(Vec3f(0, 1, 0));
    m.colors.push_back(Vec3f(1));
    m.tangents.push_back(Vec3f(1, 0, 0));
    m.uvs.push_back(Vec2f((x + 3) / 6, (2 - z) / 2));
  }
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// An 8-bit checkerboard with a colored gradient, rows stored as glTexImage2D takes them (bottom first).
std::vector<uint8_t> checker(int size) {
  std::vector<uint8_t> rgba;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool on = ((x / 8) + (y / 8)) % 2;
      rgba.insert(rgba.end(), {uint8_t(on ? 230 : 40 + 3 * x % 200), uint8_t(on ? 200 : 60 + 2 * y % 180),
                               uint8_t(on ? 40 : 220), 255});
    }
  return rgba;
}

// A tangent-space normal map of bumps (RGB = (n + 1) / 2).
std::vector<uint8_t> bumps(int size) {
  std::vector<uint8_t> rgba;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float u = float(x) / float(size) * 8 * float(M_PI), v = float(y) / float(size) * 4 * float(M_PI);
      const Vec3f n = glm::normalize(Vec3f(0.4f * std::cos(u), 0.4f * std::cos(v), 1));
      rgba.insert(rgba.end(), {uint8_t(std::lround((n.x + 1) * 127.5f)), uint8_t(std::lround((n.y + 1) * 127.5f)),
                               uint8_t(std::lround((n.z + 1) * 127.5f)), 255});
    }
  return rgba;
}

// Six faces of an environment that is continuous across the faces, as real ones are (a texel's color is a smooth
// function of its direction): a sky-like gradient with soft waves. Faces of their own flat colors would compare the
// two renderers' rounding of directions on the seams, where the bumps make the face flip from pixel to pixel.
std::array<std::vector<uint8_t>, 6> environment_faces(int size) {
  std::array<std::vector<uint8_t>, 6> faces;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::vec2 st((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size));
        const Vec3f d = glm::normalize(cube_direction({CubeFace(f), st}));
        const float wave = 0.8f + 0.2f * std::sin(6 * d.x) * std::cos(5 * d.z);
        const Vec3f c = wave * Vec3f(0.5f + 0.4f * d.x, 0.55f + 0.4f * d.y, 0.6f - 0.35f * d.z);
        for (int k = 0; k < 3; ++k)
          faces[size_t(f)].push_back(uint8_t(std::lround(255 * std::clamp(c[k], 0.0f, 1.0f))));
        faces[size_t(f)].push_back(255);
      }
  return faces;
}

/// An RGBA8 image (top row first) from rows stored bottom first.
ImageRGBA8 from_gl_rows(const std::vector<uint8_t>& rgba, int width, int height, bool flip = true) {
  ImageRGBA8 image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const uint8_t* p = &rgba[(size_t(flip ? height - 1 - y : y) * size_t(width) + size_t(x)) * 4];
      image(x, y) = glm::u8vec4(p[0], p[1], p[2], p[3]);
    }
  return image;
}

struct Case {
  std::string name;
  std::vector<GlslUniform> uniforms;
  bool floor = false;      // the receding floor instead of the sphere
  bool texture = false;    // a checker texture on unit 0 (normal_map: the bump map)
  bool mipmapped = false;  // trilinear MIPmaps (else bilinear)
  bool clamp = false;      // clamp to edge (else repeat)
  bool cube = false;       // the environment on unit 1
  std::string fragment;    // the fragment shader's text instead of the file's
};

std::string source(const std::string& file) {
  return read_file(std::string(TESSERA_SOURCE_DIR) + "/examples/shaders/" + file);
}

struct Result {
  int covered = 0, coverage_differences = 0, color_differences = 0, max_difference = 0;
  ImageRGBA8 mesa, tessera;  // the two pictures, written out when they differ
};

Result compare(const Case& c) {
  const Mesh mesh = c.floor ? floor_plane() : sphere(32, 64);
  const Mat4f projection = Mat4f(perspective(glm::radians(40.0), 1.0, 0.5, 40.0));
  const Mat4f model_view = Mat4f(look_at(Vec3(0.4, 0.5, 3.4), Vec3(0, 0, 0), Vec3(0, 1, 0))) * Mat4f(rotate_y(0.3));
  GlslDraw d;
  d.vertex_source = source(c.name + ".vert");
  d.fragment_source = c.fragment.empty() ? source(c.name + ".frag") : c.fragment;
  d.positions = mesh.positions;
  d.normals = mesh.normals;
  d.colors = mesh.colors;
  d.uvs = mesh.uvs;
  d.indices = mesh.indices;
  // User attributes by name (GLSL 3.30's position and normal read the mesh's arrays, as Tessera's usual names do).
  const auto attribute = [](const char* name, const std::vector<Vec3f>& v) {
    return reference::GlslAttribute{name, 3, {&v[0].x, &v[0].x + 3 * v.size()}};
  };
  d.attributes = {attribute("tangent", mesh.tangents), attribute("position", mesh.positions),
                  attribute("normal", mesh.normals)};
  d.model_view = model_view;
  d.projection = projection;
  d.lights.push_back({Vec4f(2, 3, 4, 1), Vec4f(0.1f, 0.1f, 0.1f, 1), Vec4f(0.9f, 0.85f, 0.8f, 1), Vec4f(1)});
  d.material = {Vec4f(0.2f, 0.2f, 0.25f, 1), Vec4f(0.8f, 0.5f, 0.3f, 1), Vec4f(0.6f, 0.6f, 0.6f, 1), Vec4f(0, 0, 0, 1),
                40};
  d.uniforms = c.uniforms;
  const int texture_size = 64;
  if (c.texture) {
    reference::GlslTexture t;
    t.width = t.height = texture_size;
    t.rgba = c.name == "normal_map" ? bumps(texture_size) : checker(texture_size);
    t.filter = c.mipmapped ? reference::GlFilter::linear_mipmap_linear : reference::GlFilter::linear;
    t.wrap = c.clamp ? reference::GlslWrap::clamp_to_edge : reference::GlslWrap::repeat;
    d.textures.emplace_back(0, t);
  }
  const int cube_size = 32;
  if (c.cube) {
    reference::GlslCubeMap cube;
    cube.size = cube_size;
    cube.faces = environment_faces(cube_size);
    d.cube_maps.emplace_back(1, cube);
  }
  reference::GlslRenderer renderer(d, kSize, kSize);
  const std::vector<uint8_t> mesa = renderer.render();
  const std::vector<float> mesa_depth = renderer.depth();

  Program p = Program::compile({d.vertex_source, c.name + ".vert"}, {d.fragment_source, c.name + ".frag"});
  FixedFunctionState state;
  state.model_view = model_view;
  state.projection = projection;
  state.lights[0] = {d.lights[0].ambient, d.lights[0].diffuse, d.lights[0].specular, d.lights[0].position};
  state.front_material = state.back_material = {d.material.ambient, d.material.diffuse, d.material.specular,
                                                d.material.emission, d.material.shininess};
  p.set_fixed_function(state);
  for (const GlslUniform& u : c.uniforms) {
    if (!u.floats.empty()) p.set_uniform(u.name, u.floats);
    if (!u.ints.empty()) p.set_uniform(u.name, u.ints);
  }
  if (c.texture) {
    Sampler sampler;
    sampler.filter = c.mipmapped ? Filter::trilinear : Filter::bilinear;
    sampler.wrap_u = sampler.wrap_v = c.clamp ? Wrap::clamp : Wrap::repeat;
    p.bind_texture(
        0, std::make_shared<Texture2D>(from_gl_rows(d.textures[0].second.rgba, texture_size, texture_size), sampler));
  }
  if (c.cube) {
    std::array<ImageRGBA, 6> faces;
    for (int f = 0; f < 6; ++f)  // a face's row t = 0 is its first row as uploaded: no flip
      faces[size_t(f)] = to_float(from_gl_rows(d.cube_maps[0].second.faces[size_t(f)], cube_size, cube_size, false));
    p.bind_cube_map(1, std::make_shared<CubeMap>(faces, Filter::bilinear));
  }
  raster3d::Framebuffer fb(kSize, kSize);
  fb.clear_color(Vec3f(0), 0.0f);
  ProgramInputs in;
  in.positions = mesh.positions;
  in.normals = mesh.normals;
  in.colors = mesh.colors;
  in.uvs = mesh.uvs;
  in.attributes["tangent"] = {&mesh.tangents[0].x, 3};
  p.draw_triangles(fb, raster3d::RasterState{}, in, mesh.indices);

  Result r;
  r.mesa = ImageRGBA8(kSize, kSize);
  std::memcpy(&r.mesa(0, 0), mesa.data(), mesa.size());
  r.tessera = fb.color();
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const uint8_t* m = &mesa[(size_t(y) * kSize + size_t(x)) * 4];
      const glm::u8vec4 t = fb.color()(x, y);
      const bool mesa_covered = mesa_depth[size_t(y) * kSize + size_t(x)] < 1.0f,
                 tessera_covered = fb.depth()(x, y) != raster3d::kDepthMax;
      r.coverage_differences += mesa_covered != tessera_covered;
      if (!mesa_covered || !tessera_covered) continue;
      ++r.covered;
      int worst = 0;
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(int(m[k]) - int(t[k])));
      r.max_difference = std::max(r.max_difference, worst);
      r.color_differences += worst > 2;
    }
  return r;
}

/// Asserts identical coverage and at most `allowed` (a fraction) of the covered pixels more than 2/255 apart.
void expect_matches(const Case& c, double allowed = 0.001) {
  const Result r = compare(c);
  EXPECT_GT(r.covered, kSize * kSize / 20) << c.name;
  EXPECT_EQ(r.coverage_differences, 0) << c.name;
  EXPECT_LE(r.color_differences, int(allowed * r.covered))
      << c.name << ": " << r.color_differences << " of " << r.covered << " pixels differ by more than 2/255 (max "
      << r.max_difference << ")";
  if (r.coverage_differences > 0 || r.color_differences > int(allowed * r.covered)) {
    const std::string stem = ::testing::TempDir() + "glsl_" + c.name;
    write_image(stem + "_mesa.png", r.mesa);
    write_image(stem + "_tessera.png", r.tessera);
    std::printf("the pictures: %s_mesa.png, %s_tessera.png\n", stem.c_str(), stem.c_str());
  }
  std::printf("%-20s %6d pixels, %d over 2/255, max difference %d/255\n", c.name.c_str(), r.covered,
              r.color_differences, r.max_difference);
}

GlslUniform f(const std::string& name, std::vector<float> v) { return {name, std::move(v), {}}; }
GlslUniform i(const std::string& name, std::vector<int> v) { return {name, {}, std::move(v)}; }

TEST(GlslMesa, NotesDiffuse) { expect_matches({"notes_diffuse"}); }
TEST(GlslMesa, NotesTwist) { expect_matches({"notes_twist", {f("twist", {0.002f})}}); }
TEST(GlslMesa, NotesTextureMagnified) { expect_matches({"notes_texture", {i("myTexture", {0})}, false, true}); }
TEST(GlslMesa, NotesTwoTextures) {
  expect_matches({"notes_two_textures", {i("myTexture", {0})}, false, true, false, true});
}
TEST(GlslMesa, Phong) { expect_matches({"phong"}); }
TEST(GlslMesa, Blinn) { expect_matches({"blinn"}); }
TEST(GlslMesa, Toon) { expect_matches({"toon", {f("base_color", {0.9f, 0.6f, 0.2f})}}); }
TEST(GlslMesa, BrickWithDiscard) {
  expect_matches({"brick",
                  {f("brick_color", {0.7f, 0.2f, 0.1f}), f("mortar_color", {0.8f, 0.8f, 0.75f}),
                   f("brick_size", {0.3f, 0.15f}), f("brick_pct", {0.85f, 0.8f})}});
}
TEST(GlslMesa, NormalMapWithCubeMap) {
  expect_matches({"normal_map",
                  {i("normal_map", {0}), i("environment", {1}), f("reflectivity", {0.4f})},
                  false,
                  true,
                  false,
                  false,
                  true});
}
TEST(GlslMesa, LoopsAndBranchesOnUniforms) {
  for (const int wrap : {0, 1})
    expect_matches({"loops",
                    {i("light_count", {3}), f("light_dir", {1, 1, 1, -1, 0.5f, 0.2f, 0, -1, 0.3f, 0, 0, 1}),
                     f("light_color", {0.6f, 0.3f, 0.2f, 0.1f, 0.4f, 0.2f, 0.2f, 0.2f, 0.5f, 1, 1, 1}),
                     i("wrap_lighting", {wrap}), i("rim_power", {3})}});
}
TEST(GlslMesa, Phong330) {
  const Mat4f model_view = Mat4f(look_at(Vec3(0.4, 0.5, 3.4), Vec3(0, 0, 0), Vec3(0, 1, 0))) * Mat4f(rotate_y(0.3));
  const Mat4f projection = Mat4f(perspective(glm::radians(40.0), 1.0, 0.5, 40.0));
  const Mat3f normal_matrix = glm::inverseTranspose(Mat3f(model_view));
  const auto floats = [](const auto& m) { return std::vector<float>(&m[0][0], &m[0][0] + sizeof(m) / 4); };
  expect_matches(
      {"phong330",
       {f("model_view", floats(model_view)), f("projection", floats(projection)),
        f("normal_matrix", floats(normal_matrix)), f("light_position", {2, 3, 4, 1}),
        f("light_color", {1, 0.95f, 0.9f}), f("ambient_color", {0.05f, 0.05f, 0.08f}),
        f("diffuse_color", {0.3f, 0.5f, 0.8f}), f("specular_color", {0.5f, 0.5f, 0.5f}), f("shininess", {25})}});
}
TEST(GlslMesa, MinifiedMipmappedTexture) {
  // Measured: 99.06 % of the pixels within 2/255, all within 5/255. llvmpipe filters 8-bit textures in lower
  // precision (its 8-bit AoS path: GALLIVM_PERF=no_aos_sampling halves the count) and Tessera in float; the rest is
  // at the checks' edges, where the two MIPmap levels differ most.
  expect_matches({"textured_lod", {i("color_map", {0}), f("scale", {1})}, true, true, true}, 0.01);
  const Result r = compare({"textured_lod", {i("color_map", {0}), f("scale", {1})}, true, true, true});
  EXPECT_LE(r.max_difference, 6);
}
TEST(GlslMesa, Derivatives) {
  expect_matches(
      {"dfdx",
       {f("frequency", {12}), f("stripe_color", {0.1f, 0.2f, 0.6f}), f("background_color", {0.95f, 0.9f, 0.8f})}});
}

}  // namespace
}  // namespace tessera::glsl

namespace tessera::glsl {
namespace {

TEST(GlslMesa, GalleryScenesOfTheNotesPrograms) {
  // Example 29's four scenes (examples/glsl_notes_scenes.hpp) through Mesa and Tessera. Mesa's picture is written
  // beside the test's other files: docs/gallery/29_glsl_programs_mesa.png is a copy.
  std::vector<ImageRGB> mesa_panels;
  for (const examples::NotesScene& s : examples::notes_scenes()) {
    GlslDraw d;
    d.vertex_source = source(s.program + ".vert");
    d.fragment_source = source(s.program + ".frag");
    d.positions = s.positions;
    d.normals = s.normals;
    d.colors = s.colors;
    d.uvs = s.uvs;
    d.indices = s.indices;
    d.model_view = s.model_view;
    d.projection = s.projection;
    d.lights.push_back({s.light_position});
    for (const auto& [name, values] : s.float_uniforms) d.uniforms.push_back(f(name, values));
    for (const auto& [name, values] : s.int_uniforms) d.uniforms.push_back(i(name, values));
    d.clear_color = Vec4f(0.05f, 0.05f, 0.08f, 1);
    if (!s.texture.empty()) {
      reference::GlslTexture t;
      t.width = s.texture.width(), t.height = s.texture.height();
      for (int y = t.height - 1; y >= 0; --y)  // GL rows bottom first
        for (int x = 0; x < t.width; ++x) t.rgba.insert(t.rgba.end(), &s.texture(x, y)[0], &s.texture(x, y)[0] + 4);
      t.filter =
          s.filter == Filter::trilinear ? reference::GlFilter::linear_mipmap_linear : reference::GlFilter::linear;
      t.wrap = s.wrap == Wrap::clamp ? reference::GlslWrap::clamp_to_edge : reference::GlslWrap::repeat;
      d.textures.emplace_back(0, t);
    }
    const int size = examples::kNotesSceneSize;
    const std::vector<uint8_t> mesa = reference::render_glsl(d, size, size);
    const ImageRGBA8 tessera = examples::draw_with_tessera(s, d.vertex_source, d.fragment_source);
    ImageRGBA8 mesa_image(size, size);
    std::memcpy(&mesa_image(0, 0), mesa.data(), mesa.size());
    mesa_panels.push_back(to_rgb(to_float(mesa_image)));
    int over = 0, worst = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        for (int c = 0; c < 3; ++c) {
          const int difference = std::abs(int(mesa_image(x, y)[c]) - int(tessera(x, y)[c]));
          worst = std::max(worst, difference);
          over += difference > 2;
        }
    std::printf("%-20s %d channel values over 2/255, largest difference %d/255\n", s.program.c_str(), over, worst);
    EXPECT_LE(over, size * size * 3 / 200) << s.program;  // 0.5 % of the channel values (the trilinear texture)
    EXPECT_LE(worst, 6) << s.program;
  }
  ImageRGB sheet(examples::kNotesSceneSize * 4, examples::kNotesSceneSize);
  for (int p = 0; p < 4; ++p)
    for (int y = 0; y < sheet.height(); ++y)
      for (int x = 0; x < examples::kNotesSceneSize; ++x)
        sheet(p * examples::kNotesSceneSize + x, y) = mesa_panels[size_t(p)](x, y);
  write_image(::testing::TempDir() + "29_glsl_programs_mesa.png", sheet);
}

}  // namespace
}  // namespace tessera::glsl
