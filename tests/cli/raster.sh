#!/usr/bin/env bash
# tessera raster: every shading model and option on a hand-written cube and quad; a known pixel color and an analytic
# depth read back from --depth-out; --stats keys agreeing with the depth file; the same picture for any --threads;
# clean failures (exit 1 or 2, a message, no output file).
# $1 = the tessera binary, $2 = a scratch folder.
set -euo pipefail
tessera="$1"
scratch="$2"
data="$(cd "$(dirname "$0")/../data" && pwd)"
shaders="$(cd "$(dirname "$0")/../../examples/shaders" && pwd)"
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

# --stats: the keys (docs/cli.md; tris and seconds kept for scripts), 12 triangles for the cube (6 quads), and
# `pixels` equal to the covered pixels of --depth-out.
"$tessera" raster cube.obj -o stats.png --size 40x30 --depth-out stats.pfm --repeat 3 --stats > stats.txt
keys="triangles tris pixels width height samples seconds tris_per_s read_s compute_s write_s total_s"
[ "$(sed 's/=.*//' stats.txt | tr '\n' ' ')" = "$keys " ] || { echo "expected the keys $keys"; cat stats.txt; exit 1; }
grep -q '^tris=12$' stats.txt && grep -q '^triangles=12$' stats.txt || { echo "expected 12 triangles"; cat stats.txt; exit 1; }
grep -q '^width=40$' stats.txt && grep -q '^height=30$' stats.txt && grep -q '^samples=1$' stats.txt \
  || { echo "expected width=40 height=30 samples=1"; cat stats.txt; exit 1; }
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

# The framed views (CameraOptions, docs/raster3d.md): trace --shade normal shows n/2 + 1/2. On a unit sphere seen
# orthographically with --ortho-size 2, the center pixel's normal is the direction D toward the eye, and the pixel
# v = 0.49 above it (row 16 of 65) has the normal v U + sqrt(1 - v^2) D, U the image's up. D and U are written out
# by hand for each view and up axis. Then the eye's distance: bench raycast's single 1x1 ray from the eye to the
# center of the cube [-1,1]^3 hits it at t = d - 1/max|D_i|, with the framing distance d = 1.1 sqrt(3) / sin(22.5 deg).
$py - <<'PY'
import math
n, m = 48, 97  # 97 meridians: no view direction runs exactly along an edge
with open('sphere.obj', 'w') as f:
    for i in range(n + 1):
        for j in range(m):
            th, ph = math.pi * i / n, 2 * math.pi * j / m
            x, y, z = math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)
            f.write(f'v {x:.9f} {y:.9f} {z:.9f}\nvn {x:.9f} {y:.9f} {z:.9f}\n')
    for i in range(n):
        for j in range(m):
            a, b = i * m + j + 1, i * m + (j + 1) % m + 1
            f.write(f'f {a}//{a} {a + m}//{a + m} {b + m}//{b + m} {b}//{b}\n')
PY
# view:up-axis[:front-axis]
views="front:y back:y left:y right:y top:y bottom:y iso:y three-quarter:y front:z top:z right:z front:x front:y:-z
       right:y:-z front:z:+x top:z:+x"
for vuf in $views; do
  IFS=: read -r view up front <<< "$vuf"
  name="${view}_$up${front:+_$front}"
  "$tessera" trace sphere.obj -o "view_$name.png" --shade normal --ortho --ortho-size 2 --size 65x65 \
    --view "$view" --up-axis "$up" --front-axis "${front:-auto}"
  "$tessera" bench raycast cube.obj --size 1x1 --random-rays 0 --view "$view" --up-axis "$up" \
    --front-axis "${front:-auto}" --hits-out "hits_$name.txt" > /dev/null
done
"$tessera" trace sphere.obj -o view_default.png --shade normal --ortho --ortho-size 2 --size 65x65
"$tessera" trace sphere.obj -o view_angles.png --shade normal --ortho --ortho-size 2 --size 65x65 --azimuth -60 \
  --elevation 45 --up-axis z
