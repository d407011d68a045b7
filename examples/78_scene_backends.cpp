// One scene description, two renderers (the scene module drives both): the whitted scene ray traced (reflection,
// refraction, the checkerboard, every light's shadows by shadow rays), then rasterized with local shading: the same
// checkerboard per pixel, the glass sphere blended over what lies behind it (no refraction), the mirror reflecting a
// cube map of the scene drawn from its center (one bounce), with every light's shadows from a shadow map per light
// (the notes' 2-pass z-buffer), and from stencil shadow volumes (one additive pass per light). The scene has two
// lights: the second casts the fainter shadows.
#include "gallery.hpp"
#include "tessera/scene/raster.hpp"
#include "tessera/scene/trace.hpp"

TESSERA_EXAMPLE(ex78_scene_backends, "78_scene_backends",
                "One scene, two renderers: ray traced, rasterized with a shadow map, rasterized with shadow volumes") {
  using namespace tessera;
  const Scene scene = builtin_scene("whitted");
  RenderSettings s = render_settings(scene);
  s.width = 320;
  s.height = 240;
  s.progress = false;
  gallery.add("78_scene_backends.png",
              examples::side_by_side({render(to_ray_scene(scene), s),
                                      rasterize_scene(scene, s.width, s.height, RasterShadows::map),
                                      rasterize_scene(scene, s.width, s.height, RasterShadows::volumes)}),
              "The built-in whitted scene ray traced; rasterized with a shadow map per light; rasterized with "
              "shadow volumes (the second light casts the fainter shadows). The rasterizer shows the checkerboard and "
              "blends the glass over what lies behind it, unrefracted; its mirror reflects a cube map drawn from its "
              "center, one bounce deep.");
}
