// The SVG document parser: the builder that turns the XML reader's events (xml.hpp) into shapes with resolved styles
// and transforms.
#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "svg_syntax.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/math/matrix_stack.hpp"
#include "tessera/svg/svg.hpp"
#include "xml.hpp"

namespace tessera {
namespace {

using svg::SvgValueError;
using xml::Attribute;
using xml::Event;
// A paint as specified: currentColor is resolved when a shape is painted, from its `color` property.
struct PaintSpec {
  enum class Kind { none, color, current_color };
  Kind kind = Kind::none;
  Vec4f color{0, 0, 0, 1};
};

// The properties of the subset: all inherited except opacity and display (SVG 1.1 property index).
struct Properties {
  PaintSpec fill{PaintSpec::Kind::color, {0, 0, 0, 1}};
  PaintSpec stroke;
  Vec4f color{0, 0, 0, 1};
  float fill_opacity = 1, stroke_opacity = 1;
  FillRule fill_rule = FillRule::non_zero;
  StrokeStyle stroke_style;
  bool visible = true;
};

// One open element.
struct Frame {
  Properties properties;
  float own_opacity = 1;    // the element's opacity property
  float group_opacity = 1;  // product of own_opacity down from the root
  bool rendering = true;    // false inside a subtree that draws nothing (unsupported, display:none, title, ...)
  bool shape = false;       // a shape element: its children are never rendered
};

enum class ElementKind { container, shape, descriptive, unsupported };

ElementKind element_kind(std::string_view name) {
  static constexpr std::string_view kShapes[] = {"rect", "circle", "ellipse", "line", "polyline", "polygon", "path"};
  if (name == "g" || name == "a") return ElementKind::container;
  if (std::find(std::begin(kShapes), std::end(kShapes), name) != std::end(kShapes)) return ElementKind::shape;
  if (name == "title" || name == "desc" || name == "metadata") return ElementKind::descriptive;
  return ElementKind::unsupported;
}

// Properties that change the picture but are unsupported: counted as warnings when not "none".
bool is_unsupported_property(std::string_view name) {
  static constexpr std::string_view kNames[] = {"stroke-dasharray", "clip-path",    "mask",       "filter",
                                                "marker",           "marker-start", "marker-mid", "marker-end"};
  return std::find(std::begin(kNames), std::end(kNames), name) != std::end(kNames);
}

// Counts by name in order of first appearance, for the warning lines.
class Tally {
 public:
  void add(std::string_view name) {
    for (auto& [n, count] : counts_)
      if (n == name) return void(++count);
    counts_.emplace_back(std::string(name), 1);
  }
  bool empty() const { return counts_.empty(); }
  std::string list() const {
    std::string out;
    for (const auto& [n, count] : counts_) out += fmt::format("{}{} ({})", out.empty() ? "" : ", ", n, count);
    return out;
  }

 private:
  std::vector<std::pair<std::string, int>> counts_;
};

class DocumentBuilder {
 public:
  DocumentBuilder(std::string_view text, const std::string& source_name)
      : map_(text, source_name), reader_(text, map_, "svg") {}

  SvgDocument build() {
    document_.source = map_.name();
    Event event = reader_.next();
    if (event.name != "svg")
      fail(event.offset, fmt::format("expected <svg> as the root element, got <{}>", event.name));
    root(event);
    while ((event = reader_.next()).kind != Event::Kind::eof) {
      if (event.kind == Event::Kind::start)
        start_element(event);
      else
        end_element();
    }
    if (!unsupported_elements_.empty())
      document_.warnings.push_back("unsupported SVG elements ignored: " + unsupported_elements_.list());
    if (!unsupported_attributes_.empty())
      document_.warnings.push_back("unsupported SVG attributes ignored: " + unsupported_attributes_.list());
    if (!paint_servers_.empty())
      document_.warnings.push_back("unsupported paint servers (url(...)) replaced by their fallback color or none: " +
                                   paint_servers_.list());
    return std::move(document_);
  }

 private:
  [[noreturn]] void fail(size_t offset, const std::string& what) const { map_.fail(offset, what); }