$py - <<'PY'
import math
import numpy as np
from PIL import Image
s, c = math.sin, math.cos
r = math.radians
i3 = 1 / math.sqrt(3)
# view: (D, U) by hand. y up: front +z, right +x; z up: front -y, right +x; x up: front +z, right -y.
expected = {
    'front_y': ((0, 0, 1), (0, 1, 0)), 'back_y': ((0, 0, -1), (0, 1, 0)),
    'left_y': ((-1, 0, 0), (0, 1, 0)), 'right_y': ((1, 0, 0), (0, 1, 0)),
    'top_y': ((0, 1, 0), (0, 0, -1)), 'bottom_y': ((0, -1, 0), (0, 0, 1)),
    'iso_y': ((i3, i3, i3), (-i3 / math.sqrt(2), math.sqrt(2 / 3), -i3 / math.sqrt(2))),
    'three-quarter_y': ((s(r(30)) * c(r(20)), s(r(20)), c(r(30)) * c(r(20))),
                        (-s(r(30)) * s(r(20)), c(r(20)), -c(r(30)) * s(r(20)))),
    'default': ((s(r(30)) * c(r(20)), s(r(20)), c(r(30)) * c(r(20))),
                (-s(r(30)) * s(r(20)), c(r(20)), -c(r(30)) * s(r(20)))),
    'front_z': ((0, -1, 0), (0, 0, 1)), 'top_z': ((0, 0, 1), (0, 1, 0)), 'right_z': ((1, 0, 0), (0, 0, 1)),
    'front_x': ((0, 0, 1), (1, 0, 0)),
    # --front-axis: Spot's -z (its right is then -x), and +x for z-up (right +y, top view's image up -x).
    'front_y_-z': ((0, 0, -1), (0, 1, 0)), 'right_y_-z': ((-1, 0, 0), (0, 1, 0)),
    'front_z_+x': ((1, 0, 0), (0, 0, 1)), 'top_z_+x': ((0, 0, 1), (-1, 0, 0)),
    # azimuth -60 (toward the left), elevation 45, z up: D = cos 45 (cos 60 (-y) - sin 60 (+x)) + sin 45 z.
    'angles': ((-s(r(60)) * c(r(45)), -c(r(60)) * c(r(45)), s(r(45))),
               (s(r(60)) * s(r(45)), c(r(60)) * s(r(45)), c(r(45)))),
}
v = 1 - 2 * 16.5 / 65
d = 1.1 * math.sqrt(3) / math.sin(math.radians(22.5))
for name, (D, U) in expected.items():
    D, U = np.array(D), np.array(U)
    img = np.asarray(Image.open(f'view_{name}.png').convert('RGB')) / 255.0
    for (row, col), normal in (((32, 32), D), ((16, 32), v * U + math.sqrt(1 - v * v) * D)):
        got = 2 * img[row, col] - 1
        assert np.abs(got - normal).max() < 0.03, (name, row, col, got, normal)
    if name in ('default', 'angles'):
        continue
    index, t, prim = open(f'hits_{name}.txt').read().split()
    want = d - 1 / np.abs(D).max()
    assert abs(float(t) - want) < 1e-4 * d, (name, t, want)
PY

# The teapot (z up) from the front with --up-axis z: its lid's knob, the highest point (z = 3.15, x = 0), is the top
# of the picture, near the middle column; the teapot is wider (spout to handle, 6.4) than tall (3.15).
teapot="${TESSERA_SHARED_DATA:-}/bezier/teapot.bpt"
if [ ! -f "$teapot" ]; then
  echo "skipped the teapot check: no shared data in TESSERA_SHARED_DATA"
else
  "$tessera" patch "$teapot" -o teapot.obj --tess 8 --quiet
  "$tessera" raster teapot.obj -o teapot_front.png --up-axis z --view front --size 160x120 --shading unlit \
    --depth-out teapot_front.pfm
  $py - <<'PY'
