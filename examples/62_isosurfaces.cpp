// Marching cubes: a CT head's skin and bone (shared data when present, else a procedural phantom) and a gyroid.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/procedural.hpp"
#include "tessera/volume/volume_io.hpp"

TESSERA_EXAMPLE(ex62_isosurfaces, "62_isosurfaces", "Marching cubes iso-surfaces: CT head skin and bone, a gyroid") {
  using namespace tessera;
  using namespace tessera::examples;
  const auto head =
      gallery.data_file("volumes/headsq_64x64x93_int16le.mhd", "a procedural phantom (ellipsoid and shell)");
  Volume<float> ct;
  float skin = 500, bone = 1150;
  if (head) {
    ct = to_float(read_volume(head->string()));
  } else {  // phantom: a soft ellipsoid "head" around a denser shell "skull"
    ct = make_sphere(64, 0.8);
    for (float& v : ct.voxels()) v = v > 0.12f ? 600.0f : v > 0.0f ? 1300.0f : 0.0f;
  }
  examples::MeshViewOptions options;
  options.wireframe = false;
  options.camera = Camera{};
  const Vec3 lo = ct.origin(), hi = ct.to_world(Vec3(ct.dims() - 1)), mid = 0.5 * (lo + hi);
  options.camera->center = mid;
  // The CT's z runs from the neck up, so "up" on screen is -z; the face looks toward -y. Frame the volume's bounding
  // sphere and light from the viewer's upper left.
  const Vec3 view_dir = glm::normalize(Vec3(0.45, -1.0, -0.25));
  options.camera->eye = mid + view_dir * sphere_fit_distance(0.5 * glm::length(hi - lo), options.camera->fovy / 2, 1);
  options.camera->up = {0, 0, -1};
  options.light_dir = glm::normalize(view_dir + Vec3(-0.6, 0.0, -0.6));
  options.camera->near = 1;
  options.camera->far = 1e4;
  options.color = {0.9f, 0.72f, 0.62f};
  const std::string subject = head ? "CT head" : "Phantom head";
  const auto caption = [&](const std::string& text) {
    return head ? text : stand_in_caption("a procedural phantom (an ellipsoid around a shell)", "the CT head", text);
  };
  gallery.add("62_ct_skin.png", render_mesh(marching_cubes(ct, {.iso = skin}), options),
              caption(fmt::format("{}, skin iso-surface (marching cubes at {:g}).", subject, skin)));
  options.color = {0.95f, 0.93f, 0.85f};
  gallery.add("62_ct_bone.png", render_mesh(marching_cubes(ct, {.iso = bone}), options),
              caption(fmt::format("{}, bone iso-surface (marching cubes at {:g}).", subject, bone)));
  examples::MeshViewOptions g;
  g.wireframe = false;
  gallery.add("62_gyroid.png", render_mesh(marching_cubes(make_gyroid(64), {}), g),
              "The gyroid sin x cos y + sin y cos z + sin z cos x = 0.");
}
