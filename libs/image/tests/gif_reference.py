#!/usr/bin/env python3
"""An independent GIF reference for animation_test.cpp: Python's PIL decodes, a block walk written from the GIF89a
specification reads the color tables.

  gif_reference.py FILE OUTDIR

prints, one item per line:
  frames N
  size W H
  loop L            (the NETSCAPE2.0 count, or "none" when the file has no loop extension)
  durations D...    (milliseconds per frame, as PIL reads them)
  colors C...       (distinct colors of each decoded frame)
  tables G L...     (the global color table's size, then each frame's local table size, 0 for none)
  rects X Y W H...  (each frame's image rectangle on the screen)
and writes each decoded frame, composited as a viewer shows it, to OUTDIR/frame-N.ppm.
"""
import struct
import sys

from PIL import Image


def color_tables(data):
    """Global table size, each image's local table size and rectangle, from the blocks (GIF89a, sections 18-26)."""
    assert data[:6] in (b"GIF87a", b"GIF89a"), "not a GIF"
    flags = data[10]
    global_size = 2 << (flags & 7) if flags & 0x80 else 0
    pos, local, rects = 13 + 3 * global_size, [], []
    while pos < len(data):
        kind = data[pos]
        if kind == 0x3B:  # trailer
            break
        if kind == 0x21:  # extension: label, then sub-blocks
            pos += 2
        elif kind == 0x2C:  # image descriptor, optional local table, LZW minimum code size, sub-blocks
            packed = data[pos + 9]
            size = 2 << (packed & 7) if packed & 0x80 else 0
            local.append(size)
            rects.extend(struct.unpack("<4H", data[pos + 1:pos + 9]))
            pos += 10 + 3 * size + 1
        else:
            raise ValueError("unexpected block 0x%02x at byte %d" % (kind, pos))
        while data[pos] != 0:
            pos += 1 + data[pos]
        pos += 1
    return global_size, local, rects


def main():
    path, outdir = sys.argv[1], sys.argv[2]
    global_size, local, rects = color_tables(open(path, "rb").read())
    im = Image.open(path)
    loop = im.info.get("loop")
    durations, colors = [], []
    for i in range(im.n_frames):
        im.seek(i)
        durations.append(im.info.get("duration", 0))
        rgb = im.convert("RGB")
        colors.append(len(rgb.getcolors(maxcolors=1 << 24)))
        w, h = rgb.size
        with open("%s/frame-%d.ppm" % (outdir, i), "wb") as f:
            f.write(b"P6\n%d %d\n255\n" % (w, h) + rgb.tobytes())
    print("frames", im.n_frames)
    print("size", *im.size)
    print("loop", "none" if loop is None else loop)
    print("durations", *durations)
    print("colors", *colors)
    print("tables", global_size, *local)
    print("rects", *rects)


if __name__ == "__main__":
    main()
