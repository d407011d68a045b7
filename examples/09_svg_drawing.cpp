// 09: an SVG drawing through the canvas's SVG front end, with and without antialiasing.
// The drawing (examples/data/tiger-lite.svg) is embedded at build time, so the gallery needs no source tree.
#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/svg/svg.hpp"
#include "tiger_lite_svg.hpp"

TESSERA_EXAMPLE(ex09_svg_drawing, "09_svg_drawing", "An SVG drawing rendered by the canvas") {
  const tessera::SvgDocument drawing = tessera::parse_svg(tessera::examples::kTigerLiteSvg, "tiger-lite.svg");
  tessera::SvgRenderOptions options;
  options.background = {1, 1, 1, 1};
  gallery.add("09_svg_antialiased.png", tessera::to_rgba8(tessera::render_svg(drawing, options)),
              "tiger-lite.svg rendered with exact-area antialiasing (compare: rsvg-convert within 0.4% RMSE)");
  options.antialias = false;
  gallery.add("09_svg_aliased.png", tessera::to_rgba8(tessera::render_svg(drawing, options)),
              "The same drawing with --no-antialias: a pixel is filled iff its center is inside");
}
