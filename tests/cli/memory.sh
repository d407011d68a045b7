#!/usr/bin/env bash
# The memory budget (issue 24, class 3) end to end: every large-request site refuses, before allocating and before
# writing anything, a request whose estimate is over --max-memory, with the estimate and the budget in the message
# (exit 1); the same request under a budget large enough runs. A tiny budget (1M) keeps every request modest.
# Usage: memory.sh TESSERA_BINARY SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2
mkdir -p "$dir"

fail() {
  echo "memory.sh: $*" >&2
  exit 1
}

# refuse OUT WHAT CMD...: CMD exits 1, says "WHAT ... needs about X, the memory budget is 1.0 MiB", and leaves no OUT.
refuse() {
  local out=$1 what=$2
  shift 2
  rm -f "$out"
  local rc=0
  "$@" --max-memory 1M 2>"$dir/err" >/dev/null || rc=$?
  [ "$rc" = 1 ] || fail "$*: expected exit 1 under --max-memory 1M, got $rc: $(cat "$dir/err")"
  grep -q "tessera: error: .*$what.* needs about [0-9.]* [KMGT]iB, the memory budget is 1.0 MiB (raise it with --max-memory SIZE)" \
    "$dir/err" || fail "$*: unexpected message: $(cat "$dir/err")"
  [ ! -e "$out" ] || fail "$*: left $out behind"
}

# --max-memory values: sizes with binary suffixes; anything else is a usage error (exit 2).
rc=0
"$bin" mesh info "$dir/none.obj" --max-memory 12Q 2>"$dir/err" || rc=$?
[ "$rc" = 2 ] || fail "--max-memory 12Q: expected exit 2, got $rc"
grep -q "expected a memory size such as 512M or 4G" "$dir/err" || fail "--max-memory 12Q: $(cat "$dir/err")"
"$bin" canvas --help | grep -q -- "--max-memory" || fail "canvas --help does not list --max-memory"

# SVG: width x height x 24 bytes (float RGBA, a coverage row buffer, the 8-bit copy). 300x300 = 2.1 MiB.
printf '<svg xmlns="http://www.w3.org/2000/svg" width="46000" height="46000"><rect width="10" height="10"/></svg>' \
  >"$dir/bomb.svg"
refuse "$dir/svg.png" "rendering at 300x300 pixels" "$bin" canvas render "$dir/bomb.svg" -o "$dir/svg.png" --size 300x300
"$bin" canvas render "$dir/bomb.svg" -o "$dir/svg.png" --size 300x300 --max-memory 3M --quiet
[ -s "$dir/svg.png" ] || fail "canvas render under a 3M budget wrote nothing"
# The 103-byte SVG's own size: 46000 x 46000 x 24 bytes = 47.3 GiB, refused in a 4 GiB budget.
rc=0
"$bin" canvas render "$dir/bomb.svg" -o "$dir/svg46k.png" --max-memory 4G 2>"$dir/err" || rc=$?
[ "$rc" = 1 ] && grep -q "46000x46000 pixels needs about 47.3 GiB, the memory budget is 4.0 GiB" "$dir/err" ||
  fail "46000x46000 SVG: $(cat "$dir/err")"

# Subdivision: faces x 4^levels. The cube's 6 quads, 3 Catmull-Clark levels = 384 faces (~60 KiB): fits in 1M;
# 6 levels = 24576 faces (~3.8 MiB): refused.
cube=$(dirname "$0")/../data/cube.obj
refuse "$dir/sub.obj" "subdivide: 6 levels of 6 faces (24576 faces)" \
  "$bin" mesh subdivide "$cube" -o "$dir/sub.obj" --levels 6
"$bin" mesh subdivide "$cube" -o "$dir/sub.obj" --levels 3 --max-memory 1M --quiet
[ "$(grep -c '^f ' "$dir/sub.obj")" = 384 ] || fail "subdivide --levels 3 under 1M: wrong output"

# Image readers: width x height x (decoded samples + 16 bytes of float RGBA) from the header, before decoding.
# A 600x600 8-bit PNG (8 KB) needs 600*600*20 bytes = 6.9 MiB; a 19-byte PPM header declaring 16000x16000 RGB is
# refused before its (missing) pixel data is looked at.
python3 - "$dir/white.png" <<'PY'
import struct, sys, zlib
w = h = 600
raw = b"".join(b"\0" + b"\xff" * (3 * w) for _ in range(h))
chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                              chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
PY
refuse "$dir/none" "'$dir/white.png': decoding 600x600 pixels" "$bin" fractal dimension "$dir/white.png" --invert
"$bin" fractal dimension "$dir/white.png" --invert --max-memory 8M --stats | grep -q '^width=600$' ||
  fail "fractal dimension under an 8M budget"
