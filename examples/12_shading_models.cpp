// Example 12: where the shading equation is evaluated (the notes, "Shading Equation: where to apply it?"). The same
// coarse sphere (16 x 10 facets) under the same light and shiny plastic: per polygon (flat: one color per facet),
// per vertex (Gouraud: colors interpolated, so the highlight is smeared and takes the facets' shape) and per pixel
// (Phong interpolation: normals interpolated and the equation evaluated at every pixel, a round highlight).
#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/mesh/primitives.hpp"

TESSERA_EXAMPLE(ex12_shading_models, "12_shading_models", "Flat, Gouraud and Phong shading of a sphere") {
  using namespace tessera;
  const PolyMesh sphere = make_uv_sphere(16, 10);
  std::vector<ImageRGB> panels;
  for (const raster3d::ShadingModel model :
       {raster3d::ShadingModel::flat, raster3d::ShadingModel::gouraud, raster3d::ShadingModel::phong}) {
    examples::MeshViewOptions o;
    o.width = o.height = 280;
    o.camera = Camera{.eye = {0, 0, 4.2}, .center = {0, 0, 0}, .fovy = radians(35), .near = 2, .far = 7};
    o.light_dir = {-0.5, 0.6, 1.0};
    o.shading = model;
    o.material = raster3d::Material::plastic({0.2f, 0.45f, 0.85f}, 40);
    o.wireframe = false;
    panels.push_back(examples::render_mesh(sphere, o));
  }
  gallery.add("12_shading_models.png", examples::side_by_side(panels),
              "One 16 x 10 sphere, one light, a shiny plastic: flat shading (per polygon), Gouraud (per vertex: the "
              "highlight is smeared into the facets' shape) and Phong interpolation (per pixel: a round highlight).");
}
