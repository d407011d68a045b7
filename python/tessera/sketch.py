"""Processing-style sketches in Python, on the runner of Tessera's C++ sketches (docs/python.md, docs/sketch.md).

As py5, two ways to write one. Module functions: define setup() and draw() (and the event functions you need:
mouse_pressed, mouse_released, mouse_dragged, mouse_moved, mouse_wheel(delta), key_pressed, key_released,
window_resized) at the top of a script that does `from tessera.sketch import *`, call Processing's drawing functions
by their lower_case names (size, background, fill, rect, ellipse, begin_shape, push_matrix, translate, ...), read the
variables (frame_count, mouse_x, mouse_y, pmouse_x, pmouse_y, mouse_is_pressed, mouse_button, key, key_code,
key_is_pressed, width, height, focused) and end with run_sketch(). Or a class: derive from Sketch, override the same
methods, draw with self.rect(...), read self.mouse_x, and pass an instance to run_sketch(sketch).

run_sketch runs headless by default (a fixed frame rate, deterministic: the same script, the same frames) or in a
window (window=True; SDL2), and writes the frames to an animated GIF, a video (.mp4, .webm, ...), numbered PNGs or the
last picture (output=). In a notebook, run_sketch(..., animation=True) returns an Animation that shows as a GIF.
"""
import inspect as _inspect
import os as _os
import tempfile as _tempfile
import types as _types

from . import _tessera
from ._tessera import ArcMode, ColorMode, LineCap, LineJoin, MouseButton, ShapeKind, TextAlignX, TextAlignY
from ._tessera import builtin_demo_input, window_supported  # noqa: F401

# Processing's constants.
POINTS, LINES, TRIANGLES = ShapeKind.points, ShapeKind.lines, ShapeKind.triangles
TRIANGLE_STRIP, TRIANGLE_FAN = ShapeKind.triangle_strip, ShapeKind.triangle_fan
QUADS, QUAD_STRIP = ShapeKind.quads, ShapeKind.quad_strip
CLOSE = True
RGB, HSB = ColorMode.rgb, ColorMode.hsb
OPEN, CHORD, PIE = ArcMode.open, ArcMode.chord, ArcMode.pie
LEFT, RIGHT, CENTER, TOP, BOTTOM, BASELINE = 37, 39, 3, 101, 102, 0  # text_align and mouse_button, as Processing's
MITER, BEVEL, ROUND, SQUARE, PROJECT = "miter", "bevel", "round", "square", "project"
UP, DOWN, SHIFT, CONTROL, ALT = 38, 40, 16, 17, 18
BACKSPACE, TAB, ENTER, ESC, DELETE, CODED = 8, 9, 10, 27, 127, 0xFFFF
PI, HALF_PI, QUARTER_PI, TWO_PI, TAU = 3.141592653589793, 1.5707963267948966, 0.7853981633974483, 6.283185307179586, \
    6.283185307179586

_ALIGN_X = {LEFT: TextAlignX.left, CENTER: TextAlignX.center, RIGHT: TextAlignX.right}
_ALIGN_Y = {BASELINE: TextAlignY.baseline, TOP: TextAlignY.top, CENTER: TextAlignY.center, BOTTOM: TextAlignY.bottom}
_JOINS = {MITER: LineJoin.miter, BEVEL: LineJoin.bevel, ROUND: LineJoin.round}
_CAPS = {SQUARE: LineCap.butt, PROJECT: LineCap.square, ROUND: LineCap.round}  # Processing's SQUARE is flat
_BUTTONS = {MouseButton.none: None, MouseButton.left: LEFT, MouseButton.right: RIGHT, MouseButton.center: CENTER}
_VARIABLES = ("frame_count", "mouse_x", "mouse_y", "pmouse_x", "pmouse_y", "mouse_is_pressed", "key", "key_code",
              "key_is_pressed", "width", "height", "window_width", "window_height", "focused")
_EVENTS = ("mouse_pressed", "mouse_released", "mouse_dragged", "mouse_moved", "mouse_wheel", "key_pressed",
           "key_released", "window_resized")

_current = None  # the sketch run_sketch is running


class Sketch(_tessera.Sketch):
    """A sketch as a class: override setup, draw and the events; the canvas's calls are methods (self.rect(...))."""

    def __getattr__(self, name):
        # Processing's drawing calls live on the canvas (known once size() has made it).
        return getattr(self.canvas(), name)

    def text_align(self, x, y=BASELINE):
        self.canvas().text_align(_ALIGN_X[x], _ALIGN_Y[y])

    def stroke_join(self, join):
        self.canvas().stroke_join(_JOINS[join])

    def stroke_cap(self, cap):
        self.canvas().stroke_cap(_CAPS[cap])

    def random(self, low, high=None):
        return _tessera.Sketch.random(self, 0.0, low) if high is None else _tessera.Sketch.random(self, low, high)

    @property
    def mouse_button_constant(self):
        """mouse_button as Processing's LEFT, RIGHT, CENTER (None before any press)."""
        return _BUTTONS[self.mouse_button]


