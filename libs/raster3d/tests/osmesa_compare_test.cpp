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
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

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

Mat4 persp(double fovy_degrees, int w, int h, double n, double f) {
  return perspective(radians(fovy_degrees), double(w) / double(h), n, f);
}

std::vector<Scene> scenes() {
  const Vec3 up(0, 1, 0);
  std::vector<Scene> s;
  s.push_back({"sphere_perspective", sphere(), 320, 240, persp(45, 320, 240, 0.5, 10),
               look_at({0.3, 0.5, 3.2}, {0, 0, 0}, up) * rotate_y(0.3)});
  s.push_back({"sphere_ortho", sphere(), 257, 211, ortho(-1.5, 1.5, -1.2, 1.3, 0.1, 10),
               look_at({1, 2, 3}, {0, 0, 0}, up)});
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
  bool flat = false;       // GL_FLAT / ShadingModel::flat
  bool cull_back = false;
  bool point_light = false;
  bool vertex_colors = false;  // unlit: the mesh's per-vertex colors, else one flat color
  bool immediate = false;      // glBegin/glEnd and Context::begin/vertex/end instead of arrays
};

const Vec3f kBackground{0.1f, 0.15f, 0.2f};
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
                                   setup.immediate ? GlSubmit::Immediate : GlSubmit::VertexArrays);
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
  ctx.shading(!setup.lit ? raster3d::ShadingModel::unlit
                         : setup.flat ? raster3d::ShadingModel::flat : raster3d::ShadingModel::gouraud);
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
  size_t covered = 0;         // pixels covered by either renderer
  size_t coverage_diff = 0;   // covered by one only
  size_t depth_exact_diff = 0;  // covered by both, any difference in the 24-bit depth
  size_t depth_diff = 0;      // covered by both, depth differs by more than kDepthTolerance
  size_t color_diff = 0;      // covered by either, some channel beyond the tolerance (coverage differences count)
  uint32_t max_depth_diff = 0;
  int max_color_diff = 0;
  std::string example;        // the first differing pixel, both renderers' values
  std::string diff_picture;   // written when something differs

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
      if (c.example.empty() && (in_t != in_g || (in_t && (dt > dg ? dt - dg : dg - dt) > kDepthTolerance) ||
                                worst > tolerance))
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
      c.max_color_diff,
      c.example.empty() ? "none" : c.example,
      c.diff_picture.empty() ? "none" : c.diff_picture);
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
  // Measured: nearest identical on every pixel, bilinear within 2/255, trilinear within 10/255 (Mesa 22.3).
  for (const Case& k : {Case{reference::GlFilter::nearest, Filter::nearest, 0, 0.999},
                        Case{reference::GlFilter::linear, Filter::bilinear, 2, 0.999},
                        Case{reference::GlFilter::linear_mipmap_linear, Filter::trilinear, 12, 0.99}}) {
    gl_texture.filter = k.gl;
    const GlFrame gl = reference::render_osmesa(floor, w, h, state);
    const Texture2D texture(image, Sampler{.filter = k.filter});
    raster3d::SurfaceUniforms u;
    u.set_camera(projection, view);
    u.model_view_projection = raster3d::gl_matrix_product(Mat4f(projection), Mat4f(view));  // as OpenGL forms it
    u.lighting = raster3d::PreparedLighting(raster3d::unlit_lighting());  // the texel, as GL_REPLACE
    u.maps.texture = &texture;
    raster3d::Framebuffer fb(w, h);
    fb.clear(kBackground);
    raster3d::draw_surface(fb, raster3d::RasterState{}, arrays, u);
    const Comparison c = compare(fb, gl, k.tolerance, fmt::format("texture_{}", int(k.gl)));
    SCOPED_TRACE(int(k.gl));
    EXPECT_GE(c.coverage_depth_match(), 0.999) << describe(c);
    EXPECT_GE(c.color_match(), k.share) << describe(c);
    fmt::print("texture filter {}: {}\n", int(k.gl), describe(c));
  }
}

