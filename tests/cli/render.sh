#!/usr/bin/env bash
# tessera render: built-in scenes and a scene file, image formats, --stats keys, --srgb against the formula, identical
# output for any thread count, clean failures (exit codes, messages with the JSON path, no partial output).
set -euo pipefail
tessera="$1"
scratch="$2"
check="$(cd "$(dirname "$0")" && pwd)/srgb_check.py"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"

"$tessera" render whitted -o w.png --size 64x48 --spp 1 --quiet && test -s w.png
"$tessera" render cornell -o c.hdr --size 32x32 --spp 2 --stats > stats.txt
for key in width height pixels samples objects lights eye_rays rays seconds rays_per_s read_s compute_s write_s \
  total_s; do
  grep -q "^$key=" stats.txt || { echo "missing $key"; cat stats.txt; exit 1; }
done
grep -q '^eye_rays=2048$' stats.txt
grep -q '^pixels=1024$' stats.txt
grep -q '^samples=2$' stats.txt
test -s c.hdr

# A scene file with a mesh beside it (paths are relative to the scene file).
mkdir -p sub/meshes
printf 'v -1 0 -1\nv 1 0 -1\nv 0 1.5 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n' > sub/meshes/tet.obj
cat > sub/scene.json <<'JSON'
{"image": {"size": [40, 30], "samples": 2},
 "camera": {"eye": [0, 1, 5], "center": [0, 0.5, 0]},
 "lights": [{"type": "point", "position": [2, 5, 5]}],
 "materials": {"m": {"diffuse": [0.8, 0.3, 0.2]}},
 "objects": [{"type": "mesh", "file": "meshes/tet.obj", "material": "m"},
             {"type": "plane", "material": "m"}]}
JSON
"$tessera" render sub/scene.json -o s.pfm --quiet && test -s s.pfm

# The rasterizer backend: same scene, local shading and shadow maps.
"$tessera" render shapes -o r.png --backend raster --size 80x40 --stats > rstats.txt
for key in width height pixels samples objects lights seconds read_s compute_s write_s total_s; do
  grep -q "^$key=" rstats.txt || { echo "raster: missing $key"; cat rstats.txt; exit 1; }
done
grep -q '^samples=1$' rstats.txt && test -s r.png
# ... and with shadow volumes, every light's shadows.
"$tessera" render cornell -o rv.png --backend raster --shadow-method volumes --size 64x64 --quiet && test -s rv.png

# --srgb encodes with the sRGB formula, for both backends: a square of linear 0.2 gray filling an orthographic view
# (ambient 1, no lights) is round(255 * srgb(0.2)) = 124 with it, and 51 without.
py=/usr/bin/python3
cat > gray.json <<'JSON'
{"image": {"size": [8, 8]}, "ambient": 1,
 "camera": {"eye": [0, 0, 5], "projection": "orthographic", "ortho_height": 2},
 "materials": {"m": {"diffuse": 0.2}},
 "objects": [{"type": "polygon", "material": "m", "vertices": [[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]]}]}
JSON
for backend in raytrace raster; do
  "$tessera" render gray.json -o "g_$backend.png" --backend "$backend" --srgb --quiet
  "$py" "$check" pixel "g_$backend.png" 3 3 0.2,0.2,0.2
  "$tessera" render gray.json -o "l_$backend.png" --backend "$backend" --quiet
  "$py" -c "import sys; from PIL import Image; sys.exit(Image.open(sys.argv[1]).getpixel((3, 3))[:3] != (51, 51, 51))" \
    "l_$backend.png"
done

# Identical pictures for any thread count (per-pixel seeded sampling).
"$tessera" render motion-blur -o t1.ppm --size 48x32 --spp 4 --threads 1 --quiet
"$tessera" render motion-blur -o t2.ppm --size 48x32 --spp 4 --threads 2 --quiet
cmp t1.ppm t2.ppm

expect_error() {
  local code="$1" pattern="$2" out="$3"
  shift 3
  set +e
  "$tessera" "$@" 2> err.txt
  local rc=$?
  set -e
  [ "$rc" -eq "$code" ] || { echo "expected exit $code, got $rc for: $*"; cat err.txt; exit 1; }
  grep -q -- "$pattern" err.txt || { echo "message lacks '$pattern':"; cat err.txt; exit 1; }
  [ ! -e "$out" ] || { echo "$out was written"; exit 1; }
}
printf '{"materials": {"m": {}}, "objects": [{"type": "sphere", "radius": -2, "material": "m"}]}' > bad.json
expect_error 1 "objects\[0\].radius: expected a positive number" bad1.png render bad.json -o bad1.png
printf '{"objects": [' > broken.json
expect_error 1 "broken.json: byte offset" bad2.png render broken.json -o bad2.png
expect_error 1 "built-in scene" bad3.png render no-such-scene -o bad3.png
expect_error 1 "expected an image file" bad4.xyz render whitted -o bad4.xyz --size 8x8
expect_error 2 "size" bad5.png render whitted -o bad5.png --size 0x8
expect_error 2 "size" bad5.png render whitted -o bad5.png --size 800
expect_error 2 "backend" bad6.png render whitted -o bad6.png --backend vulkan
expect_error 1 "positive number" bad8.png render bad.json -o bad8.png --backend raster
expect_error 2 "required" bad7.png render -o bad7.png
expect_error 1 "add --backend raster" bad9.png render whitted -o bad9.png --shadow-method volumes
# Recursion depth and samples within the scene format's limits (--depth 100000 overflowed the stack on two mirrors).
expect_error 1 "recursion depth in \[1, 64\], got 100000" bad10.png \
  render whitted -o bad10.png --size 8x8 --depth 100000
expect_error 1 "samples in \[1, 65536\], got 0" bad11.png render whitted -o bad11.png --size 8x8 --spp 0
expect_error 2 "shadow-method" bad10.png render whitted -o bad10.png --backend raster --shadow-method zpass
# Choices are listed by name, never by internal numbers.
"$tessera" render --help > help.txt
grep -q "raytrace" help.txt && grep -q "volumes" help.txt
! grep -q -- "->" help.txt || { echo "--help shows internal values:"; grep -- "->" help.txt; exit 1; }
# Orthographic scenes: a bad projection names its JSON path.
printf '{"camera": {"projection": "fisheye"}, "materials": {"m": {}}, "objects": [{"type": "sphere", "material": "m"}]}' \
  > fish.json
expect_error 1 "camera.projection: expected perspective or orthographic" bad12.png render fish.json -o bad12.png
expect_error 1 "shadow volumes need a perspective camera" bad13.png \
  render gray.json -o bad13.png --backend raster --shadow-method volumes
echo "render CLI ok"
