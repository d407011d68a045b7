// The notes' "add a primitive" contract: every shape of the ray tracer side by side (cone with its cap, cylinder,
// box, ellipsoid, polygon, disk, sphere and a triangle on the floor), from the built-in "shapes" scene.
#include "gallery.hpp"
#include "tessera/scene/trace.hpp"

TESSERA_EXAMPLE(ex72_shapes, "72_shapes", "Every ray-traced shape") {
  using namespace tessera;
  const Scene scene = builtin_scene("shapes");
  RenderSettings s = render_settings(scene);
  s.progress = false;
  gallery.add(
      "72_shapes.png", render(to_ray_scene(scene), s),
      "Left to right: the notes' cone standing on its apex with its base cap on top, a capped cylinder, a rotated box, "
      "an ellipsoid, a non-convex polygon (winding-number test), a tilted disk, a sphere; a triangle lies on "
      "the floor.");
}