  static const Attribute* find(const Event& e, std::string_view name) {
    for (const Attribute& a : e.attributes)
      if (a.name == name) return &a;
    return nullptr;
  }

  // Runs a value grammar on `text`, which starts `base` bytes into attribute `a`'s value, turning its SvgValueError
  // into an error at file:line:column (the exact column when the value holds no entity).
  template <class Parse>
  auto checked(const Event& e, const Attribute& a, std::string_view context, size_t base, std::string_view text,
               Parse&& parse) const {
    try {
      return parse(text);
    } catch (const SvgValueError& error) {
      // The value grammars quote the value through printable() (the CLI's --color reaches them directly).
      map_.fail_escaped(a.verbatim ? a.value_offset + base + error.offset() : a.value_offset,
                        fmt::format("{} of <{}>: {}", printable(context), printable(e.name), error.detail()));
    }
  }
  template <class Parse>
  auto checked(const Event& e, const Attribute& a, Parse&& parse) const {
    return checked(e, a, fmt::format("attribute '{}'", a.name), 0, a.value, std::forward<Parse>(parse));
  }

  // A length attribute (px or unitless); `fallback` when absent. Negative values throw when !allow_negative.
  double length(const Event& e, std::string_view name, double fallback, bool allow_negative = true) const {
    const Attribute* a = find(e, name);
    if (!a) return fallback;
    const double v = checked(e, *a, svg::parse_length);
    if (!allow_negative && v < 0)
      fail(a->value_offset, fmt::format("attribute '{}' of <{}> must not be negative, got {}", name, e.name, v));
    return v;
  }

  void root(const Event& e) {
    Frame frame;
    if (find(e, "width")) document_.width = length(e, "width", 0, false);
    if (find(e, "height")) document_.height = length(e, "height", 0, false);
    if (const Attribute* a = find(e, "viewBox")) {
      const std::vector<double> v = checked(e, *a, svg::parse_number_list);
      if (v.size() != 4)
        fail(a->value_offset, fmt::format("attribute 'viewBox' of <svg>: expected 4 numbers (min-x min-y width "
                                          "height), got {}",
                                          v.size()));
      if (v[2] <= 0 || v[3] <= 0)
        fail(a->value_offset, fmt::format("attribute 'viewBox' of <svg>: width and height must be positive, got "
                                          "{} and {}",
                                          v[2], v[3]));
      document_.view_box = Vec4(v[0], v[1], v[2], v[3]);
    }
    if (const Attribute* a = find(e, "preserveAspectRatio")) document_.aspect = aspect(e, *a);
    if (find(e, "transform")) unsupported_attributes_.add("transform on <svg>");
    bool display = true;
    apply_presentation(e, Frame{}, frame, display);
    frame.group_opacity = frame.own_opacity;
    frame.rendering = display;
    frames_.push_back(frame);
    stack_.push();
  }

  SvgAspect aspect(const Event& e, const Attribute& a) const {
    return checked(e, a, [](std::string_view text) {
      SvgAspect result;
      size_t pos = 0;
      std::vector<std::pair<std::string_view, size_t>> words;
      for (std::string_view part : split(text, ' ')) {
        if (!part.empty()) words.emplace_back(part, pos);
        pos += part.size() + 1;
      }
      if (!words.empty() && words[0].first == "defer") words.erase(words.begin());
      if (words.empty() || words.size() > 2)
        throw SvgValueError(0,
                            "expected an alignment such as xMidYMid and "
                            "optionally meet or slice");
      const auto [align, align_pos] = words[0];
      const auto factor = [](std::string_view m) {
        return m == "Min" ? 0.0 : m == "Mid" ? 0.5 : m == "Max" ? 1.0 : -1;
      };
      if (align == "none") {
        result.none = true;
      } else {
        const bool ok = align.size() == 8 && align[0] == 'x' && align[4] == 'Y' && factor(align.substr(1, 3)) >= 0 &&
                        factor(align.substr(5, 3)) >= 0;
        if (!ok)
          throw SvgValueError(align_pos, fmt::format("expected none or x(Min|Mid|Max)Y(Min|Mid|Max), got '{}'", align));
        result.align_x = factor(align.substr(1, 3));
        result.align_y = factor(align.substr(5, 3));
      }
      if (words.size() == 2) {
        if (words[1].first != "meet" && words[1].first != "slice")
          throw SvgValueError(words[1].second, fmt::format("expected meet or slice, got '{}'", words[1].first));
        result.slice = words[1].first == "slice";
      }
      return result;
    });
  }

