// The library's mesh renderer (MeshView, render_mesh) against independent references: a sphere's covered pixels and
// front depth against its analytic projection, a cube's flat facets against the Lambert formula, the normals' false
// colors against (n + 1) / 2, one prepared view rendered for several cameras and options against fresh ones, and
// render_into's 8-bit frame against the float picture rounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/scene/mesh_view.hpp"

namespace tessera {
namespace {

constexpr int kSize = 256;
/// The framebuffer holds 8-bit colors: a shade is within half a level of its value.
constexpr double kLevel = 0.5 / 255 + 1e-6;

/// Where a world point lands in a kSize x kSize picture through `camera` (row 0 at the top), and its window z.
Vec3 to_window(const Camera& camera, const Vec3& p) {
  const glm::dvec4 clip = camera.projection() * camera.view() * glm::dvec4(p, 1.0);
  const Vec3 ndc = Vec3(clip) / clip.w;
  return {(ndc.x + 1) / 2 * kSize, (1 - ndc.y) / 2 * kSize, (ndc.z + 1) / 2};
}

/// The unit box with each face's normal on its corners (flat faces under any shading).
PolyMesh face_normal_box() {
  PolyMesh box = make_box();
  for (size_t f = 0; f < box.face_count(); ++f)
    box.corner_normals.insert(box.corner_normals.end(), box.face(f).size(), face_normal(box, f));
  return box;
}

bool same(const ImageRGB& a, const ImageRGB& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin());
}

TEST(MeshRender, SphereCoversItsProjectedDisk) {
  // A unit sphere at distance d on the view axis: its silhouette is a circle of angular radius asin(1 / d), so
  // tan(asin(1 / d)) / tan(fovy / 2) of the half height, an area of pi R^2 pixels.
  Camera camera;
  camera.eye = {0, 0, 4};
  const double angular = std::asin(1 / 4.0);
  const double radius_px = std::tan(angular) / std::tan(camera.fovy / 2) * kSize / 2;
  const double disk = kPi * radius_px * radius_px;
  for (const MeshShading shading : {MeshShading::unlit, MeshShading::flat, MeshShading::phong}) {
    MeshViewOptions options;
    options.shading = shading;
    const MeshPicture picture = render_mesh(make_uv_sphere(256, 128), camera, kSize, kSize, options);
    // The tessellation's silhouette lies inside the sphere's (a relative area of about (pi / 256)^2 less); the pixel
    // centers on the boundary round either way.
    EXPECT_NEAR(double(picture.covered), disk, 0.005 * disk);
    // The front point (0, 0, 1) at the picture's center, its window z as the projection gives it.
    EXPECT_NEAR(picture.depth(kSize / 2, kSize / 2), to_window(camera, {0, 0, 1}).z, 1e-5);
    EXPECT_EQ(picture.depth(0, 0), 1.0f);  // the background
  }
}

TEST(MeshRender, PainterCoversWhatTheZBufferCovers) {
  Camera camera;
  camera.eye = {2, 1.5, 3};
  MeshViewOptions options;
  const MeshPicture zbuffer = render_mesh(make_torus(1, 0.4, 48, 24), camera, kSize, kSize, options);
  options.hidden_surface = raster3d::HiddenSurface::painter;
  const MeshPicture painter = render_mesh(make_torus(1, 0.4, 48, 24), camera, kSize, kSize, options);
  EXPECT_GT(zbuffer.covered, 1000u);
  EXPECT_EQ(painter.covered, zbuffer.covered);
}

TEST(MeshRender, FlatCubeFacesFollowLambert) {
  // Three faces of the box [-1, 1]^3 seen from (3, 2.5, 4), a white light from direction L: each face has
  // C (a + max(0, N.L)) (OpenGL's ambient a = 0.2 of the light model, no highlight), flat whatever its normals.
  Camera camera;
  camera.eye = {3, 2.5, 4};
  camera.far = 20;
  const Vec3 light = glm::normalize(Vec3(0.3, 1, 0.5));
  MeshViewOptions options;
  options.shading = MeshShading::flat;
  options.color = {0.9f, 0.6f, 0.3f};
  options.specular = 0;
  options.light = {MeshLightKind::directional, Vec3(0.3, 1, 0.5) * 7.0};  // any length
  const MeshPicture picture = render_mesh(make_box(), camera, kSize, kSize, options);
  for (const Vec3& n : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}) {
    const Vec3 at = to_window(camera, n);  // the face's center
    const Vec3f expected = options.color * float(0.2 + std::max(0.0, glm::dot(n, light)));
    const Vec3f got = picture.color(int(at.x), int(at.y));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], kLevel) << "face " << n.x << n.y << n.z;
  }
}