class _FunctionSketch(Sketch):
    """A sketch made of a script's module-level functions: each callback first publishes Processing's variables to
    the script's globals (and this module's), as py5 does."""

    def __init__(self, namespace):
        super().__init__()
        self._namespace = namespace

    def _call(self, name, *args):
        values = {v: getattr(self, v) for v in _VARIABLES}
        values["mouse_button"] = _BUTTONS[self.mouse_button]
        self._namespace.update(values)
        globals().update(values)
        function = self._namespace.get(name)
        if callable(function):
            function(*args)

    def setup(self):
        self._call("setup")

    def draw(self):
        self._call("draw")

    def mouse_pressed(self):
        self._call("mouse_pressed")

    def mouse_released(self):
        self._call("mouse_released")

    def mouse_dragged(self):
        self._call("mouse_dragged")

    def mouse_moved(self):
        self._call("mouse_moved")

    def mouse_wheel(self, delta):
        self._call("mouse_wheel", delta)

    def key_pressed(self):
        self._call("key_pressed")

    def key_released(self):
        self._call("key_released")

    def window_resized(self):
        self._call("window_resized")


class Animation:
    """A sketch's frames as an animated GIF: a notebook shows it; save(path) writes it."""

    def __init__(self, gif):
        self.gif = gif

    def _repr_html_(self):
        import base64
        return f'<img src="data:image/gif;base64,{base64.b64encode(self.gif).decode()}"/>'

    def save(self, path):
        with open(path, "wb") as f:
            f.write(self.gif)


def run_sketch(sketch=None, *, frames=None, seconds=None, fps=None, size=None, output=None, window=False,
               input=None, events=None, threads=0, seed=0, srgb=False, title="tessera sketch", on_frame=None,
               animation=False):
    """Runs a sketch: `sketch` (a Sketch instance, or a module or dict whose setup() and draw() functions make one),
    or by default the calling script's module-level setup() and draw().

    frames / seconds: stop after so many (headless: one second's by default); fps replaces the sketch's frame rate;
    size (width, height) replaces its size(). output: .gif, .mp4/.webm/.mov/.mkv (ffmpeg), a folder/ or
    frame-####.png for every frame, or one .png for the last. window=True opens a real window (SDL2) that runs until
    closed (Escape), exit_sketch(), or the frames/seconds given. input: a file of input events, one per line
    'FRAME EVENT ARGS' (docs/sketch.md); events: such a script as text (builtin_demo_input(name) gives a built-in's). seed: of random() and noise(). on_frame(number, rgba8 (H, W, 4)) sees every
    frame. animation=True returns an Animation (a GIF) instead of the run's counts. Exceptions raised by the
    sketch's functions end the run and propagate.
    """
    global _current
    if sketch is None:
        sketch = _FunctionSketch(_inspect.stack()[1].frame.f_globals)
    elif isinstance(sketch, (dict, _types.ModuleType)):
        sketch = _FunctionSketch(sketch if isinstance(sketch, dict) else vars(sketch))
    if animation and output:
        raise _tessera.InvalidInput("animation=True writes its own GIF: give no output")
    folder = _tempfile.TemporaryDirectory() if animation else None
    target = _os.path.join(folder.name, "sketch.gif") if animation else _os.fspath(output or "")
    previous, _current = _current, sketch
    try:
        result = _tessera._run_sketch(sketch, frames, seconds, fps, size, target, window,
                                      _os.fspath(input or ""), events or "", threads, seed, srgb, title, on_frame)
        if animation:
            with open(target, "rb") as f:
                return Animation(f.read())
        return result
    finally:
        _current = previous
        if folder:
            folder.cleanup()


def _sketch():
    if _current is None:
        raise _tessera.InvalidInput("no sketch is running: call the drawing functions from setup() and draw(), "
                                    "run by run_sketch()")
    return _current


def _forward(name, doc):
    def call(*args, **kwargs):
        return getattr(_sketch(), name)(*args, **kwargs)

    call.__name__ = name
    call.__doc__ = doc
    return call


# The module-level drawing functions of a script, forwarded to the running sketch (its canvas for the drawing calls).
for _name in ("size", "frame_rate", "millis", "no_loop", "loop", "redraw", "exit_sketch", "save_frame", "random",
              "random_seed", "noise", "noise_seed", "noise_detail", "background", "fill", "no_fill", "stroke",
              "no_stroke", "stroke_weight", "stroke_join", "stroke_cap", "smooth", "no_smooth", "color_mode", "color",
              "point", "line", "rect", "ellipse", "arc", "triangle", "quad", "begin_shape", "vertex", "bezier_vertex",
              "quadratic_vertex", "begin_contour", "end_contour", "end_shape", "push_matrix", "pop_matrix",
              "translate", "rotate", "scale", "shear_x", "shear_y", "reset_matrix", "apply_matrix", "matrix", "text",
              "text_size", "text_align", "text_width", "image"):
    globals()[_name] = _forward(_name, f"Processing's {_name} on the running sketch (see tessera.Canvas.{_name}).")
del _name

# Processing's variables, published before each callback (module-level scripts read them as globals).
frame_count = mouse_x = mouse_y = pmouse_x = pmouse_y = key_code = width = height = window_width = window_height = 0
mouse_is_pressed = key_is_pressed = False
focused = True
key = ""
mouse_button = None