printf 'P6\n16000 16000\n255\n' >"$dir/bomb.ppm"
rc=0
"$bin" fractal dimension "$dir/bomb.ppm" --max-memory 4G 2>"$dir/err" || rc=$?
[ "$rc" = 1 ] && grep -q "decoding 16000x16000 pixels needs about 6.7 GiB, the memory budget is 4.0 GiB" "$dir/err" ||
  fail "16000x16000 PPM: $(cat "$dir/err")"

# Volumes: a header's dims x voxel size x 2 (the voxel bytes read and the volume), before any voxel is read; a
# procedural name's n^3 floats. The NRRD below has a header only: the budget speaks before "file is too short".
printf 'NRRD0004\ntype: float\ndimension: 3\nsizes: 100 100 100\nencoding: raw\nendian: little\n\n' >"$dir/v.nrrd"
refuse "$dir/none" "$dir/v.nrrd: reading 100x100x100 float32 voxels" "$bin" volume info "$dir/v.nrrd"
refuse "$dir/none" "a procedural volume of 100^3 voxels" "$bin" volume info sphere:100
"$bin" volume info sphere:50 --max-memory 1M | grep -qx 'dims=50,50,50' || fail "sphere:50 under a 1M budget"

# Rendered images: width x height x bytes per pixel (raster 44, trace 24, render 28), before the mesh or scene is read.
cube=$(dirname "$0")/../data/cube.obj
refuse "$dir/r.png" "rasterizing 300x300 pixels" "$bin" raster "$cube" -o "$dir/r.png" --size 300x300
refuse "$dir/t.png" "tracing 300x300 pixels" "$bin" trace "$cube" -o "$dir/t.png" --size 300x300
refuse "$dir/s.png" "rendering 300x300 pixels" "$bin" render cornell -o "$dir/s.png" --size 300x300
"$bin" render cornell -o "$dir/s.png" --size 100x100 --spp 1 --max-memory 1M --quiet
[ -s "$dir/s.png" ] || fail "render 100x100 under a 1M budget wrote nothing"
# The issue's 4 GB container: 20000x20000 is refused with a message, not killed by the kernel.
rc=0
"$bin" render cornell -o "$dir/s.png" --size 20000x20000 --max-memory 4G 2>"$dir/err" || rc=$?
[ "$rc" = 1 ] && grep -q "rendering 20000x20000 pixels needs about 10.4 GiB, the memory budget is 4.0 GiB" "$dir/err" ||
  fail "render 20000x20000: $(cat "$dir/err")"

# What the estimates miss ends as a message naming the command, never a bare std::bad_alloc: a 1 GiB address-space
# limit with the budget raised past it.
rc=0
(ulimit -v 1048576 && exec "$bin" canvas render "$dir/bomb.svg" -o "$dir/oom.png" --size 20000x20000 --max-memory 1T) \
  2>"$dir/err" || rc=$?
[ "$rc" = 1 ] && grep -q "^tessera: error: out of memory while running 'tessera canvas render'" "$dir/err" ||
  fail "bad_alloc: expected exit 1 and 'out of memory while running', got $rc: $(cat "$dir/err")"
[ ! -e "$dir/oom.png" ] || fail "bad_alloc left $dir/oom.png"

# The other pictures with a --size: fractals, curves, volume renderings (24 bytes per pixel).
refuse "$dir/m.png" "drawing 300x300 pixels" "$bin" fractal mandelbrot -o "$dir/m.png" --size 300x300
refuse "$dir/k.png" "drawing 300x300 pixels" "$bin" fractal koch -o "$dir/k.png" --size 300x300
refuse "$dir/c.png" "drawing 300x300 pixels" "$bin" curve --points 40,260,80,40,260,40 -o "$dir/c.png" --size 300x300
refuse "$dir/v.png" "rendering 300x300 pixels" "$bin" volume render sphere:16 -o "$dir/v.png" --size 300x300
"$bin" fractal mandelbrot -o "$dir/m.png" --size 100x100 --max-memory 1M --quiet
[ -s "$dir/m.png" ] || fail "fractal mandelbrot 100x100 under a 1M budget wrote nothing"

# Textures from 8-bit files stay 8-bit: a 6000x6000 PNG (600 KB) as --texture. The budget counts its decoding at 8
# bytes per pixel (stb's RGBA samples and the 8-bit image: 274.7 MiB), not read_image's 20 (686.6 MiB, which a float
# read of the same file still needs); and the process fits in an address space of 500 MiB, where float texels (16
# bytes each, a third more for the MIPmaps: 732 MiB with level 0 alone at 549 MiB) could not.
python3 - "$dir/big.png" <<'PY'
import struct, sys, zlib
w = h = 6000
z = zlib.compressobj(9)
row = b"\0" + b"".join(bytes([37 * c % 256, 91 * c % 256, 151 * c % 256]) * 64 for c in range(94))[: 3 * w]
data = b"".join(z.compress(row) for _ in range(h)) + z.flush()
chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                              chunk(b"IDAT", data) + chunk(b"IEND", b""))
PY
printf 'v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n' >"$dir/tquad.obj"
tex=("$bin" raster "$dir/tquad.obj" -o "$dir/tex.png" --texture "$dir/big.png" --size 32x32 --eye 0,0,3 --center 0,0,0
  --threads 1 --quiet)
