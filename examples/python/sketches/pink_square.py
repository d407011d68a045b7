"""The notes' first sketch made live, in Python: a pink (255, 150, 150) square that follows the mouse, on white.

Pressing a button makes it darker while held; the key 's' toggles a black outline. The same frames as the built-in
`tessera sketch pink_square` (the tests compare them).

    python3 pink_square.py                 # a window
    python3 pink_square.py out.gif         # headless, 60 frames, the built-in's scripted mouse and keys
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


if __name__ == "__main__":
    if len(sys.argv) > 1:  # the built-in's demo: the pointer goes round, then presses, drags, and types s
        run_sketch(frames=60, output=sys.argv[1], events=builtin_demo_input("pink_square"))
    else:
        run_sketch(window=True)
