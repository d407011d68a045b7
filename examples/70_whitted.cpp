// Recursive ray tracing (the notes' "Recursive Ray Tracing"): Whitted's scene, a mirror sphere and a glass sphere over
// a checkerboard, read from the built-in scene file and rendered at increasing recursion depth.
#include "gallery.hpp"
#include "tessera/scene/trace.hpp"

TESSERA_EXAMPLE(ex70_whitted, "70_whitted", "Whitted's scene: recursive reflection and refraction") {
  using namespace tessera;
  const Scene scene = builtin_scene("whitted");
  const RayScene rs = to_ray_scene(scene);
  RenderSettings s = render_settings(scene);
  s.width = 480;
  s.height = 360;
  s.progress = false;
  gallery.add("70_whitted.png", render(rs, s),
              "The built-in whitted scene (4 stratified samples per pixel, depth 6): the mirror sphere reflects the "
              "board and the glass sphere, which refracts the board upside down.");
  // The notes' first stopping rule, made visible: depth 1 shows only local shading, depth 2 one bounce, and so on.
  std::vector<ImageRGB> panels;
  s.width = 240;
  s.height = 180;
  for (int depth : {1, 2, 3, 6}) {
    s.max_depth = depth;
    panels.push_back(render(rs, s));
  }
  gallery.add("70_whitted_depths.png", examples::side_by_side(panels),
              "Recursion depth 1, 2, 3 and 6: eye rays only, then one, two and five levels of reflected and refracted "
              "rays.");
}
