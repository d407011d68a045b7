"""The notes' first sketch made live, in Python: a pink (255, 150, 150) square that follows the mouse, on white.

Pressing a button makes it darker while held; the key 's' toggles a black outline. The same frames as the built-in
`tessera sketch pink_square` (the tests compare them).

    python3 pink_square.py                 # a window
    python3 pink_square.py out.gif         # headless, 60 frames, the gallery's scripted mouse
"""
import sys

from tessera.sketch import *  # noqa: F401,F403 (Processing's names, as py5's imported mode)

outlined = False


def setup():
    size(400, 400)


def draw():
    background(255)
    if mouse_is_pressed:
        fill(220, 90, 120)
    else:
        fill(255, 150, 150)
    if outlined:
        stroke(0)
        stroke_weight(4)
    else:
        no_stroke()
    rect(mouse_x - 25, mouse_y - 25, 50, 50)


def key_pressed():
    global outlined
    if key == "s":
        outlined = not outlined


# The pointer circles the canvas once in 40 frames, then presses and drags (the built-in's demo input).
DEMO = """1 mouse_move 200 120
6 mouse_move 257 143
11 mouse_move 280 200
16 mouse_move 257 257
21 mouse_move 200 280
26 mouse_move 143 257
31 mouse_move 120 200
36 mouse_move 143 143
41 mouse_move 200 120
46 mouse_press left
46 mouse_move 240 160
51 mouse_move 280 200
56 mouse_release left
58 key_press s
59 key_release s
"""

if __name__ == "__main__":
    if len(sys.argv) > 1:
        import pathlib
        import tempfile
        script = pathlib.Path(tempfile.mkdtemp()) / "demo.txt"
        script.write_text(DEMO)
        run_sketch(frames=60, output=sys.argv[1], input=script)
    else:
        run_sketch(window=True)
