#!/usr/bin/env bash
# tessera raster: every shading model and option on a hand-written cube and quad; a known pixel color and an analytic
# depth read back from --depth-out; --stats keys agreeing with the depth file; the same picture for any --threads;
# clean failures (exit 1 or 2, a message, no output file).
# $1 = the tessera binary, $2 = a scratch folder.
set -euo pipefail
tessera="$1"
scratch="$2"
data="$(cd "$(dirname "$0")/../data" && pwd)"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"
py=/usr/bin/python3

# The cube [-1,1]^3 as 6 quads, counterclockwise seen from outside.
cp "$data/cube.obj" cube.obj
# A 2 x 2 square in the plane z = 0, facing +z.
cat > quad.obj <<'OBJ'
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
f 1 2 3 4
OBJ

# Every shading model, both lights, wireframe, culling; default framing (no camera options).
for shading in unlit flat gouraud phong; do
  "$tessera" raster cube.obj -o "cube_$shading.png" --size 64x48 --shading "$shading" --quiet
  test -s "cube_$shading.png"
done
"$tessera" raster cube.obj -o lights_dir.png --size 48x48 --light-dir 1,1,1 --eye 3,2,4 --wireframe --cull back
"$tessera" raster cube.obj -o lights_pos.png --size 48x48 --light-pos 0,3,3 --background 1,1,1 --color '#3366cc'
$py -c "
from PIL import Image
for name in ['cube_unlit.png', 'cube_phong.png', 'lights_dir.png', 'lights_pos.png']:
    im = Image.open(name)
    assert im.size in [(64, 48), (48, 48)], (name, im.size)
    assert len(set(im.convert('RGB').getdata())) > 1, name + ' is a single color'
"

# --stats: the keys, 12 triangles for the cube (6 quads), and `pixels` equal to the covered pixels of --depth-out.
"$tessera" raster cube.obj -o stats.png --size 40x30 --depth-out stats.pfm --repeat 3 --stats > stats.txt
for key in tris pixels seconds tris_per_s; do grep -q "^$key=" stats.txt || { echo "missing $key"; cat stats.txt; exit 1; }; done
grep -q '^tris=12$' stats.txt || { echo "expected tris=12"; cat stats.txt; exit 1; }
[ "$(wc -l < stats.txt)" -eq 4 ] || { echo "expected exactly 4 stats lines"; cat stats.txt; exit 1; }
$py - "$(sed -n 's/^pixels=//p' stats.txt)" <<'PY'
import sys, numpy as np
raw = open('stats.pfm', 'rb').read()
header = raw.split(b'\n', 3)
assert header[0] == b'Pf', header[0]
w, h = map(int, header[1].split())
assert (w, h) == (40, 30), (w, h)
assert float(header[2]) < 0, 'expected little-endian PFM'
depth = np.frombuffer(header[3], dtype='<f4')
assert depth.size == w * h, depth.size
covered = int((depth < 1).sum())
assert covered == int(sys.argv[1]), (covered, sys.argv[1])
assert 0 < covered < w * h and depth.min() >= 0 and depth.max() == 1
PY

# A known picture: an unlit red square seen head-on from z = 4 with near 1 and far 7. Its center pixel is exactly
# the color, a corner the background, and its window depth is 0.875: z_ndc = (f+n)/(f-n) - 2fn/((f-n) d) with
# d = 4, i.e. 4/3 - 7/12 = 0.75, and z_w = (z_ndc + 1)/2, stored in 24 bits.
"$tessera" raster quad.obj -o quad.ppm --size 33x33 --eye 0,0,4 --center 0,0,0 --near 1 --far 7 --fovy 60 \
  --shading unlit --color 1,0,0 --background 0,0,1 --depth-out quad.pfm
$py - <<'PY'
import numpy as np
raw = open('quad.ppm', 'rb').read()
magic, w, h, maxval, pixels = raw.split(maxsplit=4)
assert magic == b'P6' and (int(w), int(h), int(maxval)) == (33, 33, 255)
rgb = np.frombuffer(pixels, dtype=np.uint8).reshape(33, 33, 3)
assert tuple(rgb[16, 16]) == (255, 0, 0), rgb[16, 16]
assert tuple(rgb[0, 0]) == (0, 0, 255), rgb[0, 0]
# The square spans tan(30 deg) * 4 = 2.31 half-heights of view 1: 1/2.31 of the half-size, 7.1 of 16.5 pixels.
assert (rgb[16, :, 0] == 255).sum() in (14, 15), (rgb[16, :, 0] == 255).sum()
depth = np.frombuffer(open('quad.pfm', 'rb').read().split(b'\n', 3)[3], dtype='<f4').reshape(33, 33)
expected = round(0.875 * (2**24 - 1)) / (2**24 - 1)
assert abs(depth[16, 16] - expected) < 1e-6, depth[16, 16]
assert depth[0, 0] == 1.0
PY

