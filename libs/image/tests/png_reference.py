#!/usr/bin/env python3
"""An independent PNG reference for image_io_test.cpp, using only Python's zlib (no stb).

  png_reference.py decode FILE        prints "W H C" and then every sample as decimal, rows top first
  png_reference.py encode FILE W H    writes an 8-bit RGBA PNG of the pattern in pattern() (filter type 0)
  png_reference.py encode16 FILE W H  writes a 16-bit grayscale PNG of pattern16() (filter type 0)
"""
import struct
import sys
import zlib


def pattern(x, y):
    return ((7 * x + 3 * y) % 256, (x * y) % 256, (255 - x) % 256, (200 + y) % 256)


def pattern16(x, y):
    return (x * 4099 + y * 257) % 65536


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def encode(path, w, h, sixteen):
    rows = bytearray()
    for y in range(h):
        rows.append(0)
        for x in range(w):
            rows += struct.pack(">H", pattern16(x, y)) if sixteen else bytes(pattern(x, y))
    ihdr = struct.pack(">IIBBBBB", w, h, 16 if sixteen else 8, 0 if sixteen else 6, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(bytes(rows)))
                + chunk(b"IEND", b""))


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else (b if pb <= pc else c)


def decode(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        assert crc == zlib.crc32(kind + body) & 0xFFFFFFFF, "bad CRC in chunk " + kind.decode()
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, "unsupported PNG flavour"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    c = 3 if ctype == 2 else 4
    raw, stride, prev, out = zlib.decompress(idat), w * c, bytearray(w * c), []
    for y in range(h):
        ftype, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - c] if i >= c else 0
            b, up_left = prev[i], (prev[i - c] if i >= c else 0)
            pred = (0, a, b, (a + b) // 2, paeth(a, b, up_left))[ftype]
            line[i] = (line[i] + pred) & 0xFF
        out += line
        prev = line
    print(w, h, c)
    print(" ".join(map(str, out)))


if __name__ == "__main__":
    if sys.argv[1] == "decode":
        decode(sys.argv[2])
    else:
        encode(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[1] == "encode16")
