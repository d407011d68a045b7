// Example 08: every Canvas primitive in one picture, in a 4 x 4 grid of 200 x 200 cells:
//   row 1: rect, ellipse, triangle, quad;
//   row 2: arc in Open, Chord and Pie modes; a shape of bezier_vertex and quadratic_vertex with a contour hole;
//   row 3: thick strokes with miter, round and bevel joins; butt, round and square caps (thin guide lines mark the
//          true end points);
//   row 4: the same ellipse and rotated lines without and with antialiasing (no_smooth / smooth); points; shapes
//          under push/pop, rotate, scale and shear; begin_shape(TriangleFan).
#include <cmath>

#include "gallery.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/canvas.hpp"

namespace {

using namespace tessera;

// Runs draw() with the origin at the center of cell (col, row).
template <class F>
void cell(Canvas& c, int col, int row, F&& draw) {
  c.push_matrix();
  c.translate(200 * col + 100, 200 * row + 100);
  draw();
  c.pop_matrix();
}

}  // namespace

TESSERA_EXAMPLE(ex08_canvas_shapes, "08_canvas_shapes", "Every canvas primitive, stroke style and transform") {
  Canvas c(800, 800);
  c.background(rgb255(250, 250, 245));
  c.stroke(rgb255(30, 30, 30));
  c.stroke_weight(3);
  c.fill(rgb255(240, 170, 60));

  cell(c, 0, 0, [&] { c.rect(-70, -50, 140, 100); });
  cell(c, 1, 0, [&] { c.ellipse(0, 0, 150, 90); });
  cell(c, 2, 0, [&] { c.triangle(-70, 60, 0, -70, 70, 60); });
  cell(c, 3, 0, [&] { c.quad(-70, -40, 50, -70, 70, 60, -30, 40); });

  c.fill(rgb255(90, 170, 120));
  const ArcMode modes[] = {ArcMode::open, ArcMode::chord, ArcMode::pie};
  for (int i = 0; i < 3; ++i) cell(c, i, 1, [&] { c.arc(0, 0, 140, 140, 0.3, 0.3 + 1.5 * kPi, modes[i]); });
  cell(c, 3, 1, [&] {
    c.begin_shape();
    c.vertex(-70, 60);
    c.bezier_vertex(-90, -80, 90, -80, 70, 60);
    c.quadratic_vertex(0, 20, -70, 60);
    c.begin_contour();
    c.vertex(-15, -10);
    c.vertex(-15, 15);
    c.vertex(15, 15);
    c.vertex(15, -10);
    c.end_contour();
    c.end_shape(true);
  });

  c.no_fill();
  c.stroke(rgb255(40, 60, 160));
  c.stroke_weight(18);
  const LineJoin joins[] = {LineJoin::miter, LineJoin::round, LineJoin::bevel};
  for (int i = 0; i < 3; ++i)
    cell(c, i, 2, [&] {
      c.stroke_join(joins[i]);
      c.begin_shape();
      c.vertex(-70, 50);
      c.vertex(-20, -50);
      c.vertex(30, 50);
      c.vertex(70, -20);
      c.end_shape();
    });
  c.stroke_join(LineJoin::miter);
  const LineCap caps[] = {LineCap::butt, LineCap::round, LineCap::square};
  cell(c, 3, 2, [&] {
    for (int i = 0; i < 3; ++i) {
      c.stroke(rgb255(40, 60, 160));
      c.stroke_weight(18);
      c.stroke_cap(caps[i]);
      c.line(-50, -50 + 50 * i, 50, -50 + 50 * i);
    }
    c.stroke(rgb255(220, 40, 40));
    c.stroke_weight(1);
    c.line(-50, -80, -50, 80);
    c.line(50, -80, 50, 80);
  });
  c.stroke_cap(LineCap::round);

  c.stroke(rgb255(30, 30, 30));
  c.stroke_weight(1);
  c.fill(rgb255(200, 80, 120));
  for (int i = 0; i < 2; ++i)
    cell(c, i, 3, [&] {
      i == 0 ? c.no_smooth() : c.smooth();
      c.ellipse(0, -35, 120, 70);
      for (int k = 0; k < 6; ++k) c.line(-80, 30 + 8 * k, 80, 40 + 12 * k);
    });
  c.smooth();
  cell(c, 2, 3, [&] {
    c.fill(rgb255(120, 120, 220, 180));
    c.push_matrix();
    c.rotate(kPi / 8);
    c.rect(-70, -70, 60, 60);
    c.pop_matrix();
    c.push_matrix();
    c.translate(40, -40);
    c.scale(0.5, 1.5);
    c.ellipse(0, 0, 60, 40);
    c.pop_matrix();
    c.push_matrix();
    c.translate(-40, 40);
    c.shear_x(kPi / 6);
    c.rect(-25, -25, 50, 50);
    c.pop_matrix();
    c.stroke_weight(6);
    for (int k = 0; k < 5; ++k) c.point(20 + 12 * k, 50 + 5 * k);
    c.stroke_weight(1);
  });
  cell(c, 3, 3, [&] {
    c.fill(rgb255(250, 200, 80));
    c.begin_shape(ShapeKind::triangle_fan);
    c.vertex(0, 0);
    for (int k = 0; k <= 8; ++k) c.vertex(75 * std::cos(kPi * k / 8), -75 * std::sin(kPi * k / 8));
    c.end_shape();
  });

  gallery.add("08_canvas_shapes.png", to_rgba8(c.image()),
              "Canvas primitives: rect, ellipse, triangle, quad; arcs Open/Chord/Pie and a Bezier shape with a hole; "
              "miter/round/bevel joins and butt/round/square caps; no_smooth vs smooth, transforms, points, a "
              "triangle fan");
}
