// Example 19: double buffering (the notes, "Output Devices": memory 1 is displayed while memory 2 receives the next
// image). Each frame is drawn into the Context's back buffer — clear, a cube orbiting a spinning torus, all through
// the gt layer — and gtSwapBuffers() presents it; what is written out is the front buffer, never a half-drawn
// image. Twelve frames of one turn are written as PNG files (19_animation_frames/frame_NN.png) and laid out on a
// contact sheet for the gallery.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster3d/gt.hpp"

namespace {

using namespace tessera;
using namespace tessera::gt;

void draw_mesh(const TriMesh& mesh) {
  gtBeginShape(GT_TRIANGLES);
  for (const uint32_t i : mesh.indices) {
    gtNormal(mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z);
    gtVertex(mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z);
  }
  gtEndShape();
}

// A polygon mesh with one normal per face (fan-triangulated): facets.
void draw_faceted(const PolyMesh& mesh) {
  gtBeginShape(GT_TRIANGLES);
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3 n = face_normal(mesh, f);
    const auto face = mesh.face(f);
    for (size_t i = 1; i + 1 < face.size(); ++i)
      for (const uint32_t v : {face[0], face[i], face[i + 1]}) {
        gtNormal(n.x, n.y, n.z);
        gtVertex(mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z);
      }
  }
  gtEndShape();
}

}  // namespace

TESSERA_EXAMPLE(ex19_animation, "19_animation", "Double-buffered animation frames") {
  constexpr int kFrames = 12, kWidth = 200, kHeight = 150;
  const TriMesh torus = to_tri_mesh(make_torus(1.0, 0.35, 40, 20));
  const PolyMesh cube = make_box();
  raster3d::Context context(kWidth, kHeight);
  gtMakeCurrent(&context);
  context.shading(raster3d::ShadingModel::gouraud);
  context.color_material(true);
  context.material(raster3d::Material::plastic({1, 1, 1}, 32, 0.5f));
  context.light(0, {.position = {-0.3f, 0.6f, 1.0f, 0.0f}});
  gtPerspective(radians(45), 1, 20);
  const std::filesystem::path frames_dir = gallery.dir() / "19_animation_frames";
  std::filesystem::create_directories(frames_dir);
  ImageRGB sheet(4 * kWidth, 3 * kHeight);
  for (int frame = 0; frame < kFrames; ++frame) {
    const double t = 2 * kPi * frame / kFrames;
    gtClear(0.1f, 0.12f, 0.16f);  // the back buffer; the front keeps showing the previous frame meanwhile
    gtLoadIdentity();
    gtLookAt(0, 2.2, 5.0, 0, 0, 0, 0, 1, 0);
    gtPushMatrix();  // the torus tumbles about a tilted horizontal axis
    gtRotateZ(0.4);
    gtRotateX(t);
    gtColor(0.9f, 0.45f, 0.2f);
    draw_mesh(torus);
    gtPopMatrix();
    gtPushMatrix();  // the cube orbits and tumbles
    gtRotateY(-t);
    gtTranslate(2.1, 0.3 * std::sin(2 * t), 0);
    gtRotate(2 * t, 1, 1, 0);
    gtScale(0.35, 0.35, 0.35);
    gtColor(0.3f, 0.6f, 0.95f);
    draw_faceted(cube);
    gtPopMatrix();
    gtSwapBuffers();  // present: the finished frame becomes the front buffer
    const ImageRGBA8& shown = context.framebuffer().front();
    write_image(frames_dir / fmt::format("frame_{:02d}.png", frame), shown);
    examples::paste(sheet, to_rgb(to_float(shown)), (frame % 4) * kWidth, (frame / 4) * kHeight);
  }
  gtMakeCurrent(nullptr);
  gallery.add("19_animation.png", sheet,
              "Twelve double-buffered frames of one turn (drawn into the back buffer, presented by gtSwapBuffers, "
              "written from the front buffer to 19_animation_frames/frame_NN.png), left to right, top to bottom.");
}
