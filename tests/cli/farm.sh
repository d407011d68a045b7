#!/usr/bin/env bash
# Animated scenes and split renders without a cluster (docs/farm.md): --frames into numbered files and movies, every
# tile of a frame assembled into the unsplit frame's bytes (both backends, any thread count), --crop, the manifest and
# --skip-existing, --list, and clean failures.
set -euo pipefail
tessera="$1"
scratch="$2"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"
fail() { echo "FAIL: $*"; exit 1; }

"$tessera" render --list > list.txt
grep -q '^whitted-moving *frames 0:47 at 24 fps$' list.txt || fail "--list: $(cat list.txt)"
grep -q '^whitted *still$' list.txt || fail "--list: $(cat list.txt)"

# Frames 10..13 of the moving scene, numbered printf-style; each differs from the next (the camera and sphere move).
"$tessera" render whitted-moving --frames 10:13 -o seq/f_%04d.png --size 48x36 --spp 2 --stats > stats.txt 2> log.txt
for f in 10 11 12 13; do test -s "seq/f_00$f.png" || fail "frame $f missing"; done
test ! -e seq/f_0009.png && test ! -e seq/f_0014.png
grep -q '^frames=4$' stats.txt && grep -q '^skipped=0$' stats.txt && grep -q '^eye_rays=13824$' stats.txt ||
  fail "stats: $(cat stats.txt)"
grep -q 'frame 13 -> seq/f_0013.png' log.txt || fail "progress lines: $(cat log.txt)"
! cmp -s seq/f_0010.png seq/f_0011.png || fail "frames 10 and 11 are the same"
# The manifest lists each frame with its size and CRC-32 (checked here with Python's zlib).
/usr/bin/python3 - <<'PY'
import json, os, zlib
files = json.load(open("seq/frames.json"))["files"]
assert sorted(files) == [f"f_00{f}.png" for f in (10, 11, 12, 13)], files
for name, e in files.items():
    data = open(os.path.join("seq", name), "rb").read()
    assert e["bytes"] == len(data) and int(e["crc32"], 16) == zlib.crc32(data), (name, e)
    assert e["frame"] == int(name[2:6]) and e["seconds"] > 0 and "tile" not in e
PY

# --skip-existing: whole frames are skipped; a damaged one (size or CRC no longer matching) is rendered again.
before=$(stat -c %Y seq/f_0011.png)
printf 'xx' >> seq/f_0012.png
"$tessera" render whitted-moving --frames 10:13 -o seq/f_%04d.png --size 48x36 --spp 2 --skip-existing --stats \
  --quiet > skip.txt
grep -q '^frames=1$' skip.txt && grep -q '^skipped=3$' skip.txt || fail "skip: $(cat skip.txt)"
test "$(stat -c %Y seq/f_0011.png)" = "$before"
"$tessera" render whitted-moving --frame 12 -o one.png --size 48x36 --spp 2 --quiet
cmp one.png seq/f_0012.png || fail "the re-rendered frame differs"
# Other settings make other pictures: with another --spp nothing is skipped, and the entries say what made them.
"$tessera" render whitted-moving --frames 10:11 -o seq/f_%04d.png --size 48x36 --spp 3 --skip-existing --stats \
  --quiet > respp.txt
grep -q '^frames=2$' respp.txt && grep -q '^skipped=0$' respp.txt || fail "other settings: $(cat respp.txt)"
grep -q '"settings": "scene [0-9a-f]* size 48x36 spp 3 depth scene seed 0 backend raytrace shadows map srgb 0"' \
  seq/frames.json || fail "no settings in frames.json"

# Every split of a frame assembles into the unsplit frame's bytes: ray tracer with motion blur (tile K on K % 2 + 1
# threads) and rasterizer, PNG and PFM.
for backend in raytrace raster; do
  for ext in png pfm; do
    "$tessera" render whitted-moving --frame 7 -o "whole_$backend.$ext" --size 50x37 --spp 3 --backend $backend --quiet
    for n in 1 3 37; do
      dir="tiles_${backend}_${ext}_$n"
      for ((k = 0; k < n; k++)); do
        "$tessera" render whitted-moving --frame 7 --tile "$k/$n" -o "$dir/f_%04d.$ext" --size 50x37 --spp 3 \
          --backend $backend --threads $((k % 2 + 1)) --quiet
      done
      test "$n" = 1 || test -s "$dir/f_0007.tile-0-of-$n.$ext"
      "$tessera" assemble "$dir/f_%04d.$ext" --frames 7 --tiles $n
      cmp "$dir/f_0007.$ext" "whole_$backend.$ext" || fail "$backend $ext: $n tiles differ from the whole frame"
    done
  done