// The reference itself: a triangle in the upper half of the view lands in the top rows of the frame (the read-back
// flips GL's bottom-up rows), at the window depth of its plane; both submission paths draw the same pixels.
TEST(OsmesaReference, FrameIsTopRowFirstWithTheExpectedDepth) {
  TriMesh triangle;
  triangle.positions = {{-0.5, 0.2, 0.5}, {0.5, 0.2, 0.5}, {0.0, 0.9, 0.5}};  // NDC, identity matrices
  triangle.indices = {0, 1, 2};
  const GlState state;
  const GlFrame immediate = reference::render_osmesa(triangle, 40, 40, state, GlSubmit::Immediate);
  const GlFrame arrays = reference::render_osmesa(triangle, 40, 40, state, GlSubmit::VertexArrays);
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

// ---- The stencil buffer ------------------------------------------------------------------------------------------
//
// Sequences of draws, each with its own RasterState (depth and stencil tests, two-sided stencil operations, write
// masks) and one unlit color, drawn by Tessera's draw_triangles and by OpenGL with the same state
// (glStencilFuncSeparate, glStencilOpSeparate, glStencilMaskSeparate, glDepthFunc, glDepthMask, glColorMask): the
// stencil, color and depth buffers must come out the same on every pixel.

// raster3d's comparison and stencil enumerations list OpenGL's in the same order as the reference's.
static_assert(int(raster3d::DepthFunc::always) == int(reference::GlCompare::always) &&
              int(raster3d::DepthFunc::notequal) == int(reference::GlCompare::notequal));
static_assert(int(raster3d::StencilOp::invert) == int(reference::GlStencilOp::invert) &&
              int(raster3d::StencilOp::incr_wrap) == int(reference::GlStencilOp::incr_wrap));

reference::GlStencilFace gl_stencil_face(const raster3d::StencilFace& f) {
  return {reference::GlCompare(int(f.func)), f.ref, f.mask, f.write_mask, reference::GlStencilOp(int(f.fail)),
          reference::GlStencilOp(int(f.zfail)), reference::GlStencilOp(int(f.zpass))};
}

// One draw: triangles (counterclockwise = front), their unlit color and alpha, the rasterizer state.
struct FlatDraw {
  TriMesh mesh;
  Vec3f color{1, 1, 1};
  raster3d::RasterState state;
  float alpha = 1;
};

// Both renderers start from color kBackground, depth 1 and stencil `clear_stencil`.
raster3d::Framebuffer draw_tessera_flat(int width, int height, const Mat4& projection, const Mat4& view,
                                           uint8_t clear_stencil, const std::vector<FlatDraw>& draws) {
  raster3d::Framebuffer fb(width, height);
  fb.clear(kBackground);
  fb.clear_stencil(clear_stencil);
  const Mat4f mvp = raster3d::gl_matrix_product(Mat4f(projection), Mat4f(view));
  for (const FlatDraw& d : draws) {
    std::vector<Vec3f> positions;
    for (const Vec3& p : d.mesh.positions) positions.emplace_back(p);
    raster3d::draw_triangles(fb, d.state, uint32_t(positions.size()), d.mesh.indices,
                             raster3d::testing::FlatVertexShader{positions.data(), mvp},
                             raster3d::Translucent<raster3d::testing::FlatFragmentShader>{{d.color}, d.alpha});
  }
  return fb;
}

GlFrame draw_gl_flat(int width, int height, const Mat4& projection, const Mat4& view, uint8_t clear_stencil,
                        const std::vector<FlatDraw>& draws) {
  reference::OsmesaContext gl(width, height);
  for (size_t k = 0; k < draws.size(); ++k) {
    const raster3d::RasterState& r = draws[k].state;
    GlState s;
    s.projection = Mat4f(projection);
    s.modelview = Mat4f(view);
    s.depth_test = r.depth_test;
    s.depth_func = reference::GlCompare(int(r.depth_func));
    s.depth_write = r.depth_write;
    s.color_write = r.color_write;
    s.stencil_test = r.stencil_test;
    s.stencil_front = gl_stencil_face(r.stencil_front);
    s.stencil_back = gl_stencil_face(r.stencil_back);
    s.color = draws[k].color;
    s.alpha = draws[k].alpha;
    s.blend = r.blend;
    s.blend_src = reference::GlBlendFactor(int(r.blend_function.src));
    s.blend_dst = reference::GlBlendFactor(int(r.blend_function.dst));
    s.blend_equation = reference::GlBlendEquation(int(r.blend_function.equation));
    s.background = kBackground;
    s.clear_stencil = clear_stencil;
    s.clear = k == 0;
    gl.begin(s);
    gl.draw(reference::GlMesh(draws[k].mesh), GlSubmit::VertexArrays);
  }
  return gl.read();
}

struct BufferComparison {
  size_t stencil_diff = 0, color_diff = 0, depth_diff = 0, alpha_diff = 0;
  std::string example;  // the first differing pixel
};

BufferComparison compare_buffers(const raster3d::Framebuffer& t, const GlFrame& g) {
  BufferComparison c;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const uint8_t st = t.stencil()(x, y), sg = g.stencil_at(x, y);
      const glm::u8vec4 ct = t.color()(x, y);
      const bool color_same = ct.x == g.channel(x, y, 0) && ct.y == g.channel(x, y, 1) && ct.z == g.channel(x, y, 2);
      const bool depth_same = t.depth()(x, y) == g.depth_at(x, y);
      c.stencil_diff += st != sg;
      c.color_diff += !color_same;
      c.depth_diff += !depth_same;
      c.alpha_diff += ct.w != g.alpha_at(x, y);
      if (c.example.empty() && (st != sg || !color_same || !depth_same || ct.w != g.alpha_at(x, y)))
        c.example = fmt::format(
            "pixel ({}, {}): tessera stencil {} rgba {},{},{},{} depth {}; OpenGL stencil {} rgba {},{},{},{} depth {}",
            x, y, st, ct.x, ct.y, ct.z, ct.w, t.depth()(x, y), sg, g.channel(x, y, 0), g.channel(x, y, 1),
            g.channel(x, y, 2), g.alpha_at(x, y), g.depth_at(x, y));
    }
  return c;
}

