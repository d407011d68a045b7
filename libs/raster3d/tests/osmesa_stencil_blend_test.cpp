// raster3d's stencil buffer and blending against Mesa's (OSMesa, llvmpipe): sequences of draws with their depth,
// stencil and blend state drawn by both, every buffer compared pixel by pixel (the rest of the OSMesa comparisons:
// osmesa_compare_test.cpp).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "osmesa_compare.hpp"
#include "osmesa_renderer.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/pipeline.hpp"
#include "test_util.hpp"

namespace tessera {
namespace {

using osmesa_compare::kBackground;
using osmesa_compare::persp;
using reference::GlFrame;
using reference::GlState;
using reference::GlSubmit;

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
  return {reference::GlCompare(int(f.func)),
          f.ref,
          f.mask,
          f.write_mask,
          reference::GlStencilOp(int(f.fail)),
          reference::GlStencilOp(int(f.zfail)),
          reference::GlStencilOp(int(f.zpass))};
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
    gl.draw(reference::GlMesh(draws[k].mesh), GlSubmit::vertex_arrays);
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