import numpy as np
raw = open('teapot_front.pfm', 'rb').read().split(b'\n', 3)
depth = np.frombuffer(raw[3], dtype='<f4').reshape(120, 160)[::-1]  # PFM: bottom row first
rows, cols = np.nonzero(depth < 1)
top = rows.min()
width, height = cols.max() - cols.min() + 1, rows.max() - top + 1
assert width > 1.7 * height, (width, height)
knob = cols[rows == top].mean()
# x = 0 in the picture: the bounds' x range is [-3, 3.43] (handle to spout), at its center 0.215 from x = 0.
x0 = cols.min() + (0 - (-3.0)) / 6.43 * width
assert abs(knob - x0) < 0.06 * width, (knob, x0, width)
PY
fi

# --ortho: the cube's front face with --ortho-size 4 on 100 pixels is 2/4 of the height, exactly 50 x 50 pixels
# (pixel centers in [25, 75)), whatever the width; without --ortho-size the bounding sphere, grown by 10%, fills the
# height: 100 x 2 / (2.2 sqrt 3) = 52.5 pixels. The sphere's disk: pi 25^2 pixels.
"$tessera" raster cube.obj -o ortho.png --view front --ortho --ortho-size 4 --size 160x100 --stats > ortho.txt
"$tessera" raster cube.obj -o ortho_framed.png --view front --ortho --size 100x100 --stats > ortho_framed.txt
"$tessera" raster sphere.obj -o ortho_sphere.png --view front --ortho --ortho-size 4 --size 100x100 --stats \
  > ortho_sphere.txt
grep -q '^pixels=2500$' ortho.txt || { echo "expected 2500 pixels"; cat ortho.txt; exit 1; }
framed=$(sed -n 's/^pixels=//p' ortho_framed.txt)
[ "$framed" -ge 2704 ] && [ "$framed" -le 2809 ] || { echo "expected 52-53 squared pixels, got $framed"; exit 1; }
disk=$(sed -n 's/^pixels=//p' ortho_sphere.txt)
$py -c "import math, sys; d = $disk; assert abs(d - math.pi * 625) < 2 * math.pi * 25, d"

# --hidden-surface: two triangles seen from the front, orthographically, unlit. Depth-sortable (a red one at z = 0, a
# green one in front at z = 0.5, overlapping it): the painter's algorithm and the z-buffer give the same picture.
# Intersecting (the green one tilted, z = x + 0.2, through the red one at x = -0.2): the z-buffer shows red left of
# x = -0.2 and green right of it; the painter's algorithm draws the green triangle (centroid z = 0.2, the nearer)
# over all of the red one.
cat > sortable.obj <<'OBJ'
v -1 -1 0 1 0 0
v 1 -1 0 1 0 0
v 0 1 0 1 0 0
v -0.5 -1 0.5 0 1 0
v 1.5 -1 0.5 0 1 0
v 0.5 1 0.5 0 1 0
f 1 2 3
f 4 5 6
OBJ
cat > crossing.obj <<'OBJ'
v -1 -1 0 1 0 0
v 1 -1 0 1 0 0
v 0 1 0 1 0 0
v -1 -1 -0.8 0 1 0
v 1 -1 1.2 0 1 0
v 0 1 0.2 0 1 0
f 1 2 3
f 4 5 6
OBJ
hs=(--view front --ortho --ortho-size 2.5 --size 100x100 --shading unlit --center 0.25,0,0)
for scene in sortable crossing; do
  for method in zbuffer painter; do
    "$tessera" raster "$scene.obj" -o "${scene}_$method.png" "${hs[@]}" --hidden-surface "$method" --stats \
      > "${scene}_$method.txt"
  done
  cmp -s <(grep '^pixels=' "${scene}_zbuffer.txt") <(grep '^pixels=' "${scene}_painter.txt") \
    || { echo "$scene: the two methods cover different pixels"; exit 1; }