std::string describe(const BufferComparison& c) {
  return fmt::format("stencil differs on {} px, color on {}, alpha on {}, depth on {}; first: {}", c.stencil_diff,
                     c.color_diff, c.alpha_diff, c.depth_diff, c.example.empty() ? "none" : c.example);
}

// A closed mesh made consistently outward (counterclockwise seen from outside): flipped when its signed volume is
// negative.
TriMesh outward(TriMesh mesh) {
  double volume = 0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    volume += glm::dot(mesh.positions[mesh.indices[3 * t]],
                       glm::cross(mesh.positions[mesh.indices[3 * t + 1]], mesh.positions[mesh.indices[3 * t + 2]]));
  if (volume < 0)
    for (size_t t = 0; t < mesh.triangle_count(); ++t) std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
  return mesh;
}

// The box [-1, 1]^3 through `m`.
TriMesh box_volume(const Mat4& m) {
  TriMesh mesh = to_tri_mesh(make_box());
  for (Vec3& p : mesh.positions) p = Vec3(m * Vec4(p, 1));
  return outward(std::move(mesh));
}

TriMesh tetrahedron_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  TriMesh mesh;
  mesh.positions = {a, b, c, d};
  mesh.indices = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
  return outward(std::move(mesh));
}

// The shadow-volume pattern: an occluder scene with depth, then closed volumes counted into the stencil buffer (color
// and depth writes off, depth test less, both faces in one draw with their own operations), then the scene drawn
// again where the count is 0 (depth equal) and where it is not (depth lequal). `zfail`: Carmack's reverse (back faces
// incr_wrap, front faces decr_wrap where the depth test fails), else z-pass (front incr_wrap, back decr_wrap where it
// passes).
std::vector<FlatDraw> shadow_volume_draws(bool zfail) {
  Rng rng(11, 77);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * double(rng.uniform()); };
  std::vector<FlatDraw> occluders;
  {  // a floor, then random triangles over it
    FlatDraw floor{.color = {0.5f, 0.5f, 0.45f}};
    floor.mesh.positions = {{-5, -1.2, -5}, {5, -1.2, -5}, {5, -1.2, 4}, {-5, -1.2, 4}};
    floor.mesh.indices = {0, 2, 1, 0, 3, 2};
    occluders.push_back(std::move(floor));
  }
  for (int t = 0; t < 9; ++t) {
    FlatDraw d{.color = {float(uniform(0.2, 1)), float(uniform(0.2, 1)), float(uniform(0.2, 1))}};
    const Vec3 center(uniform(-2.2, 2.2), uniform(-1.0, 1.2), uniform(-2.0, 1.5));
    for (int k = 0; k < 3; ++k)
      d.mesh.positions.push_back(center + Vec3(uniform(-1.5, 1.5), uniform(-1.2, 1.2), uniform(-1.2, 1.2)));
    d.mesh.indices = {0, 1, 2};
    occluders.push_back(std::move(d));
  }
  std::vector<FlatDraw> draws = occluders;  // depth less, depth and color written, no stencil test

  FlatDraw volumes;
  volumes.state.color_write = false;
  volumes.state.depth_write = false;
  volumes.state.depth_func = raster3d::DepthFunc::less;
  volumes.state.stencil_test = true;
  if (zfail) {
    volumes.state.stencil_back.zfail = raster3d::StencilOp::incr_wrap;
    volumes.state.stencil_front.zfail = raster3d::StencilOp::decr_wrap;
  } else {
    volumes.state.stencil_front.zpass = raster3d::StencilOp::incr_wrap;
    volumes.state.stencil_back.zpass = raster3d::StencilOp::decr_wrap;
  }
  const auto add = [&](const TriMesh& m) {
    const auto base = uint32_t(volumes.mesh.positions.size());
    volumes.mesh.positions.insert(volumes.mesh.positions.end(), m.positions.begin(), m.positions.end());
    for (const uint32_t i : m.indices) volumes.mesh.indices.push_back(base + i);
  };
  // Tall boxes through the floor, the occluders and each other; two reach past the left and right edges of the view.
  add(box_volume(translate(-0.3, -0.6, 0.2) * rotate_y(0.5) * rotate_x(0.3) * scale(1.1, 1.7, 0.9)));
  add(box_volume(translate(0.6, -0.3, -0.4) * rotate_z(0.4) * rotate_y(-0.7) * scale(0.9, 1.9, 0.6)));
  add(box_volume(translate(-3.8, -0.8, -0.5) * rotate_y(0.2) * scale(1.5, 1.4, 1.2)));
  add(box_volume(translate(3.9, -0.5, 0.3) * rotate_x(-0.3) * scale(1.4, 1.0, 0.8)));
  for (int t = 0; t < 4; ++t) {  // random tetrahedra around the middle, most through the floor
    const Vec3 center(uniform(-1.8, 1.8), uniform(-1.2, 0.4), uniform(-1.5, 1.0));
    const auto corner = [&] { return center + Vec3(uniform(-1.3, 1.3), uniform(-1.3, 1.3), uniform(-1.3, 1.3)); };
    const Vec3 a = corner(), b = corner(), c = corner(), d = corner();
    add(tetrahedron_volume(a, b, c, d));
  }
  draws.push_back(std::move(volumes));

  // Lit where the count is 0 (the same triangles at the same depth: depth equal), shadowed where it is not.
  for (FlatDraw d : occluders) {
    d.color = d.color * 0.5f + 0.5f;
    d.state.depth_func = raster3d::DepthFunc::equal;
    d.state.depth_write = false;
    d.state.stencil_test = true;
    d.state.stencil_front.func = d.state.stencil_back.func = raster3d::DepthFunc::equal;
    draws.push_back(std::move(d));
  }
  for (FlatDraw d : occluders) {
    d.color *= 0.4f;
    d.state.depth_func = raster3d::DepthFunc::lequal;
    d.state.depth_write = false;
    d.state.stencil_test = true;
    d.state.stencil_front.func = d.state.stencil_back.func = raster3d::DepthFunc::notequal;
    draws.push_back(std::move(d));
  }
  return draws;
}

