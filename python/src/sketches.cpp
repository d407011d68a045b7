// The canvas (Processing's drawing calls) and sketches: Python classes or module-level setup()/draw() functions run
// by the same runner as the C++ sketches (libs/sketch), in a window or headless.
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/sketch/registry.hpp"
#include "tessera/sketch/runner.hpp"
#include "tessera/sketch/sketch.hpp"

namespace tessera::python {
namespace {

/// Forwards the runner's calls to the methods a Python subclass defines (python/tessera/sketch.py).
class PythonSketch : public Sketch {
 public:
  void setup() override { PYBIND11_OVERRIDE(void, Sketch, setup, ); }
  void draw() override { PYBIND11_OVERRIDE(void, Sketch, draw, ); }
  void mouse_pressed() override { PYBIND11_OVERRIDE(void, Sketch, mouse_pressed, ); }
  void mouse_released() override { PYBIND11_OVERRIDE(void, Sketch, mouse_released, ); }
  void mouse_dragged() override { PYBIND11_OVERRIDE(void, Sketch, mouse_dragged, ); }
  void mouse_moved() override { PYBIND11_OVERRIDE(void, Sketch, mouse_moved, ); }
  void mouse_wheel(double delta) override { PYBIND11_OVERRIDE(void, Sketch, mouse_wheel, delta); }
  void key_pressed() override { PYBIND11_OVERRIDE(void, Sketch, key_pressed, ); }
  void key_released() override { PYBIND11_OVERRIDE(void, Sketch, key_released, ); }
  void window_resized() override { PYBIND11_OVERRIDE(void, Sketch, window_resized, ); }
};

/// The canvas's picture as a float32 Image (H, W, 4) viewing its pixels (live: drawing changes it; copy() keeps it).
py::object canvas_image(const py::object& self) {
  const Canvas& c = self.cast<const Canvas&>();
  const py::array view(py::dtype::of<float>(), std::vector<py::ssize_t>{c.height(), c.width(), 4},
                       &c.image().pixels()[0][0], self);
  return view.attr("view")(py::module_::import("tessera").attr("Image"));
}

/// A color as the tuple (r, g, b, a) in [0, 1].
py::tuple rgba(const Vec4f& c) { return py::make_tuple(c.x, c.y, c.z, c.w); }

/// Processing's drawing calls with their overloads, on the Canvas.
void bind_canvas(py::module_& m) {
  py::enum_<ShapeKind>(m, "ShapeKind")
      .value("polygon", ShapeKind::polygon)
      .value("points", ShapeKind::points)
      .value("lines", ShapeKind::lines)
      .value("triangles", ShapeKind::triangles)
      .value("triangle_strip", ShapeKind::triangle_strip)
      .value("triangle_fan", ShapeKind::triangle_fan)
      .value("quads", ShapeKind::quads)
      .value("quad_strip", ShapeKind::quad_strip);
  py::enum_<ColorMode>(m, "ColorMode").value("rgb", ColorMode::rgb).value("hsb", ColorMode::hsb);
  py::enum_<ArcMode>(m, "ArcMode")
      .value("open", ArcMode::open)
      .value("chord", ArcMode::chord)
      .value("pie", ArcMode::pie);
  py::enum_<TextAlignX>(m, "TextAlignX")
      .value("left", TextAlignX::left)
      .value("center", TextAlignX::center)
      .value("right", TextAlignX::right);
  py::enum_<TextAlignY>(m, "TextAlignY")
      .value("baseline", TextAlignY::baseline)
      .value("top", TextAlignY::top)
      .value("center", TextAlignY::center)
      .value("bottom", TextAlignY::bottom);
  py::enum_<LineJoin>(m, "LineJoin")
      .value("miter", LineJoin::miter)
      .value("round", LineJoin::round)
      .value("bevel", LineJoin::bevel);
  py::enum_<LineCap>(m, "LineCap")
      .value("butt", LineCap::butt)
      .value("round", LineCap::round)
      .value("square", LineCap::square);
  py::enum_<MouseButton>(m, "MouseButton")
      .value("none", MouseButton::none)
      .value("left", MouseButton::left)
      .value("right", MouseButton::right)
      .value("center", MouseButton::center);

  using C = Canvas;
  py::class_<C>(m, "Canvas", R"(A Processing-style 2D drawing surface (docs/canvas.md): Processing's calls in
lower_case (background, fill, stroke, rect, ellipse, begin_shape, push_matrix, translate, color_mode, text, ...).
Colors take Processing's forms: gray, (gray, alpha), (v1, v2, v3), (v1, v2, v3, alpha) in the color_mode's ranges
(0..255 by default). `picture` is what it shows, an Image (H, W, 4) viewing its pixels (live: copy() keeps one).)")
      .def(py::init<int, int>(), py::arg("width"), py::arg("height"),
           "size(width, height): an opaque canvas of Processing's default gray (204); fill white, stroke black, weight "
           "1.")
      .def_property_readonly("width", &C::width, "Width in pixels.")
      .def_property_readonly("height", &C::height, "Height in pixels.")
      .def_property_readonly("picture", &canvas_image,
                             "What the canvas shows: an Image (H, W, 4) viewing its pixels (live; copy() keeps one).")
      .def("_repr_png_", [](const py::object& self) { return canvas_image(self).attr("_repr_png_")(); })
      .def("save", &C::save, py::arg("path"), "Writes the picture (write_image).")
      .def("background", py::overload_cast<double>(&C::background),
           "Clears the canvas to a color (gray, (gray, alpha), (v1, v2, v3), (v1, v2, v3, alpha) in the color mode).")
      .def("background", py::overload_cast<double, double>(&C::background))
      .def("background", py::overload_cast<double, double, double>(&C::background))
      .def("background", py::overload_cast<double, double, double, double>(&C::background))
      .def("fill", py::overload_cast<double>(&C::fill),
           "The color shapes are filled with (Processing's forms, as background).")
      .def("fill", py::overload_cast<double, double>(&C::fill))
      .def("fill", py::overload_cast<double, double, double>(&C::fill))
      .def("fill", py::overload_cast<double, double, double, double>(&C::fill))
      .def("no_fill", &C::no_fill, "Shapes are not filled.")
      .def("stroke", py::overload_cast<double>(&C::stroke),
           "The color of lines and outlines (Processing's forms, as background).")
      .def("stroke", py::overload_cast<double, double>(&C::stroke))
      .def("stroke", py::overload_cast<double, double, double>(&C::stroke))
      .def("stroke", py::overload_cast<double, double, double, double>(&C::stroke))
      .def("no_stroke", &C::no_stroke, "Shapes have no outline.")
      .def("stroke_weight", &C::stroke_weight, py::arg("weight"),
           "The width of lines and outlines, in user units (scaled by the matrix).")
      .def("stroke_join", &C::stroke_join, py::arg("join"),
           "How outline segments meet: LineJoin.miter, round or bevel.")
      .def("stroke_cap", &C::stroke_cap, py::arg("cap"), "How open lines end: LineCap.butt, round or square.")
      .def("smooth", &C::smooth, "Anti-aliased edges (the default).")
      .def("no_smooth", &C::no_smooth, "Aliased edges: a pixel is in or out.")
      .def("color_mode", py::overload_cast<ColorMode>(&C::color_mode),
           "How the color numbers read: ColorMode.rgb or hsb, with the maximum of each channel (255 by default).")
      .def("color_mode", py::overload_cast<ColorMode, double>(&C::color_mode))
      .def("color_mode", py::overload_cast<ColorMode, double, double, double, double>(&C::color_mode))
      .def(
          "color", [](const C& c, double g) { return rgba(c.color(g)); },
          "The color (r, g, b, a) in [0, 1] that these numbers give in the current color mode.")
      .def("color", [](const C& c, double g, double a) { return rgba(c.color(g, a)); })
      .def("color", [](const C& c, double v1, double v2, double v3) { return rgba(c.color(v1, v2, v3)); })
      .def("color", [](const C& c, double v1, double v2, double v3, double a) { return rgba(c.color(v1, v2, v3, a)); })
      .def("point", &C::point, py::arg("x"), py::arg("y"), "A point at (x, y) in the stroke color and weight.")
      .def("line", &C::line, py::arg("x0"), py::arg("y0"), py::arg("x1"), py::arg("y1"),
           "A line from (x0, y0) to (x1, y1).")
      .def("rect", &C::rect, py::arg("x"), py::arg("y"), py::arg("w"), py::arg("h"),
           "A rectangle with corner (x, y), width w and height h.")
      .def("ellipse", &C::ellipse, py::arg("cx"), py::arg("cy"), py::arg("w"), py::arg("h"),
           "An ellipse centered at (cx, cy), w wide and h high.")
      .def("arc", &C::arc, py::arg("cx"), py::arg("cy"), py::arg("w"), py::arg("h"), py::arg("start"), py::arg("stop"),
           py::arg("mode") = ArcMode::open,
           "The arc of the ellipse (cx, cy, w, h) from angle start to stop (radians, clockwise on screen); mode OPEN, "
           "CHORD or PIE.")
      .def("triangle", &C::triangle, "A triangle through (x0, y0), (x1, y1), (x2, y2).")
      .def("quad", &C::quad, "A quadrilateral through four points.")
      .def("begin_shape", &C::begin_shape, py::arg("kind") = ShapeKind::polygon,
           "Starts a shape of vertices: a polygon, or ShapeKind.points, lines, triangles, strips, fans, quads.")
      .def("vertex", &C::vertex, py::arg("x"), py::arg("y"), "The next vertex of the shape.")
      .def("bezier_vertex", &C::bezier_vertex,
           "A cubic Bezier segment from the last vertex: control points (cx1, cy1), (cx2, cy2), end (x, y).")
      .def("quadratic_vertex", &C::quadratic_vertex,
           "A quadratic Bezier segment from the last vertex: control point (cx, cy), end (x, y).")
      .def("begin_contour", &C::begin_contour, "Starts a hole inside the shape (its vertices wind the other way).")
      .def("end_contour", &C::end_contour, "Ends the hole.")
      .def("end_shape", &C::end_shape, py::arg("close") = false,
           "Draws the shape; close=True (CLOSE) joins the last vertex to the first.")
      .def("push_matrix", &C::push_matrix, "Saves the current transformation (the matrix stack).")
      .def("pop_matrix", &C::pop_matrix, "Restores the transformation saved last.")
      .def("translate", &C::translate, py::arg("dx"), py::arg("dy"), "Moves the origin by (dx, dy).")
      .def("rotate", &C::rotate, py::arg("angle"), "Rotates by angle radians (clockwise on screen, as Processing).")
      .def("scale", py::overload_cast<double>(&C::scale), "Scales by s, or by (sx, sy).")
      .def("scale", py::overload_cast<double, double>(&C::scale))
      .def("shear_x", &C::shear_x, py::arg("angle"), "Shears x by the angle: x' = x + tan(angle) y.")
      .def("shear_y", &C::shear_y, py::arg("angle"), "Shears y by the angle: y' = y + tan(angle) x.")
      .def("reset_matrix", &C::reset_matrix, "The identity transformation again.")
      .def(
          "matrix",
          [](const C& c) {
            const Mat3& m = c.matrix();  // glm's columns: m[column][row]
            return py::make_tuple(py::make_tuple(m[0][0], m[1][0], m[2][0]), py::make_tuple(m[0][1], m[1][1], m[2][1]),
                                  py::make_tuple(m[0][2], m[1][2], m[2][2]));
          },
          "The current transformation as rows ((n00, n01, n02), (n10, n11, n12), (0, 0, 1)): the user-to-pixel map.")
      .def(
          "apply_matrix",
          [](C& c, double n00, double n01, double n02, double n10, double n11, double n12) {
            c.apply_matrix(Mat3(n00, n10, 0, n01, n11, 0, n02, n12, 1));  // glm's columns
          },
          "Processing's applyMatrix(n00, n01, n02, n10, n11, n12): x' = n00 x + n01 y + n02, y' = n10 x + n11 y + n12.")
      .def("text", &C::text, py::arg("text"), py::arg("x"), py::arg("y"),
           "Draws text with its anchor at (x, y) (text_align), in the fill color.")
      .def("text_size", &C::text_size, py::arg("px"), "The text's height in pixels.")
      .def("text_align", &C::text_align, py::arg("x"), py::arg("y") = TextAlignY::baseline,
           "Where text sits on its anchor: TextAlignX left/center/right and TextAlignY baseline/top/center/bottom.")
      .def("text_width", &C::text_width, py::arg("text"), "The width the text would take, in pixels.")
      .def(
          "image",
          [](C& c, py::handle img, double x, double y, std::optional<double> w, std::optional<double> h) {
            const ImageRGBA picture = image_rgba(img, "image");
            c.image(picture, x, y, w.value_or(picture.width()), h.value_or(picture.height()));
          },
          py::arg("image"), py::arg("x"), py::arg("y"), py::arg("w") = py::none(), py::arg("h") = py::none(),
          "Draws an image array with its corner at (x, y), scaled to w x h when given.");
}

/// The runner's options and a run, the GIL released while the runner waits (the sketch's methods take it back).
py::dict run(PythonSketch& sketch, std::optional<int> frames, std::optional<double> seconds, std::optional<double> fps,
             std::optional<std::pair<int, int>> size, const std::string& output, bool window, const std::string& input,
             const std::string& events, int threads, uint64_t seed, bool srgb, const std::string& title,
             const py::object& on_frame) {
  RunOptions o;
  o.frames = frames;
  o.seconds = seconds;
  o.fps = fps;
  o.size = size;
  o.output = output;
  o.mode = window ? RunMode::window : RunMode::headless;
  o.input = input;
  if (!events.empty()) o.events = parse_input_script(events, "events");
  o.threads = threads;
  o.seed = seed;
  o.srgb = srgb;
  o.title = title;
  FrameCallback callback;
  if (!on_frame.is_none())
    callback = [&on_frame](int frame, const ImageRGBA8& picture) {
      py::gil_scoped_acquire acquire;
      py::array_t<uint8_t> copy(std::vector<py::ssize_t>{picture.height(), picture.width(), 4},
                                &picture.pixels()[0][0]);
      on_frame(frame, copy);
    };
  RunResult r;
  {
    py::gil_scoped_release release;
    r = run_sketch(sketch, o, callback);
  }
  py::dict d;
  d["frames"] = r.frames;
  d["draws"] = r.draws;
  d["width"] = r.width;
  d["height"] = r.height;
  return d;
}

}  // namespace

void bind_sketches(py::module_& m) {
  bind_canvas(m);
  py::class_<Sketch, PythonSketch>(m, "Sketch", "The C++ sketch a Python sketch derives from (tessera.sketch).")
      .def(py::init<>(), "A sketch: override setup, draw and the events in a subclass (call super().__init__()).")
      .def("setup", &Sketch::setup, "Runs once before the first frame; call size() here.")
      .def("draw", &Sketch::draw, "Draws one frame.")
      .def("mouse_pressed", &Sketch::mouse_pressed, "A mouse button went down.")
      .def("mouse_released", &Sketch::mouse_released, "A mouse button went up.")
      .def("mouse_dragged", &Sketch::mouse_dragged, "The mouse moved with a button down.")
      .def("mouse_moved", &Sketch::mouse_moved, "The mouse moved with no button down.")
      .def("mouse_wheel", &Sketch::mouse_wheel, py::arg("delta"), "The wheel turned (delta > 0: toward the user).")
      .def("key_pressed", &Sketch::key_pressed, "A key went down (key, key_code).")
      .def("key_released", &Sketch::key_released, "A key went up.")
      .def("window_resized", &Sketch::window_resized, "The window's drawable size changed.")
      .def_readonly("frame_count", &Sketch::frame_count, "Frames drawn so far (1 during the first draw).")
      .def_readonly("mouse_x", &Sketch::mouse_x, "The pointer's x in sketch pixels.")
      .def_readonly("mouse_y", &Sketch::mouse_y, "The pointer's y in sketch pixels.")
      .def_readonly("pmouse_x", &Sketch::pmouse_x, "The pointer's x at the previous frame.")
      .def_readonly("pmouse_y", &Sketch::pmouse_y, "The pointer's y at the previous frame.")
      .def_readonly("mouse_is_pressed", &Sketch::mouse_is_pressed, "Whether a mouse button is down.")
      .def_readonly("mouse_button", &Sketch::mouse_button, "The button of the last press or release (MouseButton).")
      .def_readonly("key_code", &Sketch::key_code, "The last key's code (UP, SHIFT, ...; the upper-case letter).")
      .def_readonly("key_is_pressed", &Sketch::key_is_pressed, "Whether a key is down.")
      .def_readonly("width", &Sketch::width, "The sketch's width in pixels.")
      .def_readonly("height", &Sketch::height, "The sketch's height in pixels.")
      .def_readonly("window_width", &Sketch::window_width, "The window's drawable width (0 headless).")
      .def_readonly("window_height", &Sketch::window_height, "The window's drawable height (0 headless).")
      .def_readonly("focused", &Sketch::focused, "Whether the window has the keyboard focus.")
      .def_property_readonly(
          "key", [](const Sketch& s) { return s.key == Key::coded ? std::string() : std::string(1, char(s.key)); },
          "The last key's character ('' for a coded key).")
      .def(
          "size", [](Sketch& s, int w, int h) { s.size(w, h); }, py::arg("width"), py::arg("height"),
          "The sketch's size (a 2D canvas); call it in setup().")
      .def("frame_rate", py::overload_cast<double>(&Sketch::frame_rate), py::arg("fps"),
           "The target frame rate (60 by default).")
      .def("millis", &Sketch::millis, "Milliseconds since setup began (headless: the frames' time).")
      .def("no_loop", &Sketch::no_loop, "Stops calling draw() every frame.")
      .def("loop", &Sketch::loop, "Calls draw() every frame again.")
      .def("redraw", &Sketch::redraw, "Calls draw() once more.")
      .def("exit_sketch", &Sketch::exit, "Ends the run after this frame (Processing's exit()).")
      .def("save_frame", &Sketch::save_frame, py::arg("pattern") = "screen-####.png",
           "Writes the picture so far; the run of '#' becomes frame_count.")
      .def("random", py::overload_cast<double, double>(&Sketch::random), py::arg("low"), py::arg("high"),
           "A uniform number in [low, high).")
      .def("random_seed", &Sketch::random_seed, py::arg("seed"), "Restarts random() from a seed.")
      .def("noise", &Sketch::noise, py::arg("x"), py::arg("y") = 0.0, py::arg("z") = 0.0,
           "Processing's noise(x, y, z) in [0, 1).")
      .def("noise_seed", &Sketch::noise_seed, py::arg("seed"), "Restarts noise() from a seed.")
      .def("noise_detail", py::overload_cast<int>(&Sketch::noise_detail), py::arg("octaves"),
           "noise()'s octaves (and falloff).")
      .def("noise_detail", py::overload_cast<int, double>(&Sketch::noise_detail), py::arg("octaves"),
           py::arg("falloff"))
      .def("canvas", &Sketch::canvas, py::return_value_policy::reference_internal, "The sketch's Canvas.")
      .def(
          "picture", [](Sketch& s) { return to_python(to_float(s.picture())); },
          "The picture drawn so far as an Image.");
  m.def("_run_sketch", &run, py::arg("sketch"), py::arg("frames"), py::arg("seconds"), py::arg("fps"), py::arg("size"),
        py::arg("output"), py::arg("window"), py::arg("input"), py::arg("events"), py::arg("threads"), py::arg("seed"),
        py::arg("srgb"), py::arg("title"), py::arg("on_frame"));
  m.def("window_supported", &window_supported, "Whether this build can open windows (SDL2).");
  m.def(
      "builtin_demo_input",
      [](const std::string& name) {
        const SketchInfo* info = find_sketch(name);
        if (!info) throw InvalidInput(fmt::format("'{}' is not a built-in sketch (tessera sketch --list)", name));
        return std::string(info->demo_input);
      },
      py::arg("name"),
      "The input script (docs/sketch.md) of a built-in sketch's demo recording (`tessera sketch NAME --demo`).");
}

}  // namespace tessera::python
