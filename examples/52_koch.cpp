// Example 52: the von Koch snowflake (the notes: replace the middle third of every segment by a triangular bump, then
// repeat for all segments; infinite length in the limit). Levels 0-4 side by side, then all five overlaid: each
// level has 4/3 the length of the one before, and the area tends to 8/5 of the triangle's.
#include <fmt/format.h>

#include "gallery.hpp"
#include "tessera/fractal/draw.hpp"
#include "tessera/fractal/self_similar.hpp"
#include "tessera/image/image_io.hpp"

TESSERA_EXAMPLE(ex52_koch, "52_koch", "von Koch snowflake, levels 0-4") {
  using namespace tessera;
  const int side = 300;
  const std::vector<Vec2> deepest = koch_snowflake(4);
  ImageRGBA strip(5 * side, side, Vec4f(1.0f));
  ImageRGBA overlay(2 * side, 2 * side, Vec4f(1.0f));
  const PictureFrame big = frame_around(deepest, 2 * side, 2 * side, 12);
  for (int level = 0; level <= 4; ++level) {
    const std::vector<Vec2> flake = koch_snowflake(level);
    // Each level in its own square of the strip, framed by the level-4 outline so that all share one scale.
    ImageRGBA cell(side, side, Vec4f(1.0f));
    const PictureFrame frame = frame_around(deepest, side, side, 10);
    add_polygons(cell, {flake}, frame, {0.80f, 0.88f, 1.0f}, true);
    add_curve(cell, flake, true, frame, {0.05f, 0.15f, 0.45f}, 1.5, true);
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) strip(level * side + x, y) = cell(x, y);
  }
  // The overlay: every level contains the one before, so filling level 4 (light) first and level 0 (dark) last
  // leaves each level's added bumps as a band of its own color.
  for (int level = 4; level >= 0; --level) {
    const float t = float(level) / 4.0f;
    add_polygons(overlay, {koch_snowflake(level)}, big, Vec3f(0.1f + 0.75f * t, 0.2f + 0.65f * t, 0.5f + 0.45f * t),
                 true);
  }
  gallery.add("52_koch_levels.png", to_rgb(strip),
              fmt::format("Koch snowflake levels 0-4: lengths 3, 4, 5.33, 7.11, 9.48; area ratio to the triangle "
                          "1, 1.33, 1.48, 1.55, 1.58 -> 8/5"));
  gallery.add("52_koch_overlay.png", to_rgb(overlay),
              "Levels 0 (dark) to 4 (light) nested: each level adds a band of bumps around the one before");
  const PictureFrame curve_frame{900, 300, 10, {0.0, -0.05, 1.0, 1.0 / 3.0}};
  DrawStyle style;
  style.antialias = true;
  style.line_width = 1.2;
  gallery.add("52_koch_curve.png", to_rgb(draw_curve(koch_curve(6), false, curve_frame, style)),
              "The Koch curve at depth 6: 4097 points, length (4/3)^6 = 5.62, dimension log 4 / log 3 = 1.2619");
}