done
cmp -s sortable_zbuffer.png sortable_painter.png || { echo "painter and z-buffer differ on a sortable scene"; exit 1; }
$py - <<'PY'
import numpy as np
from PIL import Image
z = np.asarray(Image.open('crossing_zbuffer.png').convert('RGB')).astype(int)
p = np.asarray(Image.open('crossing_painter.png').convert('RGB')).astype(int)
# World x = 0.25 + (col + 0.5 - 50) * 2.5 / 100, y = (50 - row - 0.5) * 2.5 / 100; inside both triangles at y = -0.5.
row = 69
for col, zcolor in ((20, (255, 0, 0)), (28, (255, 0, 0)), (44, (0, 255, 0)), (60, (0, 255, 0))):
    x = 0.25 + (col + 0.5 - 50) * 0.025
    assert tuple(z[row, col]) == zcolor, (col, x, z[row, col])
    assert tuple(p[row, col]) == (0, 255, 0), (col, x, p[row, col])
PY

# --samples: a white half plane x < 0 seen orthographically on 11 pixels across 2 units: the edge runs through the
# centers of column 5, which N samples cover by 1/2 within 1/N (stratified in 1/N strata along x); columns left of it
# stay white, right of it black. --samples 1 is the unsampled picture, byte for byte.
cp "$data/half_plane.obj" half.obj
aa=(--view front --ortho --ortho-size 2 --center 0,0,0 --size 11x11 --shading unlit --color 1,1,1)
"$tessera" raster half.obj -o aa_default.png "${aa[@]}"
"$tessera" raster half.obj -o aa_1.png "${aa[@]}" --samples 1
cmp -s aa_default.png aa_1.png || { echo "--samples 1 differs from the default"; exit 1; }
for n in 4 9 16 64; do "$tessera" raster half.obj -o "aa_$n.png" "${aa[@]}" --samples "$n"; done
# --depth-out with samples: each pixel's nearest depth; the head-on square's is the same at every sample (0.875).
"$tessera" raster quad.obj -o quad_s4.png --size 33x33 --eye 0,0,4 --center 0,0,0 --near 1 --far 7 --fovy 60 \
  --shading unlit --samples 4 --depth-out quad_s4.pfm
$py - <<'PY'
import numpy as np
depth = np.frombuffer(open('quad_s4.pfm', 'rb').read().split(b'\n', 3)[3], dtype='<f4').reshape(33, 33)
assert abs(depth[16, 16] - round(0.875 * (2**24 - 1)) / (2**24 - 1)) < 1e-6, depth[16, 16]
assert depth[0, 0] == 1.0
PY
"$tessera" raster cube.obj -o cube_s1.png --size 64x48 --samples 1
"$tessera" raster cube.obj -o cube_s0.png --size 64x48
cmp -s cube_s0.png cube_s1.png || { echo "--samples 1 differs from the default (cube)"; exit 1; }
"$tessera" raster cube.obj -o cube_s8.png --size 64x48 --samples 8 --stats > cube_s8.txt
grep -q '^samples=8$' cube_s8.txt || { echo "expected samples=8"; cat cube_s8.txt; exit 1; }
$py - <<'PY'
import numpy as np
from PIL import Image
for n in (4, 9, 16, 64):
    a = np.asarray(Image.open(f'aa_{n}.png').convert('L')).astype(float)
    assert (a[:, :5] == 255).all() and (a[:, 6:] == 0).all(), n
    assert (np.abs(a[:, 5] / 255 - 0.5) <= 1 / n + 0.5 / 255).all(), (n, a[:, 5])
one, eight = (np.asarray(Image.open(f).convert('L')).astype(int) for f in ('cube_s1.png', 'cube_s8.png'))
# The silhouette gets in-between values; the number of distinct gray levels grows.
assert len(np.unique(eight)) > len(np.unique(one)), 'no intermediate values'
PY

