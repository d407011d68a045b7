// The lane shaders' vocabulary (lanes.hpp) against glm's scalar functions, lane by lane and bit for bit; lane
// shaders (lane_shader.hpp) on the quad stage against the same shaders per pixel through draw_triangles; texture()
// against Texture2D::sample at the quad's level of detail.
#include "tessera/raster3d/lane_shader.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tessera/core/parallel.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/lighting.hpp"
#include "tessera/raster3d/surface_shader.hpp"

namespace tessera::raster3d {
namespace {

using lanes::kWidth;

// A unit sphere's arrays with normals and latitude-longitude texture coordinates.
VertexArrays sphere_arrays(int slices, int stacks) {
  VertexArrays a = VertexArrays::from_mesh(to_tri_mesh(make_uv_sphere(slices, stacks)));
  a.normals.clear();
  a.uvs.clear();
  for (const Vec3f& p : a.positions) {
    a.normals.push_back(glm::normalize(p));
    a.uvs.emplace_back(0.5f + std::atan2(p.z, p.x) / 6.2831853f,
                       0.5f + std::asin(std::clamp(p.y, -1.0f, 1.0f)) / 3.1415927f);
  }
  return a;
}

lanes::Float random_lanes(Rng& rng, float lo, float hi) {
  lanes::Float f;
  for (int k = 0; k < kWidth; ++k) f.set_lane(k, lo + (hi - lo) * float(rng.uniform()));
  return f;
}

lanes::vec3 random_vec3(Rng& rng) {
  return {random_lanes(rng, -2, 2), random_lanes(rng, -2, 2), random_lanes(rng, -2, 2)};
}

// Bit equality of floats (NaN equal to NaN).
bool same(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(const Vec3f& a, const Vec3f& b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }

TEST(Lanes, VocabularyEqualsGlmLaneByLane) {
  Rng rng(5);
  int mismatches = 0;
  for (int round = 0; round < 200; ++round) {
    const lanes::vec3 a = random_vec3(rng), b = random_vec3(rng);
    const lanes::Float t = random_lanes(rng, 0, 1), s = random_lanes(rng, -3, 3);
    const lanes::vec3 n = normalize(a), r = reflect(a, n), c = cross(a, b), m = mix(a, b, t);
    const lanes::vec3 clamped = clamp(a, -0.5f, 0.75f), lo = min(a, b), hi = max(a, b);
    const lanes::vec3 chosen = select(s > lanes::Float(0.0f), a, b);
    const lanes::Float d = dot(a, b), len = length(a), p = pow(abs(s), t), sm = smoothstep(-1.0f, 1.0f, s);
    const Mat3f matrix(random_vec3(rng).lane(0), random_vec3(rng).lane(1), random_vec3(rng).lane(2));
    const lanes::vec3 transformed = matrix * a;
    for (int k = 0; k < kWidth; ++k) {
      const Vec3f ak = a.lane(k), bk = b.lane(k);
      const float tk = t.lane(k), sk = s.lane(k);
      mismatches += !same(n.lane(k), glm::normalize(ak));
      mismatches += !same(r.lane(k), glm::reflect(ak, glm::normalize(ak)));
      mismatches += !same(c.lane(k), glm::cross(ak, bk));
      mismatches += !same(m.lane(k), glm::mix(ak, bk, tk));
      mismatches += !same(clamped.lane(k), glm::clamp(ak, -0.5f, 0.75f));
      mismatches += !same(lo.lane(k), glm::min(ak, bk)) + !same(hi.lane(k), glm::max(ak, bk));
      mismatches += !same(chosen.lane(k), sk > 0 ? ak : bk);
      mismatches += !same(d.lane(k), glm::dot(ak, bk)) + !same(len.lane(k), glm::length(ak));
      mismatches += !same(p.lane(k), std::pow(std::abs(sk), tk));
      mismatches += !same(sm.lane(k), glm::smoothstep(-1.0f, 1.0f, sk));
      mismatches += !same(transformed.lane(k), matrix * ak);
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(Lanes, MasksAndQuadDerivatives) {
  // Two quads, lanes 4q + (0, 1, 2, 3) at (x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1): f = 3 x + 5 y + q.
  lanes::Float f;
  for (int k = 0; k < kWidth; ++k) f.set_lane(k, float(3 * (k & 1) + 5 * ((k >> 1) & 1) + 10 * (k >> 2)));
  const lanes::Float dx = dFdx(f), dy = dFdy(f);
  for (int k = 0; k < kWidth; ++k) {
    EXPECT_EQ(dx.lane(k), 3.0f) << k;
    EXPECT_EQ(dy.lane(k), 5.0f) << k;
  }
  const lanes::Mask big = f > lanes::Float(9.0f);
  EXPECT_TRUE(any(big));
  EXPECT_FALSE(all(big));
  EXPECT_TRUE(all(big | !big));
  EXPECT_FALSE(any(big & !big));
  for (int k = 0; k < kWidth; ++k) EXPECT_EQ(big.lane(k), f.lane(k) > 9.0f) << k;
}

// A lit sphere in a Context's fixed-function state, drawn with the Phong shaders of lighting.hpp per pixel and as a
// lane shader, the way a user writes one.
struct PhongLanes {
  const FixedFunctionUniforms* uniforms = nullptr;
  lanes::vec3 operator()(const lanes::Fragment<PhongVaryings>& in, lanes::Mask& kept) const {
    const lanes::vec3 n = normalize(in(&PhongVaryings::normal));
    kept &= in.front_facing();  // the back faces are discarded (none is visible on a closed sphere)
    return uniforms->lighting.shade(n, in(&PhongVaryings::position), in(&PhongVaryings::color));
  }
};

FixedFunctionUniforms lit_uniforms(int width, int height, bool local_viewer, SpecularModel specular) {
  FixedFunctionUniforms u;
  const Mat4 projection = perspective(glm::radians(45.0), double(width) / height, 0.5, 20);
  const Mat4 view = look_at({0.3, 0.4, 3.2}, {0, 0, 0}, {0, 1, 0});
  u.model_view = Mat4f(view);
  u.model_view_projection = gl_matrix_product(Mat4f(projection), u.model_view);
  u.normal_matrix = Mat3f(normal_matrix(view));
  Lighting l;
  l.material = Material::plastic({0.8f, 0.3f, 0.2f}, 37, 0.8f);
  l.light_count = 3;
  l.lights[0].position = {0.5f, 1, 1, 0};
  l.lights[1].position = {-2, 1, 1, 1};  // a point light
  l.lights[1].diffuse = {0.3f, 0.4f, 0.9f};
  l.lights[2].position = {0, -1, 0.2f, 0};
  l.local_viewer = local_viewer;
  l.specular_model = specular;
  u.lighting = PreparedLighting(l);
  u.lit = true;
  return u;
}

TEST(LaneShader, PhongEqualsThePerPixelShaderBitForBit) {
  const VertexArrays sphere = sphere_arrays(48, 24);
  for (const bool local_viewer : {false, true})
    for (const SpecularModel specular : {SpecularModel::blinn, SpecularModel::phong})
      for (const int threads : {1, 2}) {
        ThreadLimit limit(threads);
        Framebuffer a(131, 97), b(131, 97);  // odd sizes: partial tiles and quads
        const FixedFunctionUniforms u = lit_uniforms(a.width(), a.height(), local_viewer, specular);
        const PhongVertexShader vs{sphere.attributes(), &u};
        const auto count = uint32_t(sphere.positions.size());
        draw_triangles(a, RasterState{}, count, sphere.indices, vs, PhongFragmentShader{&u});
        const DrawStats stats = draw_triangles(b, RasterState{}, count, sphere.indices, vs, PhongLanes{&u});
        EXPECT_EQ(stats.primitives, sphere.indices.size() / 3);
        int color = 0, depth = 0, drawn = 0;
        for (int y = 0; y < a.height(); ++y)
          for (int x = 0; x < a.width(); ++x) {
            color += a.color()(x, y) != b.color()(x, y);
            depth += a.depth()(x, y) != b.depth()(x, y);
            drawn += a.depth()(x, y) != kDepthMax;
          }
        EXPECT_EQ(color, 0) << local_viewer << int(specular) << threads;
        EXPECT_EQ(depth, 0);
        EXPECT_GT(drawn, a.width() * a.height() / 4);
      }
}

TEST(LaneShader, DiscardedLanesWriteNothing) {
  // Stripes discarded by the lane shader's mask and by the per-pixel shader's return: the same pixels.
  const VertexArrays sphere = sphere_arrays(32, 16);
  Framebuffer a(96, 80), b(96, 80);
  const FixedFunctionUniforms u = lit_uniforms(a.width(), a.height(), false, SpecularModel::blinn);
  const PhongVertexShader vs{sphere.attributes(), &u};
  const auto per_pixel = [&u](const PhongVaryings& in, Vec3f& color) {
    color = u.lighting.shade(glm::normalize(in.normal), in.position, in.color);
    return !(std::sin(9.0f * in.position.x) > 0.0f);
  };
  const auto lane = [&u](const lanes::Fragment<PhongVaryings>& in, lanes::Mask& kept) {
    const lanes::vec3 p = in(&PhongVaryings::position);
    kept &= !(sin(lanes::Float(9.0f) * p.x) > lanes::Float(0.0f));
    return u.lighting.shade(normalize(in(&PhongVaryings::normal)), p, in(&PhongVaryings::color));
  };
  const auto count = uint32_t(sphere.positions.size());
  draw_triangles(a, RasterState{}, count, sphere.indices, vs, per_pixel);
  draw_triangles(b, RasterState{}, count, sphere.indices, vs, lane);
  int diffs = 0, holes = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      diffs += a.color()(x, y) != b.color()(x, y) || a.depth()(x, y) != b.depth()(x, y);
      holes += x > 30 && x < 66 && y > 25 && y < 55 && a.depth()(x, y) == kDepthMax;
    }
  EXPECT_EQ(diffs, 0);
  EXPECT_GT(holes, 100);  // the stripes were discarded
}

TEST(LaneShader, TextureAtTheQuadsLevelOfDetail) {
  // texture() on two quads equals Texture2D::sample at each quad's level of detail from its lane differences
  // (within the SIMD sampler's one 8-bit step).
  ImageRGBA8 image(64, 48);
  Rng rng(2);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      image(x, y) = glm::u8vec4(rng.next_u32() & 255, rng.next_u32() & 255, rng.next_u32() & 255, 255);
  for (const Filter filter : {Filter::nearest, Filter::bilinear, Filter::trilinear}) {
    const Texture2D texture(image, Sampler{Wrap::repeat, Wrap::clamp, filter});
    float worst = 0;
    for (int round = 0; round < 100; ++round) {
      lanes::vec2 uv;
      for (int q = 0; q < 2; ++q) {
        // A quad's footprint: lane 0 anywhere, steps of up to 8 texels along x and y.
        const Vec2f origin(4 * rng.uniform() - 2, 4 * rng.uniform() - 2);
        const Vec2f step_x(0.12f * rng.uniform(), 0.05f * rng.uniform()),
            step_y(0.02f * rng.uniform(), 0.15f * rng.uniform());
        for (int k = 0; k < 4; ++k) {
          const Vec2f p = origin + float(k & 1) * step_x + float(k >> 1) * step_y;
          uv.x.set_lane(4 * q + k, p.x), uv.y.set_lane(4 * q + k, p.y);
        }
      }
      const lanes::vec4 got = lanes::texture(texture, uv);
      for (int k = 0; k < kWidth; ++k) {
        const int l0 = k & ~3;
        const float lod = texture.lod(uv.lane(l0 + 1) - uv.lane(l0), uv.lane(l0 + 2) - uv.lane(l0));
        const glm::vec4 want = texture.sample(uv.lane(k), lod);
        for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(got[c].lane(k) - want[c]));
      }
    }
    EXPECT_LE(worst, 1.0f / 255) << int(filter);
  }
}

TEST(LaneShader, SurfaceShaderAsThePerPixelOne) {
  // draw_surface runs SurfaceLaneShader; the per-pixel SurfaceFragmentShader (the scene rasterizer's) gives the same
  // lit colors: exactly without maps, and within an 8-bit step with a trilinear texture (the quad's level of detail
  // against the exact derivatives' one).
  const VertexArrays sphere = sphere_arrays(40, 20);
  ImageRGBA8 image(32, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) image(x, y) = glm::u8vec4(((x / 4 + y / 4) & 1) * 255, 128, x * 8, 255);
  const Texture2D texture(image, Sampler{.filter = Filter::trilinear});
  for (const bool textured : {false, true}) {
    SurfaceUniforms u;
    u.set_camera(perspective(glm::radians(45.0), 1.0, 0.5, 20), look_at({0.3, 0.4, 3.2}, {0, 0, 0}, {0, 1, 0}));
    Lighting l;
    l.material = Material::plastic({0.9f, 0.9f, 0.9f}, 20);
    l.color_material = true;
    u.lighting = PreparedLighting(l);
    if (textured) u.maps.texture = &texture;
    Framebuffer a(120, 120), b(120, 120);
    const SurfaceVertexShader vs{sphere.attributes(), nullptr, nullptr, &u};
    draw_triangles(a, RasterState{}, uint32_t(sphere.positions.size()), sphere.indices, vs, SurfaceFragmentShader{&u});
    draw_surface(b, RasterState{}, sphere, u);
    int drawn = 0, off = 0, depth_diffs = 0;  // off: pixels more than 2/255 apart in a channel
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 120; ++x) {
        depth_diffs += a.depth()(x, y) != b.depth()(x, y);
        drawn += a.depth()(x, y) != kDepthMax;
        int worst = 0;
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, std::abs(int(a.color()(x, y)[c]) - int(b.color()(x, y)[c])));
        off += textured ? worst > 2 : worst > 0;
      }
    EXPECT_EQ(depth_diffs, 0);
    EXPECT_GT(drawn, 3000);
    // Textured: where a quad's level of detail and the exact one straddle a MIPmap level the blend differs, most on
    // the checker's edges (measured: 38 of 6923 pixels, 0.55%).
    EXPECT_LE(off, textured ? drawn / 100 : 0) << textured << " " << off << " of " << drawn;
  }
}

}  // namespace
}  // namespace tessera::raster3d
