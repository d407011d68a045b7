"""The notes' body hierarchy made to wave, in Python: a person of torso + 2 arms, an arm an extent + a hand of
fingers and a thumb ("Matrix Stack Uses"), each part drawn with the notes' GT_LINES through the matrix stack; the
shoulder and wrist angles follow frame_count. The same frames as the built-in `tessera sketch body` (the tests compare
them).

    python3 body.py                 # a window
    python3 body.py out.gif         # headless, 60 frames
"""
import math
import sys

from tessera.sketch import *  # noqa: F401,F403

UNIT = 14  # pixels per unit


def gt_lines(vertices):
    """The notes' GT_LINES: each vertex multiplied by the current matrix (gtVertex), pairs joined in pixels."""
    (a, b, c), (d, e, f), _ = matrix()
    push_matrix()
    reset_matrix()
    begin_shape(LINES)
    for x, y in vertices:
        vertex(a * x + b * y + c * 1.0, d * x + e * y + f * 1.0)
    end_shape()
    pop_matrix()


def square():
    gt_lines([(-1, -1), (1, -1), (1, -1), (1, 1), (1, 1), (-1, 1), (-1, 1), (-1, -1)])


def circle(n=20):
    vertices, old = [], (1.0, 0.0)
    for i in range(1, n + 1):
        theta = 2 * math.pi * i / n
        vertices += [old, (math.cos(theta), math.sin(theta))]
        old = (math.cos(theta), math.sin(theta))
    gt_lines(vertices)


def extent():
    push_matrix()
    scale(3, 0.5)
    translate(1, 0)  # written last, acts first
    square()
    pop_matrix()


def finger():
    push_matrix()
    scale(0.4, 0.3)
    extent()
    pop_matrix()


def hand():
    push_matrix()
    translate(1, 0)
    scale(1, 0.8)
    square()
    pop_matrix()
    for i in range(4):
        push_matrix()
        translate(2, -0.6 + 0.4 * i)
        finger()
        pop_matrix()
    push_matrix()
    translate(0.6, 0.8)
    rotate(math.radians(50))
    scale(0.7, 1)
    finger()
    pop_matrix()


def arm(wrist):
    extent()
    push_matrix()
    translate(6, 0)
    rotate(wrist)
    hand()
    pop_matrix()


def body(raise_, wave, lower):
    push_matrix()  # torso
    scale(2, 4)
    square()
    pop_matrix()
    push_matrix()  # head
    translate(0, 5.6)
    scale(1.5, 1.5)
    circle()
    pop_matrix()
    push_matrix()  # the waving arm
    translate(2, 3)
    rotate(raise_)
    arm(wave)
    pop_matrix()
    push_matrix()  # the other arm, mirrored
    translate(-2, 3)
    scale(-1, 1)
    rotate(lower)
    arm(0)
    pop_matrix()


def setup():
    size(400, 400)
    no_fill()


def draw():
    background(255)
    phase = 2 * math.pi * frame_count / 60.0
    angles = (math.radians(40) + math.radians(25) * math.sin(phase), math.radians(35) * math.sin(3 * phase),
              math.radians(-25) + math.radians(10) * math.sin(phase + math.pi))
    push_matrix()
    translate(200, 240)
    scale(UNIT, -UNIT)  # y up, as the notes' gt coordinates
    stroke_weight(1.5)
    stroke(0)
    body(*angles)
    pop_matrix()


if __name__ == "__main__":
    run_sketch(frames=60, output=sys.argv[1]) if len(sys.argv) > 1 else run_sketch(window=True)