# The same picture for any thread count.
"$tessera" raster cube.obj -o t1.ppm --size 96x64 --shading phong --wireframe --threads 1
"$tessera" raster cube.obj -o t2.ppm --size 96x64 --shading phong --wireframe --threads 2
cmp -s t1.ppm t2.ppm || { echo "--threads 1 and 2 differ"; exit 1; }

# The maps. A textured square: texture coordinates (0,0)..(1,1), a texture red on its left half and blue on its
# right half, a bump map with a ramp, a constant green environment; lit head-on.
cat > tquad.obj <<'OBJ'
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 2/2 3/3 4/4
OBJ
$py -c "
from PIL import Image
t = Image.new('RGB', (8, 8), (255, 0, 0))
for x in range(4, 8):
    for y in range(8): t.putpixel((x, y), (0, 0, 255))
t.save('halves.png')
Image.new('RGB', (16, 8), (0, 255, 0)).save('green.png')
ramp = Image.new('L', (64, 64))
for x in range(64):
    for y in range(64): ramp.putpixel((x, y), (x * 37) % 256)
ramp.save('ramp.png')
"
view=(--size 64x64 --eye 0,0,4 --center 0,0,0 --fovy 40 --light-dir 0,0,1)
"$tessera" raster tquad.obj -o textured.png "${view[@]}" --texture halves.png --filter nearest
"$tessera" raster tquad.obj -o plain.png "${view[@]}" --shading phong
"$tessera" raster tquad.obj -o bumped.png "${view[@]}" --bump ramp.png --bump-scale 0.05
"$tessera" raster tquad.obj -o mirror.png "${view[@]}" --env green.png --reflect 1 --color 0,0,0
# A mirror octahedron on the floor: below its middle the surface faces down, and with --env-cube it reflects the
# (gray) floor there; without, only the (green) environment.
cat > octa.obj <<'OBJ'
v 1 0 0
v -1 0 0
v 0 1 0
v 0 -1 0
v 0 0 1
v 0 0 -1
f 1 3 5
f 3 2 5
f 2 4 5
f 4 1 5
f 3 1 6
f 2 3 6
f 4 2 6
f 1 4 6
OBJ
mirror=(--size 48x48 --eye 0,0,4 --center 0,0,0 --floor --env green.png --reflect 1 --color 0,0,0)
"$tessera" raster octa.obj -o mirror_env.png "${mirror[@]}"
"$tessera" raster octa.obj -o mirror_cube.png "${mirror[@]}" --env-cube
# A cube over the floor, lit from the side: with --shadows the floor darkens where the cube hides the light.
"$tessera" raster cube.obj -o lit_floor.png --size 96x64 --floor --light-dir 1,1,0.3 --eye 0,3,6
"$tessera" raster cube.obj -o shadowed_floor.png --size 96x64 --floor --shadows --shadow-size 512 --light-dir 1,1,0.3 \
  --eye 0,3,6 --stats > maps_stats.txt
grep -q '^tris=12$' maps_stats.txt || { echo "expected tris=12 with the floor"; cat maps_stats.txt; exit 1; }
# The same shadow by stencil shadow volumes, counted in front of the surface and behind it.
for method in zpass zfail; do
  "$tessera" raster cube.obj -o "volume_$method.png" --size 96x64 --floor --shadows --shadow-method "$method" \
    --light-dir 1,1,0.3 --eye 0,3,6
done
# A point light beside the cube, inside its bounding sphere: the shadow map has six faces around the light.
near=(cube.obj --size 96x64 --floor --light-pos 1.5,0.3,0.4 --eye 0,3,6)
"$tessera" raster "${near[@]}" -o near_lit.png
"$tessera" raster "${near[@]}" -o near_map.png --shadows --shadow-size 512
"$tessera" raster "${near[@]}" -o near_volumes.png --shadows --shadow-method zfail
$py - <<'PY'
import numpy as np
from PIL import Image
load = lambda name: np.asarray(Image.open(name).convert('RGB')).astype(int)
t = load('textured.png')
assert t[32, 20, 0] - t[32, 20, 2] > 100, t[32, 20]            # left half: red (plus a white highlight)
assert t[32, 44, 2] - t[32, 44, 0] > 100, t[32, 44]            # right half: blue
plain, bumped = load('plain.png'), load('bumped.png')
assert (np.abs(plain - bumped).max(axis=2) > 8).sum() > 200, 'the bump map changed too little'
m = load('mirror.png')
assert m[2, 2, 1] > 250 and m[2, 2, 0] < 5, m[2, 2]           # the background shows the environment
assert m[32, 20, 1] - m[32, 20, 0] > 100, m[32, 20]            # and the mirror reflects it
env, cube = load('mirror_env.png'), load('mirror_cube.png')
assert env[34, 24, 1] - env[34, 24, 0] > 100, env[34, 24]     # the environment: green
assert abs(cube[34, 24, 1] - cube[34, 24, 0]) < 30 and cube[34, 24, 0] > 60, cube[34, 24]  # the floor: gray
lit, shadowed = load('lit_floor.png'), load('shadowed_floor.png')
darker = (lit.sum(axis=2) - shadowed.sum(axis=2) > 60).sum()
brighter = (shadowed.sum(axis=2) - lit.sum(axis=2) > 3).sum()
assert darker > 150 and brighter == 0, (darker, brighter)
for method in ('zpass', 'zfail'):
    volume = load(f'volume_{method}.png')
    # The map's shadow and the volumes' agree but on its outline (the map's texels, its bias).
    differ = (np.abs(volume - shadowed).max(axis=2) > 60).sum()
    assert differ < darker / 10, (method, differ, darker)
