// Example 21: texture mapping (the notes, "Texture Mapping"). A checkerboard on a floor seen in perspective, four
// ways: s and t interpolated linearly on the screen (affine: the checks bend where the floor's two triangles meet,
// the reason the notes divide s and t by |z|), perspective-correct with the nearest texel (blocky up close, noisy far
// away), with bilinear interpolation of the 4 nearest texels (smooth up close, still sparkling far away), and with
// trilinear MIPmap filtering (the level of detail from the exact screen derivatives of s and t: gray where the checks
// are smaller than a pixel).
#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/raster3d/surface_shader.hpp"

namespace {

using namespace tessera;

/// Affine texture coordinates from a perspective-correct pipeline: the varyings s w, t w and w interpolate
/// perspective-correctly to (sum l_i s_i) / q and 1 / q with q = sum l_i / w_i, so their ratio is the screen-linear
/// sum l_i s_i.
struct AffineVaryings {
  Vec2f uv_w;
  float w;
};

struct AffineVertexShader {
  const raster3d::VertexArrays* arrays;
  Mat4f model_view_projection;

  raster3d::VertexOut<AffineVaryings> operator()(uint32_t i) const {
    const Vec4f clip = model_view_projection * Vec4f(arrays->positions[i], 1.0f);
    return {clip, {arrays->uvs[i] * clip.w, clip.w}};
  }
};

struct AffineFragmentShader {
  const Texture2D* texture;

  bool operator()(const AffineVaryings& in, Vec3f& color) const {
    color = Vec3f(texture->bilinear(in.uv_w / in.w, 0));
    return true;
  }
};

/// A floor from z = 2 (in front of the camera) to z = -22, x in [-6, 6], as two triangles; the texture repeats every
/// 4 units (texture coordinates 0..3 across, 0..6 along).
raster3d::VertexArrays floor_quad() {
  raster3d::VertexArrays a;
  a.positions = {{-6, 0, -22}, {6, 0, -22}, {6, 0, 2}, {-6, 0, 2}};
  a.normals.assign(4, Vec3f(0, 1, 0));
  a.uvs = {{0, 6}, {3, 6}, {3, 0}, {0, 0}};
  a.indices = {0, 2, 1, 0, 3, 2};
  return a;
}

}  // namespace

TESSERA_EXAMPLE(ex21_texture_mapping, "21_texture_mapping",
                "Texture mapping: affine vs perspective-correct; nearest, bilinear and trilinear (MIPmap) filtering") {
  // 8 x 8 checks of 16 texels, two colors.
  ImageRGBA checks(128, 128);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      checks(x, y) = (x / 16 + y / 16) % 2 ? glm::vec4(0.95f, 0.92f, 0.8f, 1) : glm::vec4(0.15f, 0.35f, 0.6f, 1);
  const int w = 260, h = 200, s = 2;  // supersampled 2 x 2 for smooth edges (the filtering is per sample)
  const Mat4 projection = perspective(radians(55), double(w) / h, 0.1, 50);
  const Mat4 view = look_at({0.5, 2.2, 5}, {0, 0, -1.5}, {0, 1, 0});
  const raster3d::VertexArrays floor = floor_quad();

  std::vector<ImageRGB> panels;
  const Vec3f sky(0.8f, 0.85f, 0.9f);
  {
    const Texture2D texture(checks);
    raster3d::Framebuffer fb(w * s, h * s);
    fb.clear(sky);
    raster3d::draw_triangles(fb, raster3d::RasterState{}, 4, floor.indices,
                             AffineVertexShader{&floor, Mat4f(projection * view)}, AffineFragmentShader{&texture});
    panels.push_back(examples::downsample(fb.color_rgb(), s));
  }
  for (const Filter filter : {Filter::nearest, Filter::bilinear, Filter::trilinear}) {
    const Texture2D texture(checks, Sampler{.filter = filter});
    raster3d::SurfaceUniforms u;
    u.set_camera(projection, view);
    u.lighting = raster3d::PreparedLighting(raster3d::unlit_lighting());  // the texels as they are
    u.maps.texture = &texture;
    raster3d::Framebuffer fb(w * s, h * s);
    fb.clear(sky);
    raster3d::draw_surface(fb, raster3d::RasterState{}, floor, u);
    panels.push_back(examples::downsample(fb.color_rgb(), s));
  }
  gallery.add("21_texture_mapping.png", examples::side_by_side(panels),
              "A checkerboard floor in perspective: affine interpolation of (s, t) on the screen (bent checks along "
              "the two triangles' diagonal), perspective-correct with the nearest texel, bilinear, and trilinear "
              "MIPmap filtering (far checks average to gray instead of sparkling).");
}
