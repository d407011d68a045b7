#!/usr/bin/env bash
# tessera view, headless: turntable GIFs of each kind of viewable (frame count and size read back by PIL), --stats,
# scripted input (a drag turns the picture, a key changes the shading, r restores the home view byte for byte), --srgb
# against the sRGB formula, and clean failures: an unknown or unreadable file exits 1 with a message and no output,
# and a window without a display exits 1 suggesting --headless. The bunny's turntable (frames per second) runs when
# the shared data is present.
# $1 = the tessera binary, $2 = a scratch folder.
set -euo pipefail
tessera="$1"
scratch="$2"
data="$(cd "$(dirname "$0")/../data" && pwd)"
shared="${TESSERA_SHARED_DATA:-}"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"
py=/usr/bin/python3
fail() { echo "view_headless.sh: $*"; exit 1; }

cp "$data/cube.obj" cube.obj
# One bicubic patch: a bump over the unit square (.bpt: count, "3 3", 16 control points, k = 4 i + j).
{
  echo 1
  echo 3 3
  for i in 0 1 2 3; do for j in 0 1 2 3; do
    z=0; if [ $i -ge 1 ] && [ $i -le 2 ] && [ $j -ge 1 ] && [ $j -le 2 ]; then z=0.6; fi
    echo "$i $j $z"
  done; done
} > bump.bpt

# Turntables of a mesh, a volume, patches and a built-in scene: N frames of the asked size.
"$tessera" view cube.obj --headless --orbit 12 --size 96x64 -o cube.gif --stats > cube.stats
"$tessera" view sphere:24 --headless --orbit 4 --size 64x64 -o sphere.gif
"$tessera" view bump.bpt --headless --orbit 6 --size 64x48 -o bump.gif --shading phong
"$tessera" view whitted --headless --orbit 3 --size 64x48 -o whitted.gif
$py - <<'PY'
from PIL import Image, ImageChops
for name, frames, size in [("cube.gif", 12, (96, 64)), ("sphere.gif", 4, (64, 64)), ("bump.gif", 6, (64, 48)),
                           ("whitted.gif", 3, (64, 48))]:
    im = Image.open(name)
    assert im.n_frames == frames, (name, im.n_frames)
    assert im.size == size, (name, im.size)
    pictures = []
    for k in range(frames):
        im.seek(k)
        pictures.append(im.convert("RGB"))
    # The turntable turns: the frames are not all the same picture.
    assert any(ImageChops.difference(pictures[0], p).getbbox() for p in pictures[1:]), name + " does not turn"
    assert len(set(pictures[0].getdata())) > 2, name + ": the first frame is nearly empty"
PY
grep -qx "frames=12" cube.stats || fail "--stats frames: $(cat cube.stats)"
grep -qx "triangles=12" cube.stats || fail "--stats triangles (the cube's 6 quads): $(cat cube.stats)"
for key in width height pixels frames_per_s read_s compute_s write_s total_s; do
  grep -q "^$key=" cube.stats || fail "--stats lacks $key: $(cat cube.stats)"
done

# Scripted input: the same script, the same bytes; a drag turns the picture; r brings the home view back exactly.
printf '1 mouse_move 48 32\n1 mouse_press left\n1 mouse_move 70 20\n1 mouse_release left\n' > drag.txt
printf '1 mouse_move 48 32\n1 mouse_press left\n1 mouse_move 70 20\n1 mouse_release left\n2 key_press r\n' > reset.txt
printf '1 key_press 5\n' > wire.txt
"$tessera" view cube.obj --headless --size 96x64 -o home.png
"$tessera" view cube.obj --headless --size 96x64 --input drag.txt -o drag.png
"$tessera" view cube.obj --headless --size 96x64 --input drag.txt -o drag2.png --threads 1
"$tessera" view cube.obj --headless --size 96x64 --input reset.txt -o reset.png
"$tessera" view cube.obj --headless --size 96x64 --input wire.txt -o wire.png
cmp -s drag.png drag2.png || fail "the same script gave different pictures"
cmp -s home.png drag.png && fail "the drag did not turn the cube"
cmp -s home.png reset.png || fail "r did not restore the home view"
cmp -s home.png wire.png && fail "key 5 (wireframe) did not change the picture"

# --srgb: every byte of the encoded frame is the sRGB curve (IEC 61966-2-1) of the linear frame's byte.
"$tessera" view cube.obj --headless --size 96x64 --srgb -o home_srgb.png
$py - <<'PY'
from PIL import Image
def srgb(v):
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
lin = Image.open("home.png").convert("RGB").tobytes()
enc = Image.open("home_srgb.png").convert("RGB").tobytes()
bad = [(a, b) for a, b in zip(lin, enc) if abs(int(srgb(a / 255) * 255 + 0.5) - b) > 1]
assert not bad, f"--srgb: {len(bad)} bytes off the sRGB curve, e.g. {bad[:3]}"
assert lin != enc, "--srgb changed nothing"
PY

# Errors: exit 1 with a message naming the problem, no output file.
expect_error() {  # PATTERN ARGS...
  local pattern=$1
  shift
  set +e
  "$tessera" view "$@" 2> err.txt
  local rc=$?
  set -e
  [ $rc = 1 ] || fail "view $* exits 1 (got $rc): $(cat err.txt)"
  grep -q "^tessera: error: .*$pattern" err.txt || fail "view $*: expected '$pattern' in: $(cat err.txt)"
}
echo "not a mesh" > notes.txt
printf 'v 0 0 0\nf 1 2 3\n' > broken.obj
expect_error "no such file" missing-thing --headless -o out1.png
expect_error "cannot tell what to view" notes.txt --headless -o out2.png
expect_error "broken.obj" broken.obj --headless -o out3.png
DISPLAY= WAYLAND_DISPLAY= expect_error "no display.*--headless" cube.obj
[ ! -e out1.png ] && [ ! -e out2.png ] && [ ! -e out3.png ] || fail "a failed view left an output file"

# The bunny's turntable at 1280x720 (the viewer's performance figure; no timing is asserted).
bunny="$shared/meshes/bunny/bun_zipper.ply"
if [ -n "$shared" ] && [ -f "$bunny" ]; then
  "$tessera" view "$bunny" --headless --orbit 8 --size 320x240 --stats -o bunny.gif > bunny.stats
  grep -qx "triangles=69451" bunny.stats || fail "bunny --stats: $(cat bunny.stats)"
  grep -q "^frames_per_s=" bunny.stats || fail "bunny --stats lacks frames_per_s"
else
  echo "skipped the bunny turntable: no shared data in TESSERA_SHARED_DATA"
fi
