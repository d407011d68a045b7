// Example 42: bicubic Bezier patches, the notes' "Bezier inside Bezier". The Utah teapot's 32 patches (Newell's data,
// the shared data's bezier/teapot.bpt (Gallery::data_file); otherwise four patches built here that make a dome, and
// the caption says so), each tessellated on a uniform grid, colored per patch; beside it the control net, the
// polyhedron of the 16 control points per patch that the surface approximates.
#include <filesystem>
#include <vector>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/curves/bezier_patch.hpp"
#include "tessera/curves/bpt.hpp"
#include "tessera/mesh/measure.hpp"

namespace tessera::examples {
namespace {

// The teapot if the shared data is there, else a dome of four patches (each a quarter, its first row collapsed to
// the apex like the teapot's lid). Sets `teapot`.
std::vector<BezierPatch> load_patches(Gallery& gallery, bool& teapot) {
  const auto bpt = gallery.data_file("bezier/teapot.bpt", "a dome of 4 patches");
  teapot = bpt.has_value();
  if (teapot) return read_bpt(*bpt);
  const double k = 0.5523;  // a quarter circle's handle length
  const Vec2 arc[4] = {Vec2(1, 0), Vec2(1, k), Vec2(k, 1), Vec2(0, 1)};
  const double radius[4] = {0, 0.8, 1.5, 1.5}, height[4] = {1.5, 1.5, 0.8, 0};
  std::vector<BezierPatch> patches(4);
  for (int q = 0; q < 4; ++q)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const Vec2 a = arc[j];
        const Vec2 turned = q == 0 ? a : q == 1 ? Vec2(-a.y, a.x) : q == 2 ? -a : Vec2(a.y, -a.x);
        patches[size_t(q)].at(i, j) = Vec3(radius[i] * turned.x, radius[i] * turned.y, height[i]);
      }
  return patches;
}

// z-up data to the renderer's y-up frame.
Vec3 y_up(const Vec3& p) { return Vec3(p.x, p.z, -p.y); }

// The uniform tessellation as quads (triangle pairs a b c, a c d per grid cell) with one color per patch.
PolyMesh patch_quads(const TriMesh& tris, size_t patches, std::vector<Vec3f>& colors) {
  PolyMesh quads;
  for (const Vec3& p : tris.positions) quads.positions.push_back(y_up(p));
  const size_t per_patch = tris.triangle_count() / 2 / patches;
  for (size_t t = 0; t + 1 < tris.triangle_count(); t += 2) {
    const uint32_t* i = &tris.indices[3 * t];
    quads.add_face({i[0], i[1], i[2], i[5]});
    const Vec3f palette[] = {{0.95f, 0.72f, 0.62f}, {0.62f, 0.85f, 0.88f}, {0.96f, 0.88f, 0.58f},
                             {0.72f, 0.78f, 0.96f}, {0.75f, 0.92f, 0.68f}, {0.92f, 0.70f, 0.88f}};
    colors.push_back(palette[(t / 2 / per_patch) % std::size(palette)]);
  }
  return quads;
}

// Turns every face around.
void reverse_faces(PolyMesh& mesh) {
  PolyMesh reversed;
  reversed.positions = mesh.positions;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    reversed.add_face(std::vector<uint32_t>(face.rbegin(), face.rend()));
  }
  mesh = reversed;
}

}  // namespace
}  // namespace tessera::examples

TESSERA_EXAMPLE(ex42_bezier_patches, "42_bezier_patches", "Bicubic Bezier patches: the Utah teapot") {
  using namespace tessera;
  bool teapot = false;
  const std::vector<BezierPatch> patches = examples::load_patches(gallery, teapot);
  const TriMesh surface = tessellate(patches, PatchTessellation{.steps = 8});
  std::vector<Vec3f> colors;
  PolyMesh quads = examples::patch_quads(surface, patches.size(), colors);
  PolyMesh net = control_net(patches);
  for (Vec3& p : net.positions) p = examples::y_up(p);
  // Newell's data is wound so that du x dv points into the pot: turn it around when the enclosed volume is negative
  // (what PatchOrientation::outward does for tessellate()).
  if (signed_volume(quads) < 0) {
    examples::reverse_faces(quads);
    examples::reverse_faces(net);
  }

  const int size = 420;
  examples::MeshViewOptions options;
  options.width = options.height = size;
  ImageRGB sheet(2 * size, size, Vec3f(1.0f));
  options.face_colors = colors;
  examples::paste(sheet, examples::render_mesh(quads, options), 0);
  options.face_colors.clear();
  options.color = Vec3f(0.9f, 0.8f, 0.6f);
  examples::paste(sheet, examples::render_mesh(net, options), size);
  const std::string caption =
      std::string(teapot ? "The Utah teapot: 32 bicubic patches" : "A dome of 4 bicubic patches") +
      ", each sampled on a 9 x 9 grid of (u, v) and colored per patch (left), and its control net of 16 points per "
      "patch (right), which the surface interpolates only at the patch corners.";
  gallery.add("42_bezier_patches.png", sheet,
              teapot ? caption : examples::stand_in_caption("a dome of 4 patches", "the Utah teapot", caption));
}
