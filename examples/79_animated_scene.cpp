// Scenes that move (docs/scene-format.md, "Animation"; docs/farm.md): frames of the built-in whitted-moving, where
// keyed values swing the camera (Catmull-Rom keys) and bounce the glass sphere (a keyed translation, blurred over a
// half-frame shutter), each frame made on its own by AnimatedScene::at, as a farm's tasks make them.
#include "gallery.hpp"
#include "tessera/scene/scene.hpp"
#include "tessera/scene/trace.hpp"

TESSERA_EXAMPLE(ex79_animated_scene, "79_animated_scene", "Animated scenes: keyed camera and motion, frame by frame") {
  using namespace tessera;
  const AnimatedScene animated = load_animated_scene("whitted-moving");
  std::vector<ImageRGB> row[2];
  const int frames[] = {0, 6, 12, 18, 24, 36};
  for (int i = 0; i < 6; ++i) {
    const Scene scene = animated.at(frames[i]);
    RenderSettings s = render_settings(scene);
    s.width /= 4;
    s.height /= 4;
    s.progress = false;
    row[i / 3].push_back(render(to_ray_scene(scene), s));
  }
  const ImageRGB top = examples::side_by_side(row[0]), bottom = examples::side_by_side(row[1]);
  ImageRGB sheet(top.width(), top.height() + bottom.height(), Vec3f(1.0f));
  examples::paste(sheet, top, 0, 0);
  examples::paste(sheet, bottom, 0, top.height());
  gallery.add("79_whitted_moving.png", sheet,
              "Frames 0, 6, 12 (top) and 18, 24, 36 (bottom) of whitted-moving at 24 fps: the camera swings from "
              "left to right while the glass sphere bounces (on the floor at frames 0 and 24, blurred by its "
              "motion over the shutter; highest at 12 and 36).");
}
