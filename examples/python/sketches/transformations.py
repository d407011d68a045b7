"""The notes' 2D transformations animated, in Python: four panels, each a house (the square [0, 2]^2 under the roof
(0, 2), (2, 2), (1, 3)) drawn in light gray where it stands and filled under one transformation whose parameter
follows frame_count (theta = 2 pi frame_count / 90): translate, rotate about the pivot (1, 1) (T2 R T1), scale,
shear (x' = x + a y). The same frames as the built-in `tessera sketch transformations` (the tests compare them).

    python3 transformations.py             # a window
    python3 transformations.py out.gif     # headless, 90 frames
"""
import math
import sys

from tessera.sketch import *  # noqa: F401,F403

UNIT = 20  # pixels per unit
NAMES = ("translate", "rotate", "scale", "shear")
COLORS = ((90, 150, 230), (240, 120, 90), (110, 190, 110), (190, 120, 210))


def house():
    begin_shape()
    for x, y in ((0, 0), (2, 0), (2, 2), (1, 3), (0, 2)):
        vertex(x, y)
    end_shape(CLOSE)


def setup():
    size(400, 400)


def draw():
    background(255)
    theta = 2 * math.pi * frame_count / 90.0
    stroke(200)  # the panel dividers
    stroke_weight(1)
    line(200, 0, 200, 400)
    line(0, 200, 400, 200)
    for panel in range(4):
        push_matrix()
        column, row = panel % 2, panel // 2
        translate(200 * column + 80, 200 * row + 130)  # the panel's origin
        scale(UNIT, -UNIT)
        stroke_weight(1.0 / UNIT)
        fill(235)  # the untransformed house, and the origin
        stroke(170)
        house()
        no_stroke()
        fill(0)
        ellipse(0, 0, 0.25, 0.25)
        if panel == 0:
            translate(1.5 * math.cos(theta), 1.5 * math.sin(theta))
        elif panel == 1:
            translate(1, 1)  # T2: back to the pivot
            rotate(theta)  # R
            translate(-1, -1)  # T1: the pivot to the origin (acts first)
        elif panel == 2:
            scale(1 + 0.5 * math.sin(theta), 1 + 0.5 * math.cos(theta))
        else:
            apply_matrix(1, math.sin(theta), 0, 0, 1, 0)  # x' = x + a y
        fill(*COLORS[panel])
        stroke(40)
        house()
        pop_matrix()
        fill(60)  # the panel's name
        text_size(16)
        text(NAMES[panel], 200 * column + 10, 200 * row + 22)
        if panel == 1:  # the pivot, over the house
            no_stroke()
            fill(220, 40, 40)
            ellipse(280 + UNIT, 130 - UNIT, 7, 7)


if __name__ == "__main__":
    run_sketch(frames=90, output=sys.argv[1]) if len(sys.argv) > 1 else run_sketch(window=True)