TEST(MeshRender, NormalsShadingColorsEachFaceByItsNormal) {
  Camera camera;
  camera.eye = {3, 2.5, 4};
  camera.far = 20;
  MeshViewOptions options;
  options.shading = MeshShading::normals;
  const MeshPicture picture = render_mesh(face_normal_box(), camera, kSize, kSize, options);
  for (const Vec3& n : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}) {
    const Vec3 at = to_window(camera, n);
    const Vec3f got = picture.color(int(at.x), int(at.y));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], (n[c] + 1) / 2, kLevel);
  }
}

TEST(MeshRender, OneViewRendersManyCamerasAsFreshViewsDo) {
  const PolyMesh mesh = make_torus(1, 0.4, 32, 16);
  MeshViewOptions options;
  options.wireframe = MeshWireframe::over;
  Camera a, b;
  a.eye = {0, 2, 4};
  b.eye = {3, -1, 2};
  b.orthographic = true;
  b.ortho_height = 3;
  const MeshView view(mesh, options);
  const ImageRGB first = view.render(a, kSize, kSize).color;
  const ImageRGB other = view.render(b, kSize, kSize / 2).color;
  EXPECT_TRUE(same(view.render(a, kSize, kSize).color, first));
  EXPECT_TRUE(same(first, render_mesh(mesh, a, kSize, kSize, options).color));
  EXPECT_TRUE(same(other, render_mesh(mesh, b, kSize, kSize / 2, options).color));
  EXPECT_FALSE(same(first, view.render(b, kSize, kSize).color));
}

TEST(MeshRender, ChangedOptionsRenderAsAFreshView) {
  const PolyMesh mesh = make_uv_sphere(24, 12);
  Camera camera;
  MeshView view(mesh);
  const ImageRGB gouraud = view.render(camera, kSize, kSize).color;
  for (const MeshShading shading : {MeshShading::flat, MeshShading::normals, MeshShading::phong}) {
    MeshViewOptions options;
    options.shading = shading;
    options.background = {0.2f, 0.3f, 0.4f};
    options.wireframe = MeshWireframe::alone;
    view.set_options(options);
    EXPECT_TRUE(same(view.render(camera, kSize, kSize).color, render_mesh(mesh, camera, kSize, kSize, options).color));
  }
  view.set_options({});
  EXPECT_TRUE(same(view.render(camera, kSize, kSize).color, gouraud));
}

TEST(MeshRender, SupersamplingBoxFiltersTheLargerPicture) {
  const PolyMesh mesh = make_torus(1, 0.4, 32, 16);
  Camera camera;
  camera.eye = {0, 2, 4};
  MeshViewOptions options;
  const ImageRGB large = render_mesh(mesh, camera, 2 * kSize, 2 * kSize, options).color;
  options.supersample = 2;
  const MeshPicture small = render_mesh(mesh, camera, kSize, kSize, options);
  ASSERT_EQ(small.color.width(), kSize);
  // Each output pixel is the mean of its 2 x 2 block, computed here.
  for (int y = 0; y < kSize; y += 7)
    for (int x = 0; x < kSize; x += 5) {
      const Vec3f mean =
          (large(2 * x, 2 * y) + large(2 * x + 1, 2 * y) + large(2 * x, 2 * y + 1) + large(2 * x + 1, 2 * y + 1)) /
          4.0f;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(small.color(x, y)[c], mean[c], 1e-6);
    }
}

TEST(MeshRender, InsideOutMeshIsTurnedOutward) {
  PolyMesh box = make_box();
  for (size_t f = 0; f < box.face_count(); ++f)
    std::reverse(box.face_vertices.begin() + box.face_offsets[f], box.face_vertices.begin() + box.face_offsets[f + 1]);
  EXPECT_TRUE(MeshView(box).turned_outward());
  EXPECT_FALSE(MeshView(make_box()).turned_outward());
  MeshViewOptions keep;
  keep.turn_outward = false;
  EXPECT_FALSE(MeshView(box, keep).turned_outward());
}

