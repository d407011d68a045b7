// Example 40: Bezier curves as the notes draw them. A cubic with its control polygon and convex hull, and de
// Casteljau's construction at t = 1/2 (midpoints of the legs, midpoints of those, and their midpoint Q(1/2)) and at t =
// 3/4; the two halves of the subdivision at 1/2, each a Bezier curve of its own; and a chain of cubics made C1 by
// reflecting each segment's last leg through the joint.
#include <string>

#include "gallery.hpp"
#include "tessera/curves/figure.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera::examples {
namespace {

// The figure's SVG next to the PNG the gallery shows, both from the same text (raster2d renders the PNG).
void add_figure(Gallery& gallery, const std::string& stem, const CurveFigure& figure, const std::string& caption) {
  const std::string svg = curve_figure_svg(figure);
  gallery.add(stem + ".png", to_rgb(render_svg(parse_svg(svg, stem), SvgRenderOptions{})), caption);
}

}  // namespace
}  // namespace tessera::examples

TESSERA_EXAMPLE(ex40_bezier_curves, "40_bezier_curves",
                "Bezier curves: de Casteljau construction, subdivision, chains") {
  using namespace tessera;
  const Bezier2 notes = cubic(Vec2(40, 340), Vec2(90, 60), Vec2(330, 40), Vec2(370, 330));
  for (const double t : {0.5, 0.75}) {
    CurveFigure figure{.width = 400, .height = 380, .curves = {notes}};
    figure.construction = t;
    const std::string name = t == 0.5 ? "half" : "three_quarters";
    examples::add_figure(gallery, "40_de_casteljau_" + name, figure,
                         t == 0.5 ? "De Casteljau at t = 1/2: midpoints of the three legs (green), of those (yellow), "
                                    "and Q(1/2) (red); the curve stays in the convex hull (blue) of P1..P4."
                                  : "De Casteljau at t = 3/4: the same construction with 3/4-points instead of "
                                    "midpoints gives Q(3/4).");
  }
  CurveFigure halves{.width = 400, .height = 380, .curves = {notes}, .show_hull = false};
  halves.construction = 0.5;
  halves.show_split = true;
  examples::add_figure(gallery, "40_subdivision", halves,
                       "Subdivision at 1/2: the outer points of the construction are the control polygons of the "
                       "left (red) and right (blue) halves, each a cubic Bezier curve that reproduces its half.");
  // A C1 chain: each next segment starts with the reflection of the previous one's last control point.
  std::vector<Bezier2> chain{cubic(Vec2(30, 200), Vec2(60, 60), Vec2(150, 60), Vec2(170, 190))};
  chain.push_back(c1_continuation(chain.back(), Vec2(280, 340), Vec2(300, 200)));
  chain.push_back(c1_continuation(chain.back(), Vec2(440, 60), Vec2(560, 220)));
  const CurveFigure chained{.width = 600, .height = 380, .curves = chain};
  examples::add_figure(gallery, "40_c1_chain", chained,
                       "A chain of three cubics joined with C1 continuity: at each joint the neighbouring control "
                       "points are collinear and equally far from it (" +
                           std::string(chain_continuity<Vec2>(chain) == Continuity::c1 ? "checked: C1" : "not C1") +
                           ").");
}
