#pragma once
// The notes' self-similar fractals as geometry, built to a given depth (level 0 is the starting shape), all inside
// the unit square [0, 1]^2 (the snowflake pokes out a little) with y up:
//   Cantor set (1883):       remove the open middle third of every segment; 2^n segments of length 3^-n
//   Cantor dust (2D):        the Cantor set times itself; 4^n squares of side 3^-n
//   Sierpinski carpet (1916): remove the middle ninth of every square; 8^n squares of side 3^-n
//   Sierpinski triangle:     remove the middle quarter of every triangle; 3^n triangles
//   von Koch curve (1904):   replace the middle third of every segment by two sides of an equilateral triangle
//   Hilbert and Peano curves (1890/1891): space-filling curves through the centers of a 2^n x 2^n / 3^n x 3^n grid
// The measures the notes state (Cantor (2/3)^n -> 0, carpet (8/9)^n -> 0, Koch length (4/3)^n -> infinity, snowflake
// area -> 8/5 of the triangle) are given in closed form beside the geometry so that tests can compare the two.
#include <cstdint>
#include <vector>

#include "tessera/math/types.hpp"

namespace tessera {

/// A closed interval [a, b] of the real line.
struct Interval {
  double a, b;
};

/// An axis-aligned rectangle [x, x + w] x [y, y + h].
struct Rect {
  double x, y, w, h;
};

/// A triangle by its corners, counterclockwise.
struct Triangle2 {
  Vec2 a, b, c;
};

// Each constructor caps the depth so that its output stays below about five million elements; a depth outside
// [0, cap] throws InvalidInput naming the cap.

/// The depth-n Cantor set in [0, 1]: 2^n intervals of length 3^-n, left to right. Depth at most 20.
std::vector<Interval> cantor_set(int depth);

/// The depth-n Cantor dust in [0, 1]^2 (Cantor set x Cantor set): 4^n squares of side 3^-n.
/// Depth at most 10.
std::vector<Rect> cantor_dust(int depth);

/// The depth-n Sierpinski carpet in [0, 1]^2: the 8^n squares of side 3^-n that remain.
/// Depth at most 7.
std::vector<Rect> sierpinski_carpet(int depth);

/// The depth-n Sierpinski triangle: the 3^n triangles that remain of the equilateral triangle with base [0, 1] on
/// the x axis. Depth at most 12.
std::vector<Triangle2> sierpinski_triangle(int depth);

/// The depth-n von Koch curve from a to b: 4^n + 1 points; the bumps lie to the left of a -> b.
/// Depth at most 10.
std::vector<Vec2> koch_curve(int depth, Vec2 a = {0, 0}, Vec2 b = {1, 0});

/// The depth-n von Koch snowflake on the equilateral triangle of side 1 centered at (0.5, 0.5): a closed polygon
/// (first point not repeated) of 3 * 4^n points, counterclockwise. Depth at most 10.
std::vector<Vec2> koch_snowflake(int depth);

/// The depth-n Hilbert curve: the 4^n centers of a 2^n x 2^n grid of the unit square in curve order, from the
/// bottom-left cell to the bottom-right one; consecutive points are grid neighbours. Depth at most 10.
std::vector<Vec2> hilbert_curve(int depth);

/// The depth-n Peano curve (Peano's serpentine ordering): the 9^n centers of a 3^n x 3^n grid in curve order, from
/// the bottom-left cell to the top-right one; consecutive points are grid neighbours. Depth at most 7.
std::vector<Vec2> peano_curve(int depth);

/// Length of an open polyline.
double polyline_length(const std::vector<Vec2>& points);
/// Signed area of a closed polygon (shoelace formula; positive when counterclockwise).
double polygon_area(const std::vector<Vec2>& polygon);

/// Closed forms of the notes: total length of the depth-n Cantor set, (2/3)^n.
double cantor_measure(int depth);
/// Area left of the unit carpet at depth n, (8/9)^n.
double carpet_area(int depth);
/// Area left of the Sierpinski triangle at depth n, as a fraction of the triangle: (3/4)^n.
double sierpinski_triangle_fraction(int depth);
/// Length of the depth-n Koch curve over a unit segment, (4/3)^n.
double koch_length(int depth);
/// Area of the depth-n snowflake over the area of its starting triangle: 1 + (3/5)(1 - (4/9)^n), -> 8/5.
double snowflake_area_ratio(int depth);

/// The Hausdorff-Besicovitch (similarity) dimension D = log(copies) / log(scale) of a set made of `copies` copies of
/// itself, each scaled by 1/scale (the notes: Koch 4 copies at 1/3 -> 1.2619). Throws InvalidInput unless
/// copies >= 1 and scale > 1.
double similarity_dimension(double copies, double scale);

}  // namespace tessera