  void start_element(const Event& e) {
    const Frame& parent = frames_.back();
    Frame frame = parent;
    frame.own_opacity = 1;
    frame.shape = false;
    ElementKind kind = element_kind(e.name);
    if (parent.shape && kind != ElementKind::descriptive) kind = ElementKind::unsupported;  // never rendered
    if (parent.rendering && kind == ElementKind::unsupported) unsupported_elements_.add(e.name);
    bool display = true;
    if (parent.rendering && (kind == ElementKind::container || kind == ElementKind::shape))
      apply_presentation(e, parent, frame, display);
    frame.rendering = parent.rendering && display && (kind == ElementKind::container || kind == ElementKind::shape);
    frame.shape = kind == ElementKind::shape;
    frame.group_opacity = parent.group_opacity * frame.own_opacity;
    stack_.push();
    if (frame.rendering)
      if (const Attribute* a = find(e, "transform")) stack_.multiply(checked(e, *a, parse_svg_transform));
    frames_.push_back(frame);
    if (frame.rendering && frame.shape) add_shape(e, frame);
  }

  void end_element() {
    frames_.pop_back();
    stack_.pop();
  }

  // Presentation attributes first, then the style attribute's declarations, which take precedence.
  void apply_presentation(const Event& e, const Frame& parent, Frame& frame, bool& display) {
    for (const Attribute& a : e.attributes)
      if (a.name != "style") property(e, a, a.name, 0, a.value, parent, frame, display);
    const Attribute* style = find(e, "style");
    if (!style) return;
    size_t pos = 0;
    for (std::string_view declaration : split(style->value, ';')) {
      const size_t start = pos;
      pos += declaration.size() + 1;
      if (trim(declaration).empty()) continue;
      const size_t colon = declaration.find(':');
      if (colon == std::string_view::npos) {
        const size_t lead = declaration.size() - declaration.substr(declaration.find_first_not_of(' ')).size();
        fail(style->verbatim ? style->value_offset + start + lead : style->value_offset,
             fmt::format("style of <{}>: expected 'property: value', got '{}'", e.name, trim(declaration)));
      }
      std::string name(trim(declaration.substr(0, colon)));
      std::transform(name.begin(), name.end(), name.begin(), [](char c) { return char(std::tolower(c)); });
      std::string_view value = declaration.substr(colon + 1);
      if (const size_t bang = value.find("!important"); bang != std::string_view::npos) value = value.substr(0, bang);
      property(e, *style, name, start + colon + 1, value, parent, frame, display);
    }
  }