// Shadow-volume counts, z-fail and z-pass: OpenGL's stencil, color and depth buffers on every pixel.
TEST(OsmesaCompareStencil, StencilTwoSidedCountsMatchOpenGL) {
  const int w = 240, h = 180;
  const Mat4 projection = persp(50, w, h, 0.5, 20), view = look_at({1.2, 2.4, 6.0}, {0, -0.3, 0}, {0, 1, 0});
  for (const bool zfail : {true, false}) {
    SCOPED_TRACE(zfail ? "z-fail" : "z-pass");
    const std::vector<FlatDraw> draws = shadow_volume_draws(zfail);
    const raster3d::Framebuffer t = draw_tessera_flat(w, h, projection, view, 0, draws);
    const GlFrame g = draw_gl_flat(w, h, projection, view, 0, draws);
    // The counts are not trivial: overlapping volumes give 2 and more, and a good part of the view is in a volume.
    size_t inside = 0;
    int deepest = 0;
    for (const uint8_t v : g.stencil) {
      inside += v != 0;
      deepest = std::max(deepest, int(v));
    }
    EXPECT_GT(inside, size_t(w * h / 10));
    EXPECT_GE(deepest, 2);
    const BufferComparison c = compare_buffers(t, g);
    fmt::print("stencil volumes ({}): {} px inside, up to {} deep; {}\n", zfail ? "z-fail" : "z-pass", inside, deepest,
               describe(c));
    EXPECT_EQ(c.stencil_diff, 0u) << describe(c);
    EXPECT_EQ(c.color_diff, 0u) << describe(c);
    EXPECT_EQ(c.depth_diff, 0u) << describe(c);
  }
}

