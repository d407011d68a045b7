#!/usr/bin/env python3
"""Checks an 8-bit picture written with --srgb against the sRGB formula (IEC 61966-2-1), independently of Tessera.

    srgb_check.py pfm LINEAR.pfm ENCODED.png   every pixel of ENCODED is round(255 * srgb(LINEAR)) (within 1, for the
                                               float rounding of values that fall on a half step)
    srgb_check.py pixel ENCODED.png X Y R,G,B  pixel (X, Y) is round(255 * srgb(R,G,B)) exactly (linear R,G,B)

Exit 0 when it holds, 1 with a message on stderr when it does not. Needs PIL (python3-pil).
"""
import struct
import sys

from PIL import Image


def srgb(v):
    """The sRGB transfer curve (linear -> encoded), clamped to [0, 1] first as 8-bit output is."""
    v = min(max(v, 0.0), 1.0)
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def byte(v):
    return int(srgb(v) * 255 + 0.5)


def read_pfm(path):
    """A color PFM as rows of (r, g, b), top row first (the file stores the bottom row first)."""
    data = open(path, "rb").read()
    magic, size, scale, body = data.split(b"\n", 3)
    if magic != b"PF":
        sys.exit(f"{path}: expected a color PFM (PF), got {magic!r}")
    w, h = map(int, size.split())
    floats = struct.unpack(("<" if float(scale) < 0 else ">") + "%df" % (w * h * 3), body[: w * h * 12])
    return w, h, [[floats[3 * (r * w + x): 3 * (r * w + x) + 3] for x in range(w)] for r in reversed(range(h))]


def main():
    assert byte(0.5) == 188, "the formula's own check: linear middle gray is 188"
    if sys.argv[1] == "pfm":
        w, h, rows = read_pfm(sys.argv[2])
        png = Image.open(sys.argv[3]).convert("RGB")
        if png.size != (w, h):
            sys.exit(f"sizes differ: {png.size} and {(w, h)}")
        worst = max(abs(png.getpixel((x, y))[c] - byte(rows[y][x][c])) for y in range(h) for x in range(w)
                    for c in range(3))
        if worst > 1:
            sys.exit(f"{sys.argv[3]} differs from srgb({sys.argv[2]}) by up to {worst}")
    elif sys.argv[1] == "pixel":
        png = Image.open(sys.argv[2]).convert("RGB")
        x, y = int(sys.argv[3]), int(sys.argv[4])
        expected = tuple(byte(float(v)) for v in sys.argv[5].split(","))
        if png.getpixel((x, y)) != expected:
            sys.exit(f"{sys.argv[2]} pixel ({x}, {y}) is {png.getpixel((x, y))}, expected {expected}")
    else:
        sys.exit(__doc__)


main()
