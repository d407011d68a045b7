#pragma once
// The SVG front end (the svg module, above raster2d): a strict parser for the subset of SVG 1.1 a person draws by hand,
// and a renderer that turns it into raster2d's fill_path/stroke_path calls (docs/svg.md lists the subset).
//
// parse_svg() reads the document into shapes in user coordinates: every shape keeps the product of its ancestors'
// `transform` lists (a matrix stack, CTM = CTM * T, so the transform written last acts first) and its resolved style.
// render_svg() maps the root's viewBox onto the image (preserveAspectRatio), flattens curves within a tolerance in
// device pixels and fills and strokes every shape in document order. Anything malformed throws InvalidInput naming
// file:line:column and what was expected; unsupported elements and attributes are never dropped silently but counted
// in SvgDocument::warnings.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/parse.hpp"
#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"
#include "tessera/raster2d/path.hpp"

namespace tessera {

/// One piece of a subpath in absolute user coordinates: a line to `end`, or a quadratic (control c1) or cubic
/// (controls c1, c2) Bezier to `end`. The parser resolves H/V, the smooth forms S/T, relative commands and elliptical
/// arcs (as cubics) into these three kinds.
struct SvgSegment {
  enum class Kind { line, quadratic, cubic };
  Kind kind = Kind::line;
  Vec2 c1{0.0}, c2{0.0};
  Vec2 end{0.0};
};

/// A subpath: where it starts, its segments, and whether it was closed with Z.
struct SvgSubpath {
  Vec2 start{0.0};
  std::vector<SvgSegment> segments;
  bool closed = false;
};

/// A paint: std::nullopt is `none`, otherwise straight RGBA (alpha from rgba(), 1 for every other color syntax).
using SvgPaint = std::optional<Vec4f>;

/// The presentation of one shape after inheritance, presentation attributes and style="..." (which wins).
struct SvgStyle {
  SvgPaint fill = Vec4f(0, 0, 0, 1);
  SvgPaint stroke;
  float fill_opacity = 1;
  float stroke_opacity = 1;
  float opacity = 1;  ///< the element's opacity times its ancestors' (group opacity approximated per element)
  FillRule fill_rule = FillRule::non_zero;
  StrokeStyle stroke_style;  ///< width in user units
};

/// One painted element (rect, circle, ellipse, line, polyline, polygon or path).
struct SvgShape {
  std::string element;               ///< the element's name, e.g. "rect"
  long line = 0;                     ///< line of its start tag in the source
  std::vector<SvgSubpath> subpaths;  ///< its geometry in user coordinates
  Mat3 transform{1.0};  ///< user coordinates to the root's (viewBox) coordinates: the product of the transform lists
  SvgStyle style;
};

/// The root's preserveAspectRatio: align factors 0 (min), 0.5 (mid) or 1 (max); `none` stretches.
struct SvgAspect {
  bool none = false;
  double align_x = 0.5, align_y = 0.5;
  bool slice = false;  ///< slice (cover the viewport) instead of meet (fit inside it)
};

/// A parsed SVG document.
struct SvgDocument {
  std::string source;                   ///< name used in messages (the file name)
  std::optional<double> width, height;  ///< the root's width and height in px, when given
  std::optional<Vec4> view_box;         ///< min-x, min-y, width, height
  SvgAspect aspect;
  std::vector<SvgShape> shapes;       ///< in painting order
  std::vector<std::string> warnings;  ///< one line each, e.g. "unsupported SVG elements ignored: text (3)"
};

/// Parses an SVG document held in memory; `source_name` prefixes every error ("a.svg:12:5: expected '>'").
/// Throws InvalidInput for malformed XML, a root that is not <svg>, bad attribute values (numbers, colors, path data,
/// transforms), units other than px, and negative sizes.
SvgDocument parse_svg(std::string_view text, const std::string& source_name);

/// Reads and parses an SVG file. Throws IoError when it cannot be read, InvalidInput as parse_svg.
SvgDocument load_svg(const std::filesystem::path& path);

/// Parses SVG path data (the `d` attribute: M L H V C S Q T A Z, absolute and relative, implicit repeats, compact
/// numbers such as "1.5.5", "-1-2", "1e-3"). Arcs follow the SVG 1.1 implementation notes F.6 (endpoint to center
/// conversion, out-of-range radii scaled up) and become cubics of at most 45 degrees each. Empty data gives no
/// subpaths. Throws InvalidInput "character N: what was expected".
std::vector<SvgSubpath> parse_svg_path_data(std::string_view d);

/// Parses a `transform` list (matrix, translate, scale, rotate(a [cx cy]), skewX, skewY; angles in degrees) into
/// one matrix: "T1 T2" gives T1 * T2, exactly as MatrixStack::multiply applied in order. Throws InvalidInput.
Mat3 parse_svg_transform(std::string_view text);

/// Parses a color: #rgb, #rrggbb, rgb(r, g, b) with integers or percentages, rgba(r, g, b, a), or one of the 147
/// CSS color keywords (case-insensitive). Channels are clamped to [0, 1]. Throws InvalidInput for anything else.
Vec4f parse_svg_color(std::string_view text);

/// How a document becomes an image.
struct SvgRenderOptions {
  int width = 0, height = 0;     ///< output size in pixels; 0 takes the document's (see svg_output_size)
  bool antialias = true;         ///< area coverage; false fills pixels whose center is inside
  Vec4f background{0, 0, 0, 0};  ///< straight RGBA the image starts with (transparent by default)
  double tolerance = 0.1;        ///< curve flattening tolerance in device pixels
};

/// The image size render_svg uses: the options' when set, otherwise the root's width/height (rounded up), falling back
/// on the viewBox size. Throws InvalidInput when neither is known or a size is outside [1, 65536].
Size2 svg_output_size(const SvgDocument& document, const SvgRenderOptions& options);

/// The viewport transform of the root: maps root (viewBox) coordinates onto a width x height image following
/// preserveAspectRatio (default xMidYMid meet). Without a viewBox, the root's width x height box plays its part; with
/// neither, it is the identity. Precondition: width, height > 0.
Mat3 svg_viewport_transform(const SvgDocument& document, int width, int height);

/// A flattened subpath in device coordinates.
struct SvgPolyline {
  std::vector<Vec2> points;
  bool closed = false;
};

/// Maps subpaths through `to_device` (control points map exactly: Bezier curves are affine invariant) and flattens
/// each curve within `tolerance` device pixels by the curves module's flatten (as flatten_cubic; quadratics elevated).
std::vector<SvgPolyline> flatten_svg_subpaths(const std::vector<SvgSubpath>& subpaths, const Mat3& to_device,
                                              double tolerance);

/// Renders the document: each shape's fill (its fill-rule) then its stroke (the outline of stroke_path computed in
/// the shape's user space, so non-uniform scales and skews shape the pen as SVG requires), composited source-over with
/// alpha = paint alpha x fill- or stroke-opacity x opacity. Throws InvalidInput for a bad size (svg_output_size) or
/// coordinates that overflow after the transforms.
ImageRGBA render_svg(const SvgDocument& document, const SvgRenderOptions& options);

}  // namespace tessera
