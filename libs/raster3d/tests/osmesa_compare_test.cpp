// raster3d against Mesa's fixed-function OpenGL 1.x (OSMesa, llvmpipe): the same meshes, matrices, lights and
// materials drawn by both; coverage, 24-bit depth and 8-bit color compared pixel by pixel over the pixels either
// renderer covers. Goals (issue 4): unlit flat-colored meshes with the same coverage and depth on >= 99.9% of those
// pixels; lit Gouraud (and the flat shade model) within 2/255 per channel on >= 99%.
//
// "Same depth" is bit-identical: Tessera evaluates the depth plane in llvmpipe's float32 arithmetic (vertex transform,
// clipper, setup, interpolation and unorm24 conversion as Mesa 22.3 does them; docs/raster3d.md), so the 24-bit values
// match exactly; the few pixels that may differ must stay within kDepthTolerance units of 2^-24. The exact-match share
// is printed with every comparison. Unlit colors are exact: both round x * 255 to nearest with ties to even.
//
// A failing case writes a diff picture to the test's temporary folder (path in the failure message): red = only
// Tessera covers, green = only OpenGL covers, blue = depth differs beyond the tolerance, yellow = color beyond it.
#include "osmesa_compare.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "osmesa_renderer.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/surface_shader.hpp"
#include "test_util.hpp"

