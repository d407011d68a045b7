// Example 53: the notes' "remove the middle" fractals. Cantor (1883): remove the middle third of a segment, then of
// each piece, ... (measure (2/3)^n -> 0, "dust"). Sierpinski carpet (1916): remove the middle ninth of a square, then
// of the other eight, ... (area (8/9)^n -> 0, still one unbroken object). The Sierpinski triangle removes the middle
// quarter of a triangle. Each picture gives the similarity dimension D = log(copies) / log(scale).
#include "gallery.hpp"
#include "tessera/fractal/draw.hpp"
#include "tessera/fractal/self_similar.hpp"
#include "tessera/image/image_io.hpp"

TESSERA_EXAMPLE(ex53_sierpinski_cantor, "53_sierpinski_cantor", "Sierpinski carpet and triangle, Cantor set and dust") {
  using namespace tessera;
  DrawStyle style;
  style.ink = {0.15f, 0.2f, 0.45f};
  gallery.add("53_sierpinski_carpet.png", to_rgb(draw_polygons(as_polygons(sierpinski_carpet(5)), {729, 729}, style)),
              "Sierpinski carpet, depth 5: 32768 squares, area (8/9)^5 = 0.555, D = log 8 / log 3 = 1.8928");

  style.ink = {0.55f, 0.1f, 0.1f};
  style.antialias = true;
  const PictureFrame triangle_frame{740, 660, 10, {0.0, 0.0, 1.0, 0.8660254037844386 * 1.0}};
  gallery.add("53_sierpinski_triangle.png",
              to_rgb(draw_polygons(as_polygons(sierpinski_triangle(7)), triangle_frame, style)),
              "Sierpinski triangle, depth 7: 2187 triangles, area (3/4)^7 = 0.133, D = log 3 / log 2 = 1.585");

  // The Cantor set's construction: level k as a bar in row k.
  std::vector<Rect> bars;
  const int levels = 6;
  for (int k = 0; k <= levels; ++k)
    for (const Interval& i : cantor_set(k))
      bars.push_back({i.a, 1.0 - (k + 0.8) / (levels + 1), i.b - i.a, 0.45 / (levels + 1)});
  style.ink = {0.1f, 0.1f, 0.1f};
  style.antialias = false;
  gallery.add("53_cantor_set.png", to_rgb(draw_polygons(as_polygons(bars), {745, 300, 8, {0, 0, 1, 1}}, style)),
              "Cantor set, levels 0-6: 2^k pieces of length 3^-k, measure (2/3)^k -> 0, D = log 2 / log 3 = 0.6309");

  style.ink = {0.1f, 0.35f, 0.2f};
  gallery.add("53_cantor_dust.png", to_rgb(draw_polygons(as_polygons(cantor_dust(4)), {745, 745, 8}, style)),
              "Cantor dust (Cantor set x Cantor set), depth 4: 256 squares, D = log 4 / log 3 = 1.2619");
}