// Every stencil function, operation, reference, mask and write mask, both faces, on top of known values: 8 columns
// of initial values (0, 1, 127, 128, 254, 255 and two patterns, written by `replace`) over all but the bottom rows
// (which keep the clear value, 0 or 0x3c), each column half covered by a nearer occluder (the right half fails the
// depth test: zfail; the left passes it: zpass), crossed by 32 rows of quads with random state, three layers deep,
// some with the depth test off, some with color writes.
TEST(OsmesaCompareStencil, StencilOpsAndMasksMatchOpenGL) {
  const int w = 64, h = 96, columns = 8, rows = 32;
  const uint8_t initial[columns] = {0, 1, 127, 128, 254, 255, 0x5a, 0xa5};
  // An axis-aligned rectangle in NDC at window-aligned pixel edges, counterclockwise (front) or clockwise (back).
  const auto rect = [&](int x0, int x1, int y0, int y1, double z, bool front) {
    TriMesh m;
    const auto nx = [&](int x) { return -1.0 + 2.0 * x / w; };
    const auto ny = [&](int y) { return 1.0 - 2.0 * y / h; };  // image rows from the top
    m.positions = {{nx(x0), ny(y1), z}, {nx(x1), ny(y1), z}, {nx(x1), ny(y0), z}, {nx(x0), ny(y0), z}};
    m.indices = front ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
    return m;
  };
  std::vector<FlatDraw> draws;
  for (int k = 0; k < columns; ++k) {  // the initial values, and the occluder over each column's right half
    FlatDraw seed{.mesh = rect(k * 8, k * 8 + 8, 0, h - 12, 0.9, k % 2 == 0), .color = {0.2f, 0.2f, 0.2f}};
    seed.state.depth_test = false;
    seed.state.depth_write = false;
    seed.state.stencil_test = true;
    seed.state.stencil_front = seed.state.stencil_back = {.ref = initial[k], .zpass = raster3d::StencilOp::replace};
    draws.push_back(std::move(seed));
    draws.push_back({.mesh = rect(k * 8 + 4, k * 8 + 8, 0, h, -0.5, true), .color = {0.6f, 0.6f, 0.6f}});
  }
  Rng rng(5, 31);
  const auto pick = [&](int n) { return int(rng.next_u32() % uint32_t(n)); };
  const auto byte = [&] {  // often all bits, else a random byte
    return pick(3) == 0 ? uint8_t(0xff) : uint8_t(rng.next_u32() >> 24);
  };
  const auto random_face = [&] {
    raster3d::StencilFace f;
    f.func = raster3d::DepthFunc(pick(8));
    f.ref = uint8_t(rng.next_u32() >> 24);
    f.mask = byte();
    f.write_mask = byte();
    f.fail = raster3d::StencilOp(pick(8));
    f.zfail = raster3d::StencilOp(pick(8));
    f.zpass = raster3d::StencilOp(pick(8));
    return f;
  };
  for (int layer = 0; layer < 3; ++layer)
    for (int r = 0; r < rows; ++r) {
      FlatDraw d{.mesh = rect(0, w, r * 3, r * 3 + 3, 0.0, pick(2) == 0),
                    .color = {float(pick(256)) / 255.0f, float(pick(256)) / 255.0f, float(pick(256)) / 255.0f}};
      d.state.depth_test = pick(4) != 0;
      d.state.depth_write = false;
      d.state.color_write = pick(2) == 0;
      d.state.stencil_test = pick(8) != 0;
      d.state.stencil_front = random_face();
      d.state.stencil_back = random_face();
      draws.push_back(std::move(d));
    }
  // Every function and every operation in every role, on both faces, among the draws with the stencil test on.
  std::vector<int> used(2 * 4 * 8, 0);
  for (const FlatDraw& d : draws)
    if (d.state.stencil_test)
      for (const int face : {0, 1}) {
        const raster3d::StencilFace& f = face == 0 ? d.state.stencil_front : d.state.stencil_back;
        const int roles[4] = {int(f.func), int(f.fail), int(f.zfail), int(f.zpass)};
        for (int k = 0; k < 4; ++k) ++used[size_t((face * 4 + k) * 8 + roles[k])];
      }
  EXPECT_EQ(std::ranges::count(used, 0), 0);
  for (const uint8_t clear : {uint8_t(0), uint8_t(0x3c)}) {
    SCOPED_TRACE(int(clear));
    const Mat4 identity(1.0);
    const raster3d::Framebuffer t = draw_tessera_flat(w, h, identity, identity, clear, draws);
    const GlFrame g = draw_gl_flat(w, h, identity, identity, clear, draws);
    const BufferComparison c = compare_buffers(t, g);
    std::vector<bool> seen(256, false);
    for (const uint8_t v : g.stencil) seen[v] = true;
    const auto distinct = std::ranges::count(seen, true);
    fmt::print("stencil ops (clear {}): {} distinct values; {}\n", clear, distinct, describe(c));
    EXPECT_GE(distinct, 16);
    EXPECT_EQ(c.stencil_diff, 0u) << describe(c);
    EXPECT_EQ(c.color_diff, 0u) << describe(c);
    EXPECT_EQ(c.depth_diff, 0u) << describe(c);
  }
}