namespace tessera {
namespace {

using osmesa_compare::kBackground;
using osmesa_compare::persp;
using reference::GlFrame;
using reference::GlState;
using reference::GlSubmit;

// ---- Meshes ----------------------------------------------------------------------------------------------------

TriMesh sphere() { return to_tri_mesh(make_uv_sphere(40, 20)); }
TriMesh torus() { return to_tri_mesh(make_torus(1.0, 0.4, 40, 20)); }

// A cube with one normal per face: every triangle gets its own three vertices.
TriMesh faceted_cube() {
  const TriMesh shared = to_tri_mesh(make_box());
  TriMesh mesh;
  for (size_t t = 0; t < shared.triangle_count(); ++t) {
    const Vec3 a = shared.positions[shared.indices[3 * t]], b = shared.positions[shared.indices[3 * t + 1]],
               c = shared.positions[shared.indices[3 * t + 2]];
    const Vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (const Vec3& p : {a, b, c}) {
      mesh.indices.push_back(uint32_t(mesh.positions.size()));
      mesh.positions.push_back(p);
      mesh.normals.push_back(n);
    }
  }
  return mesh;
}

// 250 random triangles in [-1, 1]^3 with edges up to ~0.8, random unit normals and random colors per vertex:
// interpenetrating, every orientation, many slivers.
TriMesh triangle_soup() {
  Rng rng(7, 2024);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * double(rng.uniform()); };
  TriMesh mesh;
  for (int t = 0; t < 250; ++t) {
    const Vec3 center(uniform(-0.8, 0.8), uniform(-0.8, 0.8), uniform(-0.8, 0.8));
    for (int k = 0; k < 3; ++k) {
      mesh.indices.push_back(uint32_t(mesh.positions.size()));
      mesh.positions.push_back(center + Vec3(uniform(-0.4, 0.4), uniform(-0.4, 0.4), uniform(-0.4, 0.4)));
      mesh.normals.push_back(glm::normalize(Vec3(uniform(-1, 1), uniform(-1, 1), uniform(0.2, 1))));
      mesh.colors.emplace_back(uniform(0, 1), uniform(0, 1), uniform(0, 1));
    }
  }
  return mesh;
}

// ---- Scenes: a mesh, a camera, an image size ---------------------------------------------------------------------

struct Scene {
  std::string name;
  TriMesh mesh;
  int width, height;
  Mat4 projection, model_view;
};

std::vector<Scene> scenes() {
  const Vec3 up(0, 1, 0);
  std::vector<Scene> s;
  s.push_back({"sphere_perspective", sphere(), 320, 240, persp(45, 320, 240, 0.5, 10),
               look_at({0.3, 0.5, 3.2}, {0, 0, 0}, up) * rotate_y(0.3)});
  s.push_back(
      {"sphere_ortho", sphere(), 257, 211, ortho(-1.5, 1.5, -1.2, 1.3, 0.1, 10), look_at({1, 2, 3}, {0, 0, 0}, up)});
  s.push_back({"torus_oblique", torus(), 320, 240, persp(60, 320, 240, 0.5, 10),
               look_at({2.0, -1.6, 1.8}, {0, 0, 0}, up) * rotate_x(0.4)});
  s.push_back({"cube_perspective", faceted_cube(), 300, 300, persp(50, 300, 300, 1, 10),
               look_at({2.2, 1.7, 2.8}, {0, 0, 0}, up) * rotate_y(0.2)});
  s.push_back({"cube_ortho", faceted_cube(), 240, 200, ortho(-2.4, 2.2, -1.9, 2.0, 0.5, 8),
               look_at({-2, 1.2, 3}, {0, 0, 0}, up) * rotate_z(0.1)});
  s.push_back({"soup_perspective", triangle_soup(), 320, 240, persp(40, 320, 240, 1, 8),
               look_at({0.5, 0.8, 3.5}, {0, 0, 0}, up)});
  s.push_back({"soup_ortho", triangle_soup(), 301, 197, ortho(-1.4, 1.4, -1.0, 1.1, 0.2, 6),
               look_at({0, 0, 3}, {0, 0, 0}, up) * rotate_y(0.8)});
  // The near plane (1.0 in front of an eye 1.45 from the center) cuts the unit sphere: the front cap is clipped
  // away and the inside shows through.
  s.push_back({"sphere_near_plane", sphere(), 320, 240, persp(70, 320, 240, 1.0, 10),
               look_at({0.0, 0.2, 1.45}, {0, 0, 0}, up)});
  // The torus fills more than the view: its triangles cross all four screen edges (and the near plane).
  s.push_back({"torus_screen_edges", torus(), 320, 240, persp(50, 320, 240, 0.3, 10),
               look_at({0.9, 0.5, 1.6}, {0.7, 0.1, 0}, up)});
  s.push_back({"cube_screen_edges_ortho", faceted_cube(), 200, 160, ortho(-0.7, 0.5, -0.4, 0.6, 0.5, 8),
               look_at({1.5, 1.0, 3}, {0, 0, 0}, up)});
  return s;
}

// ---- Both renderers from one description ---------------------------------------------------------------------------

struct DrawSetup {
  bool lit = false;
  bool flat = false;  // GL_FLAT / ShadingModel::flat
  bool cull_back = false;
  bool point_light = false;
  bool vertex_colors = false;  // unlit: the mesh's per-vertex colors, else one flat color
  bool immediate = false;      // glBegin/glEnd and Context::begin/vertex/end instead of arrays
};

const Vec3f kFlatColor{0.9f, 0.6f, 0.3f};

GlState gl_state(const Scene& scene, const DrawSetup& setup) {
  GlState s;
  s.projection = Mat4f(scene.projection);
  s.modelview = Mat4f(scene.model_view);
  s.lighting = setup.lit;
  s.light.position = setup.point_light ? Vec4f(1.5f, 2.0f, 1.0f, 1.0f) : Vec4f(0.35f, 0.6f, 0.8f, 0.0f);
  s.light.ambient = {0.1f, 0.1f, 0.1f, 1};
  s.light.diffuse = {0.9f, 0.85f, 0.8f, 1};
  s.light.specular = {1, 1, 1, 1};
  s.material.ambient = {0.3f, 0.4f, 0.8f, 1};
  s.material.diffuse = {0.3f, 0.5f, 0.9f, 1};
  s.material.specular = {0.5f, 0.5f, 0.5f, 1};
  s.material.emission = {0.02f, 0.0f, 0.03f, 1};
  s.material.shininess = 24;
  s.smooth = !setup.flat;
  s.cull_back = setup.cull_back;
  s.color = kFlatColor;
  s.background = kBackground;
  return s;
}

// The mesh as the setup draws it: normals only when lit, colors only for unlit vertex colors.
TriMesh mesh_for(const Scene& scene, const DrawSetup& setup) {
  TriMesh mesh = scene.mesh;
  if (!setup.lit) mesh.normals.clear();
  if (setup.lit || !setup.vertex_colors) mesh.colors.clear();
  mesh.uvs.clear();
  return mesh;
}

GlFrame render_gl(const Scene& scene, const DrawSetup& setup) {
  return reference::render_osmesa(mesh_for(scene, setup), scene.width, scene.height, gl_state(scene, setup),
                                  setup.immediate ? GlSubmit::immediate : GlSubmit::vertex_arrays);
}

// Tessera with the same state: matrices loaded as OpenGL's, the light set under an identity model-view (eye space).
raster3d::Framebuffer render_tessera(const Scene& scene, const DrawSetup& setup) {
  const GlState gl = gl_state(scene, setup);
  const TriMesh mesh = mesh_for(scene, setup);
  raster3d::Context ctx(scene.width, scene.height);
  ctx.clear(kBackground);
  ctx.matrix_mode(raster3d::MatrixMode::projection);
  ctx.load_matrix(scene.projection);
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  ctx.load_identity();
  ctx.light(0, raster3d::Light{gl.light.position, Vec3f(gl.light.ambient), Vec3f(gl.light.diffuse),
                               Vec3f(gl.light.specular)});
  ctx.material(raster3d::Material{Vec3f(gl.material.ambient), Vec3f(gl.material.diffuse), Vec3f(gl.material.specular),
                                  Vec3f(gl.material.emission), gl.material.shininess});
  ctx.shading(!setup.lit   ? raster3d::ShadingModel::unlit
              : setup.flat ? raster3d::ShadingModel::flat
                           : raster3d::ShadingModel::gouraud);
  ctx.cull(setup.cull_back ? raster3d::CullMode::back : raster3d::CullMode::none);
  ctx.color(kFlatColor);
  ctx.load_matrix(scene.model_view);
  if (setup.immediate) {
    ctx.begin(raster3d::Primitive::triangles);
    for (const uint32_t i : mesh.indices) {
      if (!mesh.normals.empty()) ctx.normal(Vec3f(mesh.normals[i]));
      if (!mesh.colors.empty()) ctx.color(Vec3f(mesh.colors[i]));
      const Vec3& p = mesh.positions[i];
      ctx.vertex(p.x, p.y, p.z);
    }
    ctx.end();
  } else {
    ctx.draw(mesh);
  }
  return std::move(ctx.framebuffer());
}

// ---- Comparison ------------------------------------------------------------------------------------------------

constexpr uint32_t kDepthTolerance = 2;  // units of 2^-24, for the pixels whose depth is not bit-identical

struct Comparison {
  size_t covered = 0;           // pixels covered by either renderer
  size_t coverage_diff = 0;     // covered by one only
  size_t depth_exact_diff = 0;  // covered by both, any difference in the 24-bit depth
  size_t depth_diff = 0;        // covered by both, depth differs by more than kDepthTolerance
  size_t color_diff = 0;        // covered by either, some channel beyond the tolerance (coverage differences count)
  uint32_t max_depth_diff = 0;
  int max_color_diff = 0;
  std::string example;       // the first differing pixel, both renderers' values
  std::string diff_picture;  // written when something differs