# --srgb: every pixel is the sRGB curve of the linear picture's value (an unlit gray ramp of vertex colors).
cat > ramp.obj <<'OBJ'
v -1 -1 0 0 0 0
v 1 -1 0 1 1 1
v 1 1 0 1 1 1
v -1 1 0 0 0 0
f 1 2 3 4
OBJ
"$tessera" raster ramp.obj -o ramp_linear.png --view front --size 64x64 --shading unlit
"$tessera" raster ramp.obj -o ramp_srgb.png --view front --size 64x64 --shading unlit --srgb
$py - <<'PY'
import numpy as np
from PIL import Image
lin = np.asarray(Image.open('ramp_linear.png').convert('RGB')) / 255.0
srgb = np.asarray(Image.open('ramp_srgb.png').convert('RGB')).astype(float)
want = np.where(lin <= 0.0031308, 12.92 * lin, 1.055 * lin ** (1 / 2.4) - 0.055) * 255
assert np.abs(srgb - want).max() <= 0.5 + 1e-9, np.abs(srgb - want).max()
assert len(np.unique(lin)) > 30
PY

# An inside-out mesh (every face wound clockwise, no normals in the file) would be lit from behind, black but for the
# ambient term, and culled whole by --cull back: it is drawn turned outward, the same picture as the cube, with a note.
awk '/^f /{printf "f"; for (i = NF; i > 1; i--) printf " %s", $i; print ""; next} {print}' cube.obj > inside_out.obj
for cull in none back; do
  "$tessera" raster cube.obj -o "outward_$cull.png" --size 64x48 --cull "$cull"
  "$tessera" raster inside_out.obj -o "inward_$cull.png" --size 64x48 --cull "$cull" 2> inward.txt
  cmp -s "outward_$cull.png" "inward_$cull.png" || { echo "the inside-out cube differs (--cull $cull)"; exit 1; }
  grep -q "wind inward" inward.txt || { echo "no note on the inside-out cube"; cat inward.txt; exit 1; }
done

# Errors: the exit status, a clear message, and no output file (neither the image nor the depth file).
# GLSL programs (docs/shaders.md): a uniform color fills exactly the pixels the fixed function covers; the texture
# program shows the texture's halves (red left, blue right, nearest texels); the notes' diffuse program is pure red.
cat > flat.vert <<'GLSL'
void main() { gl_Position = ftransform(); }
GLSL
cat > flat.frag <<'GLSL'
uniform vec3 paint;
void main() { gl_FragColor = vec4(paint, 1.0); }
GLSL
"$tessera" raster cube.obj -o glsl_flat.png --size 48x48 --vertex-shader flat.vert --fragment-shader flat.frag \
  --uniform paint=0.2,0.4,0.6
"$tessera" raster cube.obj -o glsl_fixed.png --size 48x48 --shading unlit --color 0.2,0.4,0.6
"$tessera" raster tquad.obj -o glsl_texture.png --size 64x64 --eye 0,0,4 --center 0,0,0 --fovy 40 --vertex-shader "$shaders/notes_texture.vert" \
  --fragment-shader "$shaders/notes_texture.frag" --texture0 halves.png --filter nearest
"$tessera" raster cube.obj -o glsl_diffuse.png --size 48x48 --vertex-shader "$shaders/notes_diffuse.vert" \
  --fragment-shader "$shaders/notes_diffuse.frag" --light-pos 2,3,4