done
/usr/bin/python3 -c "
import json; e = json.load(open('tiles_raytrace_png_3/frames.json'))['files']['f_0007.tile-2-of-3.png']
assert e['tile'] == [2, 3] and e['frame'] == 7, e"

# --crop renders the window's pixels of the whole frame.
"$tessera" render whitted-moving --frame 7 -o crop.pfm --size 50x37 --spp 3 --crop 10,5,30,25 --quiet
/usr/bin/python3 - <<'PY'
import struct
def pfm(path):
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    w, h = map(int, parts[1].split())
    values = struct.unpack(f"<{w * h * 3}f", parts[3][: w * h * 12])
    return w, h, [values[3 * (w * (h - 1 - y) + x): 3 * (w * (h - 1 - y) + x) + 3] for y in range(h) for x in range(w)]
W, H, whole = pfm("whole_raytrace.pfm")
w, h, crop = pfm("crop.pfm")
assert (w, h) == (20, 20), (w, h)
for y in range(h):
    for x in range(w):
        assert crop[y * w + x] == whole[(y + 5) * W + x + 10], (x, y)
PY

# A damaged tile is named by assemble, which then writes no frame.
rm -f tiles_raytrace_png_3/f_0007.png
printf 'x' >> tiles_raytrace_png_3/f_0007.tile-1-of-3.png
if "$tessera" assemble tiles_raytrace_png_3/f_%04d.png --frames 7 --tiles 3 2> err.txt; then fail "assemble accepted a damaged tile"; fi
grep -q 'f_0007.tile-1-of-3.png: differs from frames.json' err.txt || fail "$(cat err.txt)"
rm tiles_raytrace_png_3/f_0007.tile-0-of-3.png
if "$tessera" assemble tiles_raytrace_png_3/f_%04d.png --frames 7 --tiles 3 2> err.txt; then fail "assemble without a tile"; fi
grep -q 'f_0007.tile-0-of-3.png: missing' err.txt && test ! -e tiles_raytrace_png_3/f_0007.png || fail "$(cat err.txt)"

# A movie of the frames, made by the renderer or by assemble from the frame files.
"$tessera" render whitted-moving --frames 0:5 -o movie.gif --size 40x30 --spp 1 --quiet
/usr/bin/python3 -c "
from PIL import Image; im = Image.open('movie.gif'); n = 0
while True:
    n += 1
    try: im.seek(im.tell() + 1)
    except EOFError: break
assert n == 6 and im.size == (40, 30), (n, im.size)"
"$tessera" assemble seq/f_%04d.png --frames 10:13 --movie seq.gif --fps 12
test -s seq.gif

# Clean failures: usage errors exit 2, bad requests 1, and nothing is written.
status() { set +e; "$@" > /dev/null 2>&1; echo $?; set -e; }
test "$(status "$tessera" render whitted-moving --frames 0:3 -o many.png)" = 1
test "$(status "$tessera" render whitted-moving --frames 40:60 -o x_%d.png)" = 1
test "$(status "$tessera" render whitted-moving --frame 1 --frames 0:2 -o x_%d.png)" = 1
test "$(status "$tessera" render whitted-moving --tile 4/4 -o t.png)" = 1
test "$(status "$tessera" render whitted-moving --tile 0/2 -o t.jpg)" = 1
test "$(status "$tessera" render whitted-moving --tile 0/2 --crop 0,0,4,4 -o t.png)" = 1
test "$(status "$tessera" render whitted-moving --crop 0,0,400,4 -o t.png --size 40x30)" = 1
test "$(status "$tessera" render whitted-moving -o t.mp4)" = 1
test "$(status "$tessera" render whitted --frame 1 -o t.png)" = 1
test "$(status "$tessera" render --frames 0:1)" = 2
test "$(status "$tessera" assemble f_%04d.png)" = 2
test ! -e many.png && test ! -e t.png && test ! -e t.mp4 && test ! -e x_0040.png
echo "farm: ok"