// ---- Blending against OpenGL's glBlendFunc / glBlendEquation
//
// 16 columns of flat colors with their own alpha (blending off) under 302 one-pixel rows, each drawn with one blend
// function over them: every equation with every pair of factors (min and max ignore the factors), random colors and
// alphas, and the exact values 0, 1/2 and 1 among them. Color and alpha must be OpenGL's on every pixel.
TEST(OsmesaCompareBlend, EveryBlendFunctionMatchesOpenGL) {
  const int columns = 16, w = columns * 4;
  std::vector<raster3d::BlendFunction> functions;
  for (int e = 0; e < 3; ++e)
    for (int src = 0; src < 10; ++src)
      for (int dst = 0; dst < 10; ++dst)
        functions.push_back({raster3d::BlendFactor(src), raster3d::BlendFactor(dst), raster3d::BlendEquation(e)});
  functions.push_back({.equation = raster3d::BlendEquation::min});
  functions.push_back({.equation = raster3d::BlendEquation::max});
  const int h = int(functions.size());
  const auto rect = [&](int x0, int x1, int y0, int y1) {  // NDC, pixel-aligned, counterclockwise
    TriMesh m;
    const auto nx = [&](int x) { return -1.0 + 2.0 * x / w; };
    const auto ny = [&](int y) { return 1.0 - 2.0 * y / h; };
    m.positions = {{nx(x0), ny(y1), 0.0}, {nx(x1), ny(y1), 0.0}, {nx(x1), ny(y0), 0.0}, {nx(x0), ny(y0), 0.0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
  };
  Rng rng(9, 17);
  const auto value = [&] {  // often exact (0, 1/2, 1), else any 8-bit value
    const uint32_t k = rng.next_u32() % 8;
    return k == 0 ? 0.0f : k == 1 ? 1.0f : k == 2 ? 0.5f : float(rng.next_u32() >> 24) / 255.0f;
  };
  std::vector<FlatDraw> draws;
  for (int k = 0; k < columns; ++k)
    draws.push_back({.mesh = rect(k * 4, k * 4 + 4, 0, h), .color = {value(), value(), value()}, .alpha = value()});
  for (int r = 0; r < h; ++r) {
    FlatDraw d{.mesh = rect(0, w, r, r + 1), .color = {value(), value(), value()}, .alpha = value()};
    d.state.depth_test = false;
    d.state.blend = true;
    d.state.blend_function = functions[size_t(r)];
    draws.push_back(std::move(d));
  }
  const Mat4 identity(1.0);
  const raster3d::Framebuffer t = draw_tessera_flat(w, h, identity, identity, 0, draws);
  const GlFrame g = draw_gl_flat(w, h, identity, identity, 0, draws);
  const BufferComparison c = compare_buffers(t, g);
  fmt::print("blending: {}\n", describe(c));
  EXPECT_EQ(c.color_diff, 0u) << describe(c);
  EXPECT_EQ(c.alpha_diff, 0u) << describe(c);
}

}  // namespace
}  // namespace tessera