  // Applies one property. `value` starts `base` bytes into attribute `a`'s value (for error columns).
  void property(const Event& e, const Attribute& a, std::string_view name, size_t base, std::string_view value,
                const Frame& parent, Frame& frame, bool& display) {
    const std::string context =
        a.name == "style" ? fmt::format("property '{}' in style", name) : fmt::format("attribute '{}'", name);
    const auto parse = [&](auto&& grammar) { return checked(e, a, context, base, value, grammar); };
    const auto keyword = [&](std::initializer_list<std::string_view> allowed) {
      return parse([&](std::string_view text) {
        const std::string_view word = trim(text);
        for (size_t i = 0; i < allowed.size(); ++i)
          if (word == allowed.begin()[i]) return i;
        std::string list;
        for (std::string_view w : allowed) list += fmt::format("{}{}", list.empty() ? "" : ", ", w);
        throw SvgValueError(0, fmt::format("expected one of {}, got '{}'", list, word));
      });
    };
    Properties& p = frame.properties;
    if (trim(value) == "inherit") {
      if (name == "opacity") frame.own_opacity = parent.own_opacity;
      return;  // every other supported property is inherited already
    }
    if (name == "fill" || name == "stroke") {
      (name == "fill" ? p.fill : p.stroke) = parse([&](std::string_view text) { return paint(text); });
    } else if (name == "color") {
      p.color = parse(parse_svg_color);
    } else if (name == "fill-opacity") {
      p.fill_opacity = parse(svg::parse_opacity);
    } else if (name == "stroke-opacity") {
      p.stroke_opacity = parse(svg::parse_opacity);
    } else if (name == "opacity") {
      frame.own_opacity = parse(svg::parse_opacity);
    } else if (name == "fill-rule") {
      p.fill_rule = keyword({"nonzero", "evenodd"}) == 0 ? FillRule::non_zero : FillRule::even_odd;
    } else if (name == "stroke-width") {
      p.stroke_style.width = parse([](std::string_view text) {
        const double w = svg::parse_length(text);
        if (w < 0) throw SvgValueError(0, fmt::format("stroke width must not be negative, got {}", w));
        return w;
      });
    } else if (name == "stroke-linejoin") {
      static constexpr LineJoin kJoins[] = {LineJoin::miter, LineJoin::round, LineJoin::bevel};
      p.stroke_style.join = kJoins[keyword({"miter", "round", "bevel"})];
    } else if (name == "stroke-linecap") {
      static constexpr LineCap kCaps[] = {LineCap::butt, LineCap::round, LineCap::square};
      p.stroke_style.cap = kCaps[keyword({"butt", "round", "square"})];
    } else if (name == "stroke-miterlimit") {
      p.stroke_style.miter_limit = parse([](std::string_view text) {
        const double m = svg::parse_number(text);
        if (m < 1) throw SvgValueError(0, fmt::format("the miter limit must be at least 1, got {}", m));
        return m;
      });
    } else if (name == "visibility") {
      p.visible = keyword({"visible", "hidden", "collapse"}) == 0;
    } else if (name == "display") {
      display = trim(value) != "none";
    } else if (is_unsupported_property(name) && trim(value) != "none") {
      unsupported_attributes_.add(name);
    }
  }

  // none | currentColor | <color> | url(...) [fallback]
  PaintSpec paint(std::string_view text) {
    const std::string_view t = trim(text);
    if (t == "none") return {};
    if (t == "currentColor") return {PaintSpec::Kind::current_color, {}};
    if (t.substr(0, 4) == "url(") {
      const size_t close = t.find(')');
      if (close == std::string_view::npos) throw SvgValueError(text.find("url("), "expected ')' to close url(");
      paint_servers_.add(t.substr(0, close + 1));
      const std::string_view fallback = trim(t.substr(close + 1));
      return fallback.empty() ? PaintSpec{} : paint(fallback);
    }
    return {PaintSpec::Kind::color, parse_svg_color(text)};
  }

  static SvgPaint resolve(const PaintSpec& spec, const Properties& p) {
    if (spec.kind == PaintSpec::Kind::none) return std::nullopt;
    return spec.kind == PaintSpec::Kind::color ? spec.color : p.color;
  }

  void add_shape(const Event& e, const Frame& frame) {
    SvgShape shape;
    shape.element = e.name;
    shape.line = map_.line(e.offset);
    shape.subpaths = geometry(e);
    shape.transform = stack_.top();
    const Properties& p = frame.properties;
    shape.style = {resolve(p.fill, p),  resolve(p.stroke, p), p.fill_opacity, p.stroke_opacity,
                   frame.group_opacity, p.fill_rule,          p.stroke_style};
    if (p.visible && !shape.subpaths.empty()) document_.shapes.push_back(std::move(shape));
  }

