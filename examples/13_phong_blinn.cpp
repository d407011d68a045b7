// Example 13: the two specular terms of the notes ("Shiny Surfaces"): Phong's (E.R)^P with R = 2N(N.L) - L, and
// Blinn's (H.N)^P with the half-way vector H = (L + E) / |L + E|. For the same exponent Blinn's highlight is wider
// (the angle between H and N is about half the angle between E and R); Blinn with 4P looks much like Phong with P.
// Per-pixel (Phong-interpolated) shading on a finely tessellated sphere, so that only the term differs.
#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"

TESSERA_EXAMPLE(ex13_phong_blinn, "13_phong_blinn", "Phong (E.R)^P versus Blinn (H.N)^P highlights") {
  using namespace tessera;
  const PolyMesh sphere = make_uv_sphere(64, 32);
  struct Panel {
    raster3d::SpecularModel model;
    float exponent;
  };
  std::vector<ImageRGB> panels;
  for (const Panel& p : {Panel{raster3d::SpecularModel::phong, 20}, Panel{raster3d::SpecularModel::blinn, 20},
                         Panel{raster3d::SpecularModel::blinn, 80}}) {
    examples::MeshViewOptions o;
    o.width = o.height = 280;
    o.camera = Camera{.eye = {0, 0, 4.2}, .center = {0, 0, 0}, .fovy = radians(35), .near = 2, .far = 7};
    o.light_dir = {-1.0, 0.8, 0.6};  // from the upper left, so the highlights sit off-center
    o.shading = raster3d::ShadingModel::phong;
    o.specular = p.model;
    o.material = raster3d::Material::plastic({0.75f, 0.2f, 0.15f}, p.exponent);
    o.wireframe = false;
    panels.push_back(examples::render_mesh(sphere, o));
  }
  gallery.add("13_phong_blinn.png", examples::side_by_side(panels),
              "Specular terms with a light from the upper left: Phong (E.R)^20, Blinn (H.N)^20 (a wider highlight) and "
              "Blinn (H.N)^80 (about Phong's size: the H-N angle is about half the E-R angle).");
}
