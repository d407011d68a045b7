// Example 14: the notes' combined equation C = C_r (C_a + C_L max(0, N.L)) + C_L C_H (H.N)^P with its highlight
// color C_H: white for plastic (the highlight is the light's color) and the surface color for metal (a reddish
// surface gives reddish highlights). Top row plastic, bottom row metal, the exponent P growing to the right
// (rough to smooth: the highlight shrinks and sharpens). A torus so that each picture holds highlights at several
// angles.
#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/primitives.hpp"

TESSERA_EXAMPLE(ex14_plastic_metal, "14_plastic_metal", "Plastic versus metal highlights") {
  using namespace tessera;
  const PolyMesh torus = make_torus(1.0, 0.42, 72, 36);
  const Vec3f red{0.8f, 0.2f, 0.12f};
  constexpr int kSize = 220;
  ImageRGB sheet(3 * kSize, 2 * kSize);
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 3; ++col) {
      const float exponent = 8.0f * float(1 << (2 * col));  // 8, 32, 128
      examples::MeshViewOptions o;
      o.width = o.height = kSize;
      o.camera = Camera{.eye = {0, 2.6, 3.0}, .center = {0, -0.1, 0}, .fovy = radians(46), .near = 1.5, .far = 7};
      o.light_dir = {-0.6, 1.0, 0.7};
      o.shading = raster3d::ShadingModel::phong;
      o.material = row == 0 ? raster3d::Material::plastic(red, exponent) : raster3d::Material::metal(red, exponent);
      o.background = {0.12f, 0.12f, 0.14f};
      o.wireframe = false;
      examples::paste(sheet, examples::render_mesh(torus, o), col * kSize, row * kSize);
    }
  gallery.add("14_plastic_metal.png", sheet,
              "A red torus: plastic (top, white highlights, C_H = 1) and metal (bottom, highlights in the surface "
              "color, C_H = C_r), with the specular exponent P = 8, 32, 128 from left to right.");
}