  // Same coverage and bit-identical depth.
  double coverage_depth_match() const { return 1.0 - double(coverage_diff + depth_exact_diff) / double(covered); }
  double color_match() const { return 1.0 - double(color_diff) / double(covered); }
};

Comparison compare(const raster3d::Framebuffer& t, const GlFrame& g, int tolerance, const std::string& name) {
  EXPECT_EQ(t.width(), g.width);
  EXPECT_EQ(t.height(), g.height);
  Comparison c;
  ImageRGB diff(g.width, g.height);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const bool in_t = t.depth()(x, y) < raster3d::kDepthMax, in_g = g.depth_at(x, y) < raster3d::kDepthMax;
      if (!in_t && !in_g) continue;
      ++c.covered;
      int worst = 0;
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(int(t.color()(x, y)[k]) - int(g.channel(x, y, k))));
      Vec3f d(0.0f);
      const uint32_t dt = t.depth()(x, y), dg = g.depth_at(x, y);
      if (in_t && in_g) {
        c.max_depth_diff = std::max(c.max_depth_diff, dt > dg ? dt - dg : dg - dt);
        c.max_color_diff = std::max(c.max_color_diff, worst);
      }
      if (c.example.empty() &&
          (in_t != in_g || (in_t && (dt > dg ? dt - dg : dg - dt) > kDepthTolerance) || worst > tolerance))
        c.example = fmt::format("pixel ({}, {}): tessera depth {} rgb {},{},{}; OpenGL depth {} rgb {},{},{}", x, y, dt,
                                t.color()(x, y).x, t.color()(x, y).y, t.color()(x, y).z, dg, g.channel(x, y, 0),
                                g.channel(x, y, 1), g.channel(x, y, 2));
      if (in_t != in_g) {
        ++c.coverage_diff;
        d = in_t ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0);
      } else if (dt != dg) {
        ++c.depth_exact_diff;
        if ((dt > dg ? dt - dg : dg - dt) > kDepthTolerance) {
          ++c.depth_diff;
          d = Vec3f(0, 0, 1);
        }
      }
      if (in_t != in_g || worst > tolerance) {
        ++c.color_diff;
        if (in_t == in_g) d += Vec3f(1, 1, 0);
      }
      diff(x, y) = d;
    }
  if (c.coverage_diff + c.depth_diff + c.color_diff > 0) {
    c.diff_picture = ::testing::TempDir() + "osmesa_" + name + "_diff.png";
    write_image(c.diff_picture, diff);
  }
  return c;
}

