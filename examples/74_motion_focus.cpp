// Distribution ray tracing in time and over the lens (the notes' "Motion Blur"; depth of field by a thin lens): the
// built-in motion-blur and depth-of-field scenes, each beside its sharp (one instant, pinhole) version.
#include "gallery.hpp"
#include "tessera/scene/trace.hpp"

TESSERA_EXAMPLE(ex74_motion_focus, "74_motion_focus", "Motion blur and depth of field") {
  using namespace tessera;
  for (const char* name : {"motion-blur", "depth-of-field"}) {
    Scene scene = builtin_scene(name);
    RenderSettings s = render_settings(scene);
    s.width /= 2;
    s.height /= 2;
    s.progress = false;
    const ImageRGB blurred = render(to_ray_scene(scene), s);
    for (auto& o : scene.objects) o.motion = Motion{};
    scene.camera.aperture = 0;
    const ImageRGB sharp = render(to_ray_scene(scene), s);
    const std::string file = std::string("74_") + name + ".png";
    gallery.add(file, examples::side_by_side({sharp, blurred}),
                std::string(name) == "motion-blur"
                    ? "Left: one instant. Right: rays spread over the shutter interval; the red sphere moves right, "
                      "the blue one up, the box turns 30 degrees."
                    : "Left: a pinhole camera. Right: a thin lens of radius 0.22 focused at 7.6 units, on the third "
                      "(green) sphere; nearer and farther spheres blur.");
  }
}
