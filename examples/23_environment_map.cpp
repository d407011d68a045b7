// Example 23: environment mapping (Blinn and Newell 1976; the notes: "calculate vector R from N and V, use R to look
// up color from environment map"). Each pixel reflects the view direction about the interpolated normal,
// R = 2 (N.E) N - E, and looks R up in a lat-long image of the surroundings, which also fills the background. A
// mirror sphere, a partly reflective torus and a mirror cube (flat faces: plane mirrors). The environment is Poly
// Haven's Venice Sunset from the shared data (Gallery::data_file); without it, a procedural sky over a checkered
// ground, and the captions say so.
#include <cmath>
#include <filesystem>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/surface_shader.hpp"

namespace {

using namespace tessera;

/// A sky (blue above, pale at the horizon, a sun) over a checkered ground, as a lat-long image.
ImageRGBA procedural_sky() {
  const int w = 512, h = 256;
  ImageRGBA image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 d = latlong_direction({(x + 0.5f) / w, 1 - (y + 0.5f) / h});
      glm::vec3 c;
      if (d.y > 0) {
        c = glm::mix(glm::vec3(0.85f, 0.88f, 0.92f), glm::vec3(0.25f, 0.45f, 0.85f), std::sqrt(d.y));
        if (glm::dot(d, glm::normalize(glm::vec3(-0.5f, 0.4f, -0.6f))) > 0.995f) c = glm::vec3(1.0f, 0.95f, 0.7f);
      } else {
        // The ground plane y = -1 seen from the origin: checks of 1 unit.
        const float t = -1 / d.y;
        const bool odd = (int(std::floor(d.x * t)) + int(std::floor(d.z * t))) % 2 != 0;
        c = glm::mix(odd ? glm::vec3(0.55f, 0.4f, 0.3f) : glm::vec3(0.85f, 0.8f, 0.7f), glm::vec3(0.7f),
                     -d.y < 0.1f ? 0.6f : 0.0f);
      }
      image(x, y) = glm::vec4(c, 1);
    }
  return image;
}

// The environment and whether it is the real one (else the stand-in).
std::pair<EnvironmentMap, bool> environment_map(examples::Gallery& gallery) {
  const auto hdr = gallery.data_file("env/venice_sunset_1k.hdr", "a procedural sky over a checkered ground");
  return hdr ? std::pair(load_environment_map(*hdr), true) : std::pair(EnvironmentMap(procedural_sky()), false);
}

}  // namespace