  std::vector<SvgSubpath> geometry(const Event& e) const {
    std::vector<SvgSubpath> out;
    const auto closed_curve = [&](const Vec2& center, double rx, double ry) {
      SvgSubpath s{center + Vec2(rx, 0), {}, true};
      svg::append_arc_cubics(s.segments, center, rx, ry, 0, 0, 2 * kPi, s.start);
      out.push_back(std::move(s));
    };
    if (e.name == "path") {
      if (const Attribute* a = find(e, "d")) out = checked(e, *a, parse_svg_path_data);
    } else if (e.name == "rect") {
      const double x = length(e, "x", 0), y = length(e, "y", 0);
      const double w = length(e, "width", 0, false), h = length(e, "height", 0, false);
      double rx = length(e, "rx", 0, false), ry = length(e, "ry", 0, false);
      if (!find(e, "ry")) ry = rx;  // SVG 1.1 9.2: a missing radius takes the other one's value
      if (!find(e, "rx")) rx = ry;
      rx = std::min(rx, w / 2);
      ry = std::min(ry, h / 2);
      if (w == 0 || h == 0) return out;
      using Kind = SvgSegment::Kind;
      SvgSubpath s{{x + rx, y}, {}, true};
      const auto line = [&](double px, double py) {
        s.segments.push_back({Kind::line, Vec2(0.0), Vec2(0.0), {px, py}});
      };
      const auto corner = [&](double cx, double cy, double theta, double ex, double ey) {
        if (rx > 0 && ry > 0) svg::append_arc_cubics(s.segments, {cx, cy}, rx, ry, 0, theta, kPi / 2, {ex, ey});
      };
      line(x + w - rx, y);
      corner(x + w - rx, y + ry, -kPi / 2, x + w, y + ry);
      line(x + w, y + h - ry);
      corner(x + w - rx, y + h - ry, 0, x + w - rx, y + h);
      line(x + rx, y + h);
      corner(x + rx, y + h - ry, kPi / 2, x, y + h - ry);
      line(x, y + ry);
      corner(x + rx, y + ry, kPi, x + rx, y);
      out.push_back(std::move(s));
    } else if (e.name == "circle") {
      const double r = length(e, "r", 0, false);
      if (r > 0) closed_curve({length(e, "cx", 0), length(e, "cy", 0)}, r, r);
    } else if (e.name == "ellipse") {
      const double rx = length(e, "rx", 0, false), ry = length(e, "ry", 0, false);
      if (rx > 0 && ry > 0) closed_curve({length(e, "cx", 0), length(e, "cy", 0)}, rx, ry);
    } else if (e.name == "line") {
      const Vec2 end(length(e, "x2", 0), length(e, "y2", 0));
      out.push_back(
          {{length(e, "x1", 0), length(e, "y1", 0)}, {{SvgSegment::Kind::line, Vec2(0.0), Vec2(0.0), end}}, false});
    } else {  // polyline, polygon
      const Attribute* a = find(e, "points");
      const std::vector<double> v = a ? checked(e, *a, svg::parse_number_list) : std::vector<double>{};
      if (v.size() % 2 != 0)
        fail(a->value_offset, fmt::format("attribute 'points' of <{}>: expected pairs of coordinates, got {} numbers",
                                          e.name, v.size()));
      if (v.size() < 4) return out;
      SvgSubpath s{{v[0], v[1]}, {}, e.name == "polygon"};
      for (size_t i = 2; i < v.size(); i += 2)
        s.segments.push_back({SvgSegment::Kind::line, Vec2(0.0), Vec2(0.0), {v[i], v[i + 1]}});
      out.push_back(std::move(s));
    }
    return out;
  }

  xml::SourceMap map_;
  xml::Reader reader_;
  SvgDocument document_;
  std::vector<Frame> frames_;
  MatrixStack2 stack_;  // the CTM of the open elements: push per element, CTM = CTM * T for its transform
  Tally unsupported_elements_, unsupported_attributes_, paint_servers_;
};

}  // namespace

SvgDocument parse_svg(std::string_view text, const std::string& source_name) {
  return DocumentBuilder(text, source_name).build();
}

SvgDocument load_svg(const std::filesystem::path& path) { return parse_svg(read_file(path), path.string()); }

}  // namespace tessera