$py -c "
from PIL import Image
a, b = Image.open('glsl_flat.png').convert('RGB'), Image.open('glsl_fixed.png').convert('RGB')
assert list(a.getdata()) == list(b.getdata()), 'the uniform color differs from the fixed-function unlit picture'
assert (51, 102, 153) in set(a.getdata())
t = Image.open('glsl_texture.png').convert('RGB')
assert t.getpixel((22, 32)) == (255, 0, 0) and t.getpixel((42, 32)) == (0, 0, 255), (t.getpixel((22, 32)), t.getpixel((42, 32)))
d = Image.open('glsl_diffuse.png').convert('RGB')
reds = [p for p in d.getdata() if p != (0, 0, 0)]
assert len(reds) > 200 and all(g == 0 and b == 0 for _, g, b in reds), 'the diffuse program is red times N.L'
assert len(set(r for r, _, _ in reds)) > 5, 'N.L varies over the cube faces'
"
printf 'void main() {\n  gl_FragColor = vec4(1.0)\n}\n' > broken.frag

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
expect_error 2 "color" cube.obj -o bad.png --color 2,0,0
expect_error 2 "background" cube.obj -o bad.png --background whiteish
expect_error 2 "size" cube.obj -o bad.png --size 800
expect_error 2 "eye" cube.obj -o bad.png --eye 1,2
expect_error 2 "light-dir" cube.obj -o bad.png --light-dir 1,x,2
expect_error 2 "view" cube.obj -o bad.png --view diagonal
expect_error 2 "up-axis" cube.obj -o bad.png --up-axis w
expect_error 2 "front-axis" cube.obj -o bad.png --front-axis w
expect_error 1 "perpendicular" cube.obj -o bad.png --front-axis -y
expect_error 2 "eye" cube.obj -o bad.png --view top --eye 0,5,0
expect_error 2 "ortho" cube.obj -o bad.png --ortho-size 3
expect_error 2 "fovy" cube.obj -o bad.png --ortho --fovy 30
expect_error 2 "elevation" cube.obj -o bad.png --elevation 100
expect_error 2 "samples" cube.obj -o bad.png --samples 0
expect_error 2 "fovy" cube.obj -o bad.png --fovy 200
# Options that would change nothing are refused, not ignored.
expect_error 2 "no texture to filter" cube.obj -o bad.png --filter nearest
expect_error 2 "bump" cube.obj -o bad.png --bump-scale 0.1
expect_error 2 "shadows" cube.obj -o bad.png --shadow-size 512
expect_error 1 "nothing to reflect" cube.obj -o bad.png --reflect 0.5
expect_error 1 "without lights" cube.obj -o bad.png --shading unlit --light-dir 0,0,1
expect_error 2 "hidden-surface" cube.obj -o bad.png --hidden-surface scanline
expect_error 1 "z-buffer" cube.obj -o bad.png --hidden-surface painter --wireframe
expect_error 1 "depth" cube.obj -o bad.png --hidden-surface painter --depth-out bad.pfm
expect_error 1 "perspective" cube.obj -o bad.png --ortho --floor --shadows --shadow-method zfail
expect_error 1 "\.pfm" cube.obj -o bad.png --depth-out bad.png
expect_error 1 "not both" cube.obj -o bad.png --light-dir 0,0,1 --light-pos 0,0,5
expect_error 2 "size" cube.obj -o bad.png --size 0x10
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
expect_error 2 "needs both" cube.obj -o bad.png --vertex-shader flat.vert
expect_error 2 "add --vertex-shader" cube.obj -o bad.png --uniform paint=1,0,0
expect_error 1 "broken.frag:3:" cube.obj -o bad.png --vertex-shader flat.vert --fragment-shader broken.frag
expect_error 1 "missing.frag" cube.obj -o bad.png --vertex-shader flat.vert --fragment-shader missing.frag
expect_error 1 "declares no uniform 'colour'" cube.obj -o bad.png --vertex-shader flat.vert \
  --fragment-shader flat.frag --uniform colour=1,0,0
expect_error 1 "takes 3 values" cube.obj -o bad.png --vertex-shader flat.vert --fragment-shader flat.frag \
  --uniform paint=1,0
expect_error 1 "name=v1,v2" cube.obj -o bad.png --vertex-shader flat.vert --fragment-shader flat.frag --uniform paint
expect_error 1 "texture unit 16" tquad.obj -o bad.png --vertex-shader flat.vert --fragment-shader flat.frag \
  --texture-unit 16=halves.png
expect_error 1 "does the shading" cube.obj -o bad.png --vertex-shader flat.vert --fragment-shader flat.frag \
  --shading phong
expect_error 1 "do not combine" tquad.obj -o bad.png --vertex-shader flat.vert --fragment-shader flat.frag \
  --texture halves.png
echo "raster CLI ok"