lit, near_map, near_volumes = load('near_lit.png'), load('near_map.png'), load('near_volumes.png')
darker = (lit.sum(axis=2) - near_map.sum(axis=2) > 60).sum()
assert darker > 150 and (near_map.sum(axis=2) - lit.sum(axis=2) > 3).sum() == 0, darker
differ = (np.abs(near_volumes - near_map).max(axis=2) > 60).sum()
assert differ < darker / 10, (differ, darker)
PY

# --opacity: an unlit white cube at alpha 0.5 over black, its triangles sorted far to near, is two layers deep inside
# its outline: 0.5 (front) + 0.5 x 0.5 (back, blended first) = 0.75 of white (191); opacity 0 leaves the background.
"$tessera" raster cube.obj -o opaque.png --size 64x64 --shading unlit --color 1,1,1 --quiet
"$tessera" raster cube.obj -o half.png --size 64x64 --shading unlit --color 1,1,1 --opacity 0.5 --quiet
"$tessera" raster cube.obj -o clear.png --size 64x64 --shading unlit --color 1,1,1 --opacity 0 --quiet
"$py" - <<'PY'
import numpy as np
from PIL import Image
opaque, half, clear = (np.asarray(Image.open(f).convert("L"), dtype=int)
                       for f in ("opaque.png", "half.png", "clear.png"))
inside = opaque == 255
assert inside.sum() > 500, inside.sum()
assert (abs(half[inside] - 191) <= 1).mean() > 0.95, np.unique(half[inside], return_counts=True)
assert (half[~inside] == 0).all() and (clear == 0).all()
PY

# Errors: the exit status, a clear message, and no output file (neither the image nor the depth file).
expect_error() {
  local status="$1" pattern="$2"
  shift 2
  set +e
  "$tessera" raster "$@" 2> err.txt
  local rc=$?
  set -e
  [ "$rc" -eq "$status" ] || { echo "expected exit $status, got $rc for: $*"; cat err.txt; exit 1; }
  grep -qi -- "$pattern" err.txt || { echo "message lacks '$pattern':"; cat err.txt; exit 1; }
  for f in bad.png bad.pfm bad.xyz; do [ ! -e "$f" ] || { echo "$f was written for: $*"; exit 1; }; done
}
printf 'v 0 0 0\nv 1 0 0\nf 1 2 7\n' > broken.obj
expect_error 1 "missing.obj" missing.obj -o bad.png
expect_error 1 "broken.obj" broken.obj -o bad.png
expect_error 1 "color" cube.obj -o bad.png --color 2,0,0
expect_error 1 "\.pfm" cube.obj -o bad.png --depth-out bad.png
expect_error 1 "not both" cube.obj -o bad.png --light-dir 0,0,1 --light-pos 0,0,5
expect_error 1 "size" cube.obj -o bad.png --size 0x10
expect_error 1 "near" cube.obj -o bad.png --near 5 --far 2
expect_error 1 "xyz" cube.obj -o bad.xyz
expect_error 1 "" cube.obj -o bad.png --depth-out no_such_dir/bad.pfm
expect_error 2 "shading" cube.obj -o bad.png --shading toon
expect_error 2 "repeat" cube.obj -o bad.png --repeat 0
expect_error 2 "bump-scale: expected a number >= 0, got -1" cube.obj -o bad.png --bump-scale -1
expect_error 2 "opacity: expected a finite number, got 'nan'" cube.obj -o bad.png --opacity nan
expect_error 2 "cull" cube.obj -o bad.png --cull front
expect_error 2 "output" cube.obj
expect_error 1 "texture coordinates" cube.obj -o bad.png --texture halves.png
expect_error 1 "missing.png" tquad.obj -o bad.png --texture missing.png
expect_error 1 "per pixel" tquad.obj -o bad.png --texture halves.png --shading gouraud
expect_error 1 "wireframe" cube.obj -o bad.png --shadows --wireframe
expect_error 1 "env-cube" tquad.obj -o bad.png --env-cube
expect_error 1 "add --shadows" cube.obj -o bad.png --shadow-method zfail
expect_error 2 "shadow-method" cube.obj -o bad.png --shadows --shadow-method volume
expect_error 2 "filter" tquad.obj -o bad.png --texture halves.png --filter cubic
expect_error 1 "opacity" cube.obj -o bad.png --opacity 0.5 --floor
expect_error 2 "opacity" cube.obj -o bad.png --opacity 1.5
expect_error 2 "reflect" tquad.obj -o bad.png --env green.png --reflect 2
echo "raster CLI ok"