std::string describe(const Comparison& c) {
  return fmt::format(
      "covered {} px: coverage differs on {}, depth on {} ({} beyond {} units, by up to {}), color on {} (by up "
      "to {}/255); first: {}; diff picture: {}",
      c.covered, c.coverage_diff, c.depth_exact_diff, c.depth_diff, kDepthTolerance, c.max_depth_diff, c.color_diff,
      c.max_color_diff, c.example.empty() ? "none" : c.example, c.diff_picture.empty() ? "none" : c.diff_picture);
}

void PrintTo(const Scene& scene, std::ostream* out) { *out << scene.name; }

class OsmesaCompare : public ::testing::TestWithParam<Scene> {};

// Unlit, one flat color: coverage and depth as OpenGL's on >= 99.9% of the covered pixels, and the same color there;
// with and without culling.
TEST_P(OsmesaCompare, UnlitCoverageAndDepth) {
  const Scene& scene = GetParam();
  for (const bool cull : {false, true}) {
    const DrawSetup setup{.cull_back = cull};
    const Comparison c = compare(render_tessera(scene, setup), render_gl(scene, setup), 0,
                                 scene.name + (cull ? "_unlit_cull" : "_unlit"));
    SCOPED_TRACE(fmt::format("cull back: {}", cull));
    if (!cull) {  // (culled, the near-plane scene shows nothing: only the inside of the sphere is in view)
      ASSERT_GT(c.covered, size_t(scene.width * scene.height / 20)) << "the scene should cover a good part of the view";
    }
    if (c.covered == 0) continue;
    fmt::print("{} (cull {}): depth bit-identical on {:.1f}% of {} px, max difference {} units of 2^-24\n", scene.name,
               cull, 100.0 * double(c.covered - c.coverage_diff - c.depth_exact_diff) / double(c.covered), c.covered,
               c.max_depth_diff);
    EXPECT_GE(c.coverage_depth_match(), 0.999) << describe(c);
    EXPECT_EQ(c.depth_diff, 0u) << describe(c);
    EXPECT_GE(c.color_match(), 0.999) << describe(c);
  }
}

// Lit Gouraud with the fixed-function equation (directional and point light, specular, emission): within 2/255 per
// channel on >= 99% of the covered pixels.
TEST_P(OsmesaCompare, LitGouraud) {
  const Scene& scene = GetParam();
  for (const bool point : {false, true}) {
    const DrawSetup setup{.lit = true, .point_light = point};
    const Comparison c = compare(render_tessera(scene, setup), render_gl(scene, setup), 2,
                                 scene.name + (point ? "_gouraud_point" : "_gouraud_directional"));
    SCOPED_TRACE(fmt::format("point light: {}", point));
    EXPECT_GE(c.color_match(), 0.99) << describe(c);
    EXPECT_GE(c.coverage_depth_match(), 0.999) << describe(c);
  }
}

// The flat shade model: each triangle takes the lit color of its last vertex (OpenGL's provoking vertex).
TEST_P(OsmesaCompare, LitFlatShadeModel) {
  const Scene& scene = GetParam();
  const DrawSetup setup{.lit = true, .flat = true};
  const Comparison c = compare(render_tessera(scene, setup), render_gl(scene, setup), 2, scene.name + "_flat");
  EXPECT_GE(c.color_match(), 0.99) << describe(c);
}

INSTANTIATE_TEST_SUITE_P(Scenes, OsmesaCompare, ::testing::ValuesIn(scenes()),
                         [](const ::testing::TestParamInfo<Scene>& param) { return param.param.name; });

Scene scene_named(const std::string& name) {
  for (Scene& s : scenes())
    if (s.name == name) return std::move(s);
  throw std::runtime_error("no scene " + name);
}