TESSERA_EXAMPLE(ex23_environment_map, "23_environment_map",
                "Environment mapping: reflections looked up in a lat-long map") {
  const std::pair<EnvironmentMap, bool> loaded = environment_map(gallery);
  const EnvironmentMap& environment = loaded.first;
  const bool real_environment = loaded.second;
  const auto caption = [&](const std::string& text) {
    return real_environment ? text : examples::stand_in_caption("a procedural sky", "Poly Haven's Venice Sunset", text);
  };
  struct Panel {
    PolyMesh mesh;
    Mat4 model;
    Vec3f color;
    float reflectivity;
  };
  const Panel panels_spec[] = {{make_uv_sphere(96, 48), Mat4(1.0), {0, 0, 0}, 1.0f},
                               {make_torus(0.75, 0.3, 96, 48), rotate_x(radians(60)), {0.6f, 0.15f, 0.1f}, 0.45f},
                               {examples::with_face_normals(make_box()),
                                rotate_y(radians(35)) * rotate_x(radians(20)) * scale(0.62, 0.62, 0.62),
                                {0, 0, 0},
                                0.9f}};
  const int w = 280, h = 240, s = 2;
  const Mat4 projection = perspective(radians(40), double(w) / h, 0.5, 20);
  const Mat4 view = look_at({0.6, 0.5, 3.6}, {0, 0, 0}, {0, 1, 0});
  std::vector<ImageRGB> panels;
  for (const Panel& p : panels_spec) {
    const raster3d::VertexArrays arrays = raster3d::VertexArrays::from_mesh(to_tri_mesh(p.mesh));
    raster3d::SurfaceUniforms u;
    u.set_camera(projection, view, p.model);
    u.lighting = raster3d::PreparedLighting(examples::surface_lighting({-0.5, 0.6, 0.6}, view, 0.15f, 0.5f));
    u.color = p.color;
    u.maps.environment = &environment;
    u.maps.reflectivity = p.reflectivity;
    raster3d::Framebuffer fb(w * s, h * s);
    raster3d::draw_surface(fb, raster3d::RasterState{}, arrays, u);
    raster3d::fill_background(fb, environment, projection * view);
    panels.push_back(examples::downsample(fb.color_rgb(), s));
  }
  gallery.add(
      "23_environment_map.png", examples::side_by_side(panels),
      caption("Environment mapping: R = 2(N.E)N - E looked up in a lat-long environment (also the background): a "
              "mirror sphere, a red torus reflecting 45 %, a mirror cube (each face a plane mirror)."));

  // Cube mapping: a mirror sphere among nearby objects. The lat-long map alone shows only the far surroundings (the
  // notes: "good if objects are far away"); the scene rendered 6 times from the sphere's center puts the floor and
  // the objects into its reflection.
  struct Object {
    raster3d::VertexArrays arrays;
    Mat4 model;
    Vec3f color;
  };
  const std::vector<Object> objects = {
      {raster3d::VertexArrays::from_mesh(to_tri_mesh(make_grid(1, 1))), scale(2.5, 1, 2.5), {0.8f, 0.78f, 0.7f}},
      {raster3d::VertexArrays::from_mesh(to_tri_mesh(examples::with_face_normals(make_box()))),
       translate(-1.2, 0.4, 0.55) * rotate_y(radians(25)) * scale(0.4, 0.4, 0.4),
       {0.85f, 0.2f, 0.15f}},
      {raster3d::VertexArrays::from_mesh(to_tri_mesh(make_uv_sphere(48, 24))),
       translate(1.2, 0.45, 0.5) * scale(0.45, 0.45, 0.45),
       {0.2f, 0.7f, 0.3f}},
      {raster3d::VertexArrays::from_mesh(to_tri_mesh(make_torus(0.5, 0.18, 64, 24))),
       translate(1.1, 0.68, -1.5) * rotate_x(radians(90)),
       {0.2f, 0.35f, 0.85f}}};
  const Vec3 to_light(-0.5, 0.8, 0.6);
  const auto draw_scene = [&](raster3d::Framebuffer& fb, const Mat4& p, const Mat4& v) {
    for (const Object& o : objects) {
      raster3d::SurfaceUniforms u;
      u.set_camera(p, v, o.model);
      u.lighting = raster3d::PreparedLighting(examples::surface_lighting(to_light, v, 0.25f, 0.3f));
      u.color = o.color;
      raster3d::draw_surface(fb, raster3d::RasterState{}, o.arrays, u);
    }
    raster3d::fill_background(fb, environment, p * v);
  };
  const Vec3 center(0, 0.7, 0);
  const CubeMap cube = raster3d::render_cube_map(center, 256, draw_scene, 0.05, 50);
  const raster3d::VertexArrays mirror = raster3d::VertexArrays::from_mesh(to_tri_mesh(make_uv_sphere(96, 48)));
  const Mat4 scene_projection = perspective(radians(40), double(w) / h, 0.2, 50);
  const Mat4 scene_view = look_at({0.4, 1.6, 5.2}, {0, 0.55, 0}, {0, 1, 0});
  std::vector<ImageRGB> cube_panels;
  for (const bool use_cube : {false, true}) {
    raster3d::Framebuffer fb(w * s, h * s);
    draw_scene(fb, scene_projection, scene_view);
    raster3d::SurfaceUniforms u;
    u.set_camera(scene_projection, scene_view, translate(center.x, center.y, center.z) * scale(0.7, 0.7, 0.7));
    u.lighting = raster3d::PreparedLighting(examples::surface_lighting(to_light, scene_view, 0.0f, 0.5f));
    u.color = Vec3f(0);
    u.maps.reflectivity = 0.95f;
    if (use_cube)
      u.maps.cube = &cube;
    else
      u.maps.environment = &environment;
    raster3d::draw_surface(fb, raster3d::RasterState{}, mirror, u);
    cube_panels.push_back(examples::downsample(fb.color_rgb(), s));
  }
  gallery.add(
      "23_cube_mapping.png", examples::side_by_side(cube_panels),
      caption("Cube mapping: a mirror sphere among near objects reflecting the far lat-long environment only (left), "
              "and a cube map of the scene rendered 6 times from its center (right): the floor and the objects "
              "appear in the reflection."));
}