rm -f "$dir/tex.png"
"${tex[@]}" --max-memory 400M || fail "a 6000x6000 PNG texture under a 400M budget failed"
[ -s "$dir/tex.png" ] || fail "a 6000x6000 PNG texture under a 400M budget wrote nothing"
rc=0
"${tex[@]}" --max-memory 200M 2>"$dir/err" || rc=$?
[ "$rc" = 1 ] && grep -q "big.png': decoding 6000x6000 pixels needs about 274.7 MiB, the memory budget is 200.0 MiB" \
  "$dir/err" || fail "6000x6000 texture under 200M: $(cat "$dir/err")"
rc=0
"$bin" fractal dimension "$dir/big.png" --max-memory 400M 2>"$dir/err" >/dev/null || rc=$?
[ "$rc" = 1 ] && grep -q "decoding 6000x6000 pixels needs about 686.6 MiB" "$dir/err" ||
  fail "a float read of the 6000x6000 PNG under 400M: $(cat "$dir/err")"
rm -f "$dir/tex.png"
(ulimit -v 512000 && exec "${tex[@]}" --max-memory 1T) 2>"$dir/err" || fail "8-bit texture in 500 MiB: $(cat "$dir/err")"
[ -s "$dir/tex.png" ] || fail "8-bit texture in 500 MiB wrote nothing"

# volume render: the picture's size is refused before the volume is read (the header-only NRRD above would answer
# "reading 100x100x100 float32 voxels" if it were read first).
refuse "$dir/v.png" "rendering 300x300 pixels" "$bin" volume render "$dir/v.nrrd" -o "$dir/v.png" --size 300x300

# Marching cubes: the output counted in its first pass, 3 x (24-byte positions and normals a vertex, 16 bytes a
# triangle), before it is allocated. gyroid:50's volume (50^3 x 8 bytes) fits in 1M, its 46592 triangles (5.4 MiB)
# do not.
refuse "$dir/g.obj" "marching cubes: an iso-surface of 46592 triangles and 24132 vertices" \
  "$bin" volume isosurface gyroid:50 -o "$dir/g.obj" --quiet
"$bin" volume isosurface gyroid:50 -o "$dir/g.obj" --max-memory 6M --quiet --stats | grep -qx 'triangles=46592' ||
  fail "volume isosurface gyroid:50 under a 6M budget"

# Canvases at a size a user chose: volume contour's PNG of a 100x100x1 volume (4 times the slice: 400x400 x 20
# bytes) is refused, its SVG (no canvas) is written.
head -c 10000 /dev/zero >"$dir/flat.raw"
refuse "$dir/c.png" "a 400x400 canvas" "$bin" volume contour "$dir/flat.raw" --dims 100,100,1 --iso 0 -o "$dir/c.png"
"$bin" volume contour "$dir/flat.raw" --dims 100,100,1 --iso 0 -o "$dir/c.svg" --max-memory 1M
[ -s "$dir/c.svg" ] || fail "volume contour to SVG under a 1M budget wrote nothing"

# Shadow maps: 6 bytes a texel (4, times 1.5 for a point light's six faces) on top of the picture; raster's
# --shadow-size and a scene's lights through the raster backend.
refuse "$dir/r.png" "rasterizing 100x100 pixels with a 512x512 shadow map" \
  "$bin" raster "$cube" -o "$dir/r.png" --size 100x100 --shadows --shadow-size 512
"$bin" raster "$cube" -o "$dir/r.png" --size 100x100 --shadows --shadow-size 256 --max-memory 1M
[ -s "$dir/r.png" ] || fail "raster --shadow-size 256 under a 1M budget wrote nothing"
refuse "$dir/s.png" "rasterize: 1 shadow map of 2048x2048 texels" \
  "$bin" render cornell -o "$dir/s.png" --size 32x32 --backend raster --quiet

# bench raycast: 36 bytes a ray (primary and random), before the mesh (here missing) is read.
refuse "$dir/none" "casting 300x300 primary rays and 0 random rays" \
  "$bin" bench raycast "$dir/missing.obj" --size 300x300 --random-rays 0
refuse "$dir/none" "casting 100x100 primary rays and 100000 random rays" \
  "$bin" bench raycast "$dir/missing.obj" --size 100x100 --random-rays 100000
"$bin" bench raycast "$cube" --size 100x100 --random-rays 1000 --max-memory 1M >/dev/null ||
  fail "bench raycast 100x100 under a 1M budget"
