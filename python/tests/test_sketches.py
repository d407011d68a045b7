"""Sketches in Python: the notes' programs as Python scripts give the built-in C++ sketches' frames, byte for byte;
class sketches get their events; errors in a sketch's functions reach the caller."""
import io
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image as PILImage

import tessera
from tessera import sketch as ts

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "sketches"


@pytest.mark.parametrize("name,options", [("pink_square", ["--frames", "60", "--demo"]),
                                          ("transformations", ["--frames", "90"]),
                                          ("body", ["--frames", "60"])])
def test_python_sketch_equals_the_builtin(tmp_path, cli, name, options):
    subprocess.run([sys.executable, EXAMPLES / f"{name}.py", f"{tmp_path}/py/"], check=True, cwd=tmp_path)
    cli("sketch", name, *options, "-o", f"{tmp_path}/cli/")
    frames = sorted((tmp_path / "cli").iterdir())
    assert len(frames) == int(options[1])
    for frame in frames:
        assert (tmp_path / "py" / frame.name).read_bytes() == frame.read_bytes(), frame.name


class Counter(ts.Sketch):
    def __init__(self):
        super().__init__()
        self.presses, self.keys, self.sizes = 0, [], None

    def setup(self):
        self.size(64, 48)
        self.sizes = (self.width, self.height)

    def draw(self):
        self.background(255)
        self.fill(255, 0, 0)
        self.no_stroke()
        self.rect(self.mouse_x - 4, self.mouse_y - 4, 8, 8)

    def mouse_pressed(self):
        self.presses += 1
        assert self.mouse_button_constant == ts.LEFT

    def key_pressed(self):
        self.keys.append(self.key)


def test_class_sketch_gets_scripted_events_and_frames(tmp_path):
    script = tmp_path / "input.txt"
    script.write_text("2 mouse_move 10 20\n3 mouse_press left\n4 mouse_release left\n5 key_press q\n")
    frames = []
    sketch = Counter()
    result = ts.run_sketch(sketch, frames=6, input=script, on_frame=lambda n, rgba: frames.append(rgba))
    assert result == {"frames": 6, "draws": 6, "width": 64, "height": 48}
    assert sketch.sizes == (64, 48) and sketch.presses == 1 and sketch.keys == ["q"]
    last = frames[-1]
    assert last.shape == (48, 64, 4) and last.dtype == np.uint8
    assert tuple(last[20, 10]) == (255, 0, 0, 255) and tuple(last[0, 0]) == (255, 255, 255, 255)


def test_errors_in_a_sketch_reach_the_caller():
    class Broken(ts.Sketch):
        def draw(self):
            if self.frame_count == 3:
                raise ZeroDivisionError("frame 3")

    with pytest.raises(ZeroDivisionError, match="frame 3"):
        ts.run_sketch(Broken(), frames=10)
    with pytest.raises(tessera.InvalidInput, match="no sketch is running"):
        ts.rect(0, 0, 1, 1)


def test_animation_is_a_gif():
    class Grow(ts.Sketch):
        def setup(self):
            self.size(32, 32)

        def draw(self):
            self.background(0)
            self.ellipse(16, 16, self.frame_count * 3, self.frame_count * 3)

    animation = ts.run_sketch(Grow(), frames=8, fps=10, animation=True)
    gif = PILImage.open(io.BytesIO(animation.gif))
    assert gif.format == "GIF" and gif.n_frames == 8
    assert animation._repr_html_().startswith('<img src="data:image/gif;base64,R0lGOD')


def test_canvas_draws_with_processing_calls():
    canvas = tessera.Canvas(20, 10)
    canvas.background(0)
    canvas.no_stroke()
    canvas.fill(0, 255, 0)
    canvas.rect(5, 2, 10, 6)
    picture = canvas.picture
    assert picture.shape == (10, 20, 4)
    assert np.allclose(picture[5, 10], [0, 1, 0, 1]) and np.allclose(picture[0, 0], [0, 0, 0, 1])
    assert picture[2:8, 5:15, 1].min() == 1 and picture[:, :5, 1].max() == 0
    canvas.color_mode(ts.HSB, 360, 100, 100, 1)
    assert np.allclose(canvas.color(120, 100, 100), (0, 1, 0, 1))
    assert canvas._repr_png_()[:4] == b"\x89PNG"