// Per-vertex colors interpolated without lighting: perspective-correct interpolation against OpenGL's.
TEST(OsmesaCompareColors, VertexColorsInterpolatePerspectiveCorrectly) {
  for (const char* name : {"soup_perspective", "soup_ortho"}) {
    const Scene scene = scene_named(name);
    const DrawSetup setup{.vertex_colors = true};
    const Comparison c =
        compare(render_tessera(scene, setup), render_gl(scene, setup), 2, scene.name + "_vertex_colors");
    SCOPED_TRACE(name);
    EXPECT_GE(c.color_match(), 0.99) << describe(c);
    EXPECT_GE(c.coverage_depth_match(), 0.999) << describe(c);
  }
}

// Immediate mode on both sides (glBegin/glEnd against Context::begin/vertex/end): the same pictures as the arrays.
TEST(OsmesaCompareImmediate, ImmediateModeMatchesOpenGLImmediateMode) {
  for (const char* name : {"torus_screen_edges", "cube_perspective"}) {
    const Scene scene = scene_named(name);
    const DrawSetup setup{.lit = true, .immediate = true};
    const Comparison c = compare(render_tessera(scene, setup), render_gl(scene, setup), 2, scene.name + "_immediate");
    SCOPED_TRACE(name);
    EXPECT_GE(c.color_match(), 0.99) << describe(c);
    EXPECT_GE(c.coverage_depth_match(), 0.999) << describe(c);
  }
}

// Texture mapping against OpenGL's GL_TEXTURE_2D with GL_REPLACE: a floor in perspective whose texture repeats 4
// times, a 32 x 32 texture of random colors. Nearest texels (perspective-correct interpolation and texel selection),
// bilinear, and trilinear MIPmaps (OpenGL builds its own pyramid and takes the level of detail from 2 x 2 pixel
// differences; Tessera from the exact derivatives: nearly the same levels, so a looser tolerance).
TEST(OsmesaCompareTextures, TextureMappingMatchesOpenGL) {
  const int w = 160, h = 120, n = 32;
  Rng rng(17);
  reference::GlTexture gl_texture{n, n, std::vector<uint8_t>(size_t(n) * n * 4, 255), reference::GlFilter::nearest};
  ImageRGBA image(n, n);
  for (int j = 0; j < n; ++j)  // GL rows bottom first; image rows top first
    for (int i = 0; i < n; ++i) {
      uint8_t* texel = &gl_texture.rgba[(size_t(j) * n + i) * 4];
      for (int k = 0; k < 3; ++k) texel[k] = uint8_t(rng.next_u32() >> 24);
      image(i, n - 1 - j) = Vec4f(texel[0] / 255.0f, texel[1] / 255.0f, texel[2] / 255.0f, 1.0f);
    }
  TriMesh floor;
  floor.positions = {{-3, 0, -6}, {3, 0, -6}, {3, 0, 1}, {-3, 0, 1}};
  floor.uvs = {{0, 4}, {4, 4}, {4, 0}, {0, 0}};
  floor.indices = {0, 2, 1, 0, 3, 2};
  const Mat4 projection = persp(50, w, h, 0.5, 30), view = look_at({0.4, 1.4, 2.6}, {0, 0, -2}, {0, 1, 0});
  GlState state;
  state.projection = Mat4f(projection);
  state.modelview = Mat4f(view);
  state.background = kBackground;
  state.texture = &gl_texture;

  raster3d::VertexArrays arrays = raster3d::VertexArrays::from_mesh(floor);
  arrays.normals.assign(4, Vec3f(0, 1, 0));
  struct Case {
    reference::GlFilter gl;
    Filter filter;
    int tolerance;
    double share;
  };
  // Measured: nearest identical on every pixel, bilinear within 2/255, trilinear within 10/255 (Mesa 22.3), for float
  // texels and for 8-bit ones (Mesa's own storage; its 8-bit MIPmap levels are rounded differently, 9/255 measured).
  for (const Case& k : {Case{reference::GlFilter::nearest, Filter::nearest, 0, 0.999},
                        Case{reference::GlFilter::linear, Filter::bilinear, 2, 0.999},
                        Case{reference::GlFilter::linear_mipmap_linear, Filter::trilinear, 12, 0.99}}) {
    for (const bool eight_bit : {false, true}) {
      gl_texture.filter = k.gl;  // Mesa's texture is 8-bit either way
      const GlFrame gl = reference::render_osmesa(floor, w, h, state);
      const Texture2D texture = eight_bit ? Texture2D(to_rgba8(image), Sampler{.filter = k.filter})
                                          : Texture2D(image, Sampler{.filter = k.filter});
      raster3d::SurfaceUniforms u;
      u.set_camera(projection, view);
      u.model_view_projection = raster3d::gl_matrix_product(Mat4f(projection), Mat4f(view));  // as OpenGL forms it
      u.lighting = raster3d::PreparedLighting(raster3d::unlit_lighting());  // the texel, as GL_REPLACE
      u.maps.texture = &texture;
      raster3d::Framebuffer fb(w, h);
      fb.clear(kBackground);
      raster3d::draw_surface(fb, raster3d::RasterState{}, arrays, u);
      const std::string name = fmt::format("texture_{}{}", int(k.gl), eight_bit ? "_rgba8" : "");
      const Comparison c = compare(fb, gl, k.tolerance, name);
      SCOPED_TRACE(fmt::format("filter {}, {}", int(k.gl), eight_bit ? "rgba8" : "rgba32f"));
      EXPECT_GE(c.coverage_depth_match(), 0.999) << describe(c);
      EXPECT_GE(c.color_match(), k.share) << describe(c);
      fmt::print("texture filter {} {}: {}\n", int(k.gl), eight_bit ? "rgba8" : "rgba32f", describe(c));
    }
  }
}

