#!/usr/bin/env python3
"""A JPEG reference for image_io_test.cpp: PIL encodes and decodes (its own libjpeg build and colour conversions).

  jpeg_reference.py FOLDER   writes FOLDER/<kind>.jpg for each kind below and prints, for each, "kind W H" and then
                             PIL's RGB decoding of the file, every sample as decimal, rows top first
"""
import sys

from PIL import Image

KINDS = {  # name: (PIL mode, save options)
    "baseline": ("RGB", {}),
    "progressive": ("RGB", {"progressive": True}),
    "gray": ("L", {}),
    "full_chroma": ("RGB", {"subsampling": 0}),
    "cmyk": ("CMYK", {}),
}


def pattern(w, h):
    image = Image.new("RGB", (w, h))
    image.putdata([((7 * x + 3 * y) % 256, (x * y) % 256, 255 - 4 * x if x < 64 else 0) for y in range(h) for x in range(w)])
    return image


def main(folder):
    source = pattern(37, 23)
    for kind, (mode, options) in KINDS.items():
        path = f"{folder}/{kind}.jpg"
        source.convert(mode).save(path, quality=85, **options)
        decoded = Image.open(path).convert("RGB")
        print(kind, *decoded.size)
        print(" ".join(str(v) for pixel in decoded.getdata() for v in pixel))


if __name__ == "__main__":
    main(sys.argv[1])