TEST(MeshRender, FloorReceivesTheShadowWhereTheLightIsBlocked) {
  // The box [-1, 1]^3 over the floor y = -1, lit from (0, 1, -1): its shadow falls on the floor at z in [1, 3] behind
  // it as seen from the light. There the floor (color 0.85) gets only the ambient term 0.85 * 0.2; beside it, at
  // x = 2.5, also the diffuse 0.85 * cos 45 degrees (no highlight).
  Camera camera;
  camera.eye = {0, 4, 9};
  camera.center = {0, -1, 1};
  camera.far = 40;
  MeshViewOptions options;
  options.shading = MeshShading::phong;
  options.specular = 0;
  options.light = {MeshLightKind::directional, Vec3(0, 1, -1)};
  options.floor = true;
  options.shadows = true;
  const MeshPicture picture = render_mesh(make_box(), camera, kSize, kSize, options);
  const Vec3 shadowed = to_window(camera, {0, -1, 2}), lit = to_window(camera, {2.5, -1, 2});
  EXPECT_NEAR(picture.color(int(shadowed.x), int(shadowed.y)).y, 0.85 * 0.2, 2 * kLevel);
  EXPECT_NEAR(picture.color(int(lit.x), int(lit.y)).y, 0.85 * (0.2 + std::sqrt(0.5)), 2 * kLevel);
}

TEST(MeshRender, RefusedOptionsLeaveTheViewAsItWas) {
  const PolyMesh box = make_box();  // no uvs
  Camera camera;
  MeshView view(box);
  const ImageRGB before = view.render(camera, 64, 64).color;
  MeshViewOptions textured;
  textured.shading = MeshShading::flat;
  textured.texture = std::make_shared<const Texture2D>(ImageRGBA8(4, 4, glm::u8vec4(255)), Sampler{});
  EXPECT_THROW(view.set_options(textured), InvalidInput);
  EXPECT_THROW(MeshView(box, textured), InvalidInput);
  EXPECT_EQ(view.options().shading, MeshShading::gouraud);
  EXPECT_TRUE(same(view.render(camera, 64, 64).color, before));
}

TEST(MeshRender, EmptyMeshGivesTheBackground) {
  MeshViewOptions options;
  options.background = {0.1f, 0.2f, 0.3f};
  const MeshPicture picture = render_mesh(PolyMesh{}, Camera{}, 8, 4, options);
  EXPECT_EQ(picture.covered, 0u);
  EXPECT_EQ(picture.color(7, 3), options.background);
}

TEST(MeshRender, RenderIntoWritesRendersColorsAsBytes) {
  // render_into's bytes against render()'s float picture rounded to 8 bits, 255 c to the nearest (halves to even, as
  // the supersampled averages may fall), alpha 255: the direct copy
  // of one sample (shadings, edges, blending, the painter's algorithm, the maps' path) and the converted fallback
  // (jittered samples, supersampling, a mesh without faces).
  Camera camera;
  camera.eye = {1.5, 1.2, 2.5};
  camera.aspect = 160.0 / 120;
  const auto check = [&](const char* what, const PolyMesh& mesh, const MeshViewOptions& options) {
    const MeshView view(mesh, options);
    const ImageRGB picture = view.render(camera, 160, 120).color;
    ImageRGBA8 out(160, 120, glm::u8vec4(7));
    view.render_into(camera, out);
    long long differing = 0;
    for (size_t i = 0; i < out.pixels().size(); ++i) {
      const Vec3f c = picture.pixels()[i] * 255.0f;
      const glm::u8vec4 expected(std::nearbyint(c.x), std::nearbyint(c.y), std::nearbyint(c.z), 255);
      differing += out.pixels()[i] != expected;
    }
    EXPECT_EQ(differing, 0) << what << " " << int(options.shading);
  };
  const PolyMesh sphere = make_uv_sphere(32, 16);
  for (const MeshShading shading :
       {MeshShading::unlit, MeshShading::flat, MeshShading::gouraud, MeshShading::phong, MeshShading::normals}) {
    MeshViewOptions options;
    options.shading = shading;
    options.background = {0.1f, 0.1f, 0.12f};
    check("shading", sphere, options);
  }
  MeshViewOptions edges;
  edges.wireframe = MeshWireframe::over;
  check("edges", sphere, edges);
  MeshViewOptions blended;
  blended.opacity = 0.5;
  check("blended", sphere, blended);
  MeshViewOptions painter;
  painter.hidden_surface = raster3d::HiddenSurface::painter;
  check("painter", sphere, painter);
  MeshViewOptions shadows;
  shadows.shadows = shadows.floor = true;
  check("shadows", sphere, shadows);
  MeshViewOptions jittered;
  jittered.samples = 3;
  check("jittered", sphere, jittered);
  MeshViewOptions supersampled;
  supersampled.supersample = 2;
  check("supersampled", sphere, supersampled);
  check("empty", PolyMesh{}, MeshViewOptions{});
}

}  // namespace
}  // namespace tessera