// The reference itself: a triangle in the upper half of the view lands in the top rows of the frame (the read-back
// flips GL's bottom-up rows), at the window depth of its plane; both submission paths draw the same pixels.
TEST(OsmesaReference, FrameIsTopRowFirstWithTheExpectedDepth) {
  TriMesh triangle;
  triangle.positions = {{-0.5, 0.2, 0.5}, {0.5, 0.2, 0.5}, {0.0, 0.9, 0.5}};  // NDC, identity matrices
  triangle.indices = {0, 1, 2};
  const GlState state;
  const GlFrame immediate = reference::render_osmesa(triangle, 40, 40, state, GlSubmit::immediate);
  const GlFrame arrays = reference::render_osmesa(triangle, 40, 40, state, GlSubmit::vertex_arrays);
  EXPECT_EQ(immediate.rgb, arrays.rgb);
  EXPECT_EQ(immediate.depth, arrays.depth);
  // Column 20 (x_ndc = 0.025) crosses the triangle for window y in [24, 37.3): GL rows 24..36 (centers inside),
  // image rows 39 - 36 = 3 .. 39 - 24 = 15 from the top. z_ndc = 0.5 is window depth 0.75.
  for (int y = 0; y < 40; ++y) {
    const bool covered = immediate.depth_at(20, y) < raster3d::kDepthMax;
    EXPECT_EQ(covered, y >= 3 && y <= 15) << "row " << y;
    if (covered) {
      EXPECT_EQ(immediate.depth_at(20, y), raster3d::depth_to_unorm24(0.75)) << "row " << y;
    }
  }
}

// The vector loops (AVX2/AVX-512, picked at run time) give the same frame as the baseline loops.
TEST(OsmesaCompareThreads, InstructionSetsGiveTheSameFrame) {
  for (const bool lit : {false, true}) {
    const Scene scene = scene_named(lit ? "torus_screen_edges" : "soup_perspective");
    const DrawSetup setup{.lit = lit, .vertex_colors = !lit};
    const raster3d::Framebuffer widest = render_tessera(scene, setup);
    for (const int cap : {1, 0}) {  // AVX2, the baseline
      raster3d::detail::span_isa_cap() = cap;
      const raster3d::Framebuffer narrower = render_tessera(scene, setup);
      raster3d::detail::span_isa_cap() = -1;
      EXPECT_TRUE(std::ranges::equal(widest.color().pixels(), narrower.color().pixels())) << scene.name << cap;
      EXPECT_TRUE(std::ranges::equal(widest.depth().pixels(), narrower.depth().pixels())) << scene.name << cap;
    }
  }
}

// The comparison does not depend on Tessera's thread count (binning to tiles in parallel is deterministic).
TEST(OsmesaCompareThreads, OneAndTwoThreadsGiveTheSameFrame) {
  const Scene scene = scene_named("torus_screen_edges");
  const DrawSetup setup{.lit = true};
  raster3d::Framebuffer one = [&] {
    const ThreadLimit limit(1);
    return render_tessera(scene, setup);
  }();
  raster3d::Framebuffer two = [&] {
    const ThreadLimit limit(2);
    return render_tessera(scene, setup);
  }();
  EXPECT_TRUE(std::ranges::equal(one.color().pixels(), two.color().pixels()));
  EXPECT_TRUE(std::ranges::equal(one.depth().pixels(), two.depth().pixels()));
}

}  // namespace
}  // namespace tessera
