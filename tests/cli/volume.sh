#!/usr/bin/env bash
# tessera volume: every subcommand on a procedural volume and on a small raw file; --stats keys; --srgb; default
# pictures that show something (built-in and shared volumes, every preset on the foot CT); the default view; --ortho;
# clean failures.
set -euo pipefail
tessera="$1"
scratch="$2"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"

# A 4x4x4 uint8 raw volume: a bright 2x2x2 core in a dark shell.
/usr/bin/python3 -c "
import sys
data = bytes(200 if 1 <= x <= 2 and 1 <= y <= 2 and 1 <= z <= 2 else 10 for z in range(4) for y in range(4) for x in range(4))
open('cube.raw', 'wb').write(data)
open('short.raw', 'wb').write(data[:40])
"
raw=(--dims 4,4,4 --dtype uint8)

"$tessera" volume info sphere:16 | grep -q '^dims=16,16,16$'
"$tessera" volume info cube.raw "${raw[@]}" | grep -q '^max=200$'

"$tessera" volume isosurface gyroid:24 --iso 0 -o gyroid.obj --stats > stats.txt
# The vocabulary's keys, the phases, and the deprecated spellings scripts rely on (tris, verts, seconds = compute_s).
for key in triangles vertices area volume tris verts seconds read_s compute_s write_s total_s; do
  grep -q "^$key=" stats.txt || { echo "isosurface --stats: missing $key"; exit 1; }
done
[ "$(grep '^tris=' stats.txt | cut -d= -f2)" = "$(grep '^triangles=' stats.txt | cut -d= -f2)" ] || { echo "tris != triangles"; exit 1; }
[ "$(grep '^seconds=' stats.txt | cut -d= -f2)" = "$(grep '^compute_s=' stats.txt | cut -d= -f2)" ] || { echo "seconds != compute_s"; exit 1; }
test -s gyroid.obj
"$tessera" volume isosurface cube.raw "${raw[@]}" --iso 100 --topological -o cube.ply --stats | grep -q '^tris=[1-9]'

"$tessera" volume slice torus:20 --axis z --slice 10 -o slice.png && test -s slice.png
"$tessera" volume slice cube.raw "${raw[@]}" --axis x --slice 1 -o slice_raw.png && test -s slice_raw.png
"$tessera" volume contour sphere:20 --axis y --slice 10 --iso 0 -o contour.svg && grep -q '<polygon' contour.svg
"$tessera" volume contour cube.raw "${raw[@]}" --slice 1 --iso 100 -o contour.png && test -s contour.png
"$tessera" volume render metaballs:24 -o dvr.png --size 48x40 && test -s dvr.png
"$tessera" volume render cube.raw "${raw[@]}" --mip -o mip.png --size 32x32 && test -s mip.png
printf '0,0,0,0,0\n1,1,1,1,0.5\n' > tf.csv
"$tessera" volume render sphere:16 --tf tf.csv --eye 0,0,4 -o tf.png --size 24x24 && test -s tf.png
# The shared camera options: a view from +x with another up vector and field of view.
"$tessera" volume render torus:16 --eye 5,0,0 --up 0,0,1 --fovy 40 -o side.png --size 32x24 && test -s side.png

# --stats on every subcommand: counts from the vocabulary, then the phases and total_s.
expect_keys() {
  local what="$1" keys="$2"
  shift 2
  "$tessera" "$@" --stats > keys.txt
  for key in $keys read_s total_s; do grep -q "^$key=" keys.txt || { echo "$what --stats: missing $key"; cat keys.txt; exit 1; }; done
}
expect_keys info "voxels" volume info sphere:8
grep -q '^voxels=512$' keys.txt || { echo "info: voxels of sphere:8"; exit 1; }
expect_keys slice "width height compute_s write_s" volume slice torus:12 --slice 3 -o s.png
grep -q '^width=12$' keys.txt && grep -q '^height=12$' keys.txt || { echo "slice: size of a 12x12 slice"; exit 1; }
expect_keys contour "vertices edges compute_s write_s" volume contour sphere:20 --iso 0 -o c.svg
expect_keys contour "vertices edges width height write_s" volume contour sphere:20 --iso 0 -o c.png
expect_keys render "width height pixels compute_s write_s" volume render sphere:8 --size 20x10 -o r.png
# pixels: those the volume covers; the ball (radius 0.7 in the box [-1, 1]^3) covers some of the 200, not all.
covered=$(grep '^pixels=' keys.txt | cut -d= -f2)
[ "$covered" -gt 0 ] && [ "$covered" -lt 200 ] || { echo "render: pixels=$covered of 20x10"; exit 1; }

# --srgb: 8-bit output encoded with the sRGB formula (checked against the linear PFM of the same picture).
py=/usr/bin/python3 srgb_check="$(dirname "$0")/srgb_check.py"
[ -f "$srgb_check" ] || srgb_check="$OLDPWD/$srgb_check"
"$tessera" volume slice torus:16 --slice 8 -o slice.pfm
"$tessera" volume slice torus:16 --slice 8 -o slice_srgb.png --srgb
"$py" "$srgb_check" pfm slice.pfm slice_srgb.png || { echo "slice --srgb"; exit 1; }
"$tessera" volume render metaballs:20 --size 24x24 -o dvr.pfm --quiet
"$tessera" volume render metaballs:20 --size 24x24 -o dvr_srgb.png --srgb --quiet
"$py" "$srgb_check" pfm dvr.pfm dvr_srgb.png || { echo "render --srgb"; exit 1; }
"$tessera" volume contour sphere:20 --iso 0 -o c_srgb.png --srgb

# The default picture of every built-in volume shows it: a reasonable share of the pixels is not background.
lit() {  # lit FILE.pfm MIN_FRACTION: the share of pixels brighter than 0.02
  "$py" - "$1" "$2" <<'PY'
import sys, numpy as np
data = open(sys.argv[1], "rb").read()
magic, size, scale, body = data.split(b"\n", 3)
w, h = map(int, size.split())
img = np.frombuffer(body[: w * h * 12], dtype="<f4" if float(scale) < 0 else ">f4").reshape(h, w, 3)
share = float((img.max(axis=2) > 0.02).mean())
print(f"{sys.argv[1]}: {share:.3f} of the pixels lit")
sys.exit(0 if share >= float(sys.argv[2]) else 1)
PY
}
for spec in sphere:24 torus:24 gyroid:24 metaballs:24 noise:24; do
  "$tessera" volume render "$spec" --size 48x48 -o "default_${spec%%:*}.pfm" --quiet
  lit "default_${spec%%:*}.pfm" 0.04 || { echo "the default render of $spec is (nearly) black"; exit 1; }
done
"$tessera" volume render cube.raw "${raw[@]}" --size 48x48 -o default_raw.pfm --quiet
lit default_raw.pfm 0.04 || { echo "the default render of a raw volume is (nearly) black"; exit 1; }
# The shared CT and MRI volumes, with the default transfer function and (the foot CT) every preset.
volumes="${TESSERA_SHARED_DATA:-}/volumes"
if [ -n "${TESSERA_SHARED_DATA:-}" ] && [ -f "$volumes/foot_256x256x256_uint8.mhd" ]; then
  for name in foot_256x256x256_uint8 headsq_64x64x93_int16le hydrogen_atom_128x128x128_uint8 mr_head_160x232x160_uint8; do
    "$tessera" volume render "$volumes/$name.mhd" --size 64x64 -o "$name.pfm" --quiet
    lit "$name.pfm" 0.05 || { echo "the default render of $name is (nearly) black"; exit 1; }
  done
  for preset in ct-bone ct-skin mri; do
    "$tessera" volume render "$volumes/foot_256x256x256_uint8.mhd" --preset $preset --size 64x64 -o "foot_$preset.pfm" 2> note.txt
    grep -q "preset $preset over values" note.txt || { echo "no note on where $preset was placed"; cat note.txt; exit 1; }
    lit "foot_$preset.pfm" 0.1 || { echo "--preset $preset on the foot CT is (nearly) black"; exit 1; }
  done
else
  echo "skipped: the shared CT/MRI volumes (no \$TESSERA_SHARED_DATA/volumes/foot_256x256x256_uint8.mhd)"
fi

# The default view is not along an axis: a one-voxel rod along x, y or z projects to a line, not a dot.
for axis in 0 1 2; do
  "$py" -c "
import sys
a = int(sys.argv[1])
open('rod.raw', 'wb').write(bytes(255 if all(p == 8 for i, p in enumerate((x, y, z)) if i != a) else 0
                                  for z in range(17) for y in range(17) for x in range(17)))" $axis
  "$tessera" volume render rod.raw --dims 17,17,17 --mip --size 64x64 -o rod.pfm
  "$py" - rod.pfm <<'PY' || { echo "the default view looks along axis $axis"; exit 1; }
import sys, numpy as np
data = open(sys.argv[1], "rb").read()
magic, size, scale, body = data.split(b"\n", 3)
w, h = map(int, size.split())
img = np.frombuffer(body[: w * h * 12], dtype="<f4").reshape(h, w, 3)
ys, xs = np.nonzero(img[:, :, 0] > 0.25)
extent = np.hypot(xs.max() - xs.min(), ys.max() - ys.min())
# The rod (16 units) at 35 degrees or more from the view is at least 9 units long on screen; the view spans 2.2 x 13.9.
sys.exit(0 if extent > 0.25 * w else 1)
PY
done

# --ortho: a sphere's silhouette (radius 0.7) is 0.7 / ortho-size of the image height, from near and far alike.
printf -- '-0.005,1,1,1,0\n0.005,1,1,1,1\n' > step.csv
for eye in 0.8,1.6,2.4 3.2,6.4,9.6; do
  "$tessera" volume render sphere:48 --tf step.csv --ortho --ortho-size 2.5 --eye $eye --size 101x101 -o ortho.pfm
  "$py" - ortho.pfm <<'PY' || { echo "--ortho silhouette from $eye"; exit 1; }
import sys, numpy as np
data = open(sys.argv[1], "rb").read()
magic, size, scale, body = data.split(b"\n", 3)
w, h = map(int, size.split())
img = np.frombuffer(body[: w * h * 12], dtype="<f4").reshape(h, w, 3)
radius = np.sqrt((img.max(axis=2) > 0.1).sum() / np.pi)
expected = 0.7 / 2.5 * h
print(f"ortho silhouette radius {radius:.2f} px, analytic {expected:.2f}")
sys.exit(0 if abs(radius - expected) < 0.6 else 1)
PY
done
"$tessera" volume render sphere:16 --ortho -o ortho_default.png --size 32x32 --quiet

# Progress: --progress plain prints the rendering's phase for logs.
"$tessera" volume render sphere:16 --size 32x32 -o progress.png --progress plain 2> progress.txt
grep -q '^render: started$' progress.txt && grep -q '^render: done' progress.txt || { echo "no render progress"; cat progress.txt; exit 1; }

# A default --iso (Otsu's threshold, said on stderr); an --iso outside the values warns that the output is empty.
"$tessera" volume isosurface cube.raw "${raw[@]}" -o auto.obj 2> note.txt && grep -q "Otsu" note.txt
"$tessera" volume contour cube.raw "${raw[@]}" -o auto.svg 2> note.txt && grep -q "Otsu" note.txt && grep -q '<polygon' auto.svg
"$tessera" volume isosurface cube.raw "${raw[@]}" --iso 500 -o empty.obj 2> warn.txt
grep -q "outside the volume's values \[10, 200\]" warn.txt || { echo "no warning for an iso value outside"; cat warn.txt; exit 1; }
# The middle slice by default.
"$tessera" volume slice sphere:9 -o mid.png --stats | grep -q '^width=9$'

# A picture of nothing but background says why: a transfer function clear over the data, or a camera looking away.
printf '100,1,1,1,0\n200,1,1,1,1\n' > far.csv
"$tessera" volume render sphere:16 --tf far.csv -o clear.png --size 16x16 2> warn.txt
grep -q "transparent over the volume's values" warn.txt || { echo "no warning for a clear transfer function"; exit 1; }
"$tessera" volume render sphere:16 --eye 10,0,0 --center 20,0,0 -o away.png --size 16x16 2> warn.txt
grep -q "only the background" warn.txt || { echo "no warning for a camera looking away"; exit 1; }
"$tessera" volume render sphere:16 -o seen.png --size 16x16 2> warn.txt
! grep -q "warning" warn.txt || { echo "a warning on a good picture"; cat warn.txt; exit 1; }

# A preset cannot apply to a constant volume: exit 1 saying why.
/usr/bin/python3 -c "open('flat.raw', 'wb').write(bytes([7]) * 64)"
set +e
"$tessera" volume render flat.raw "${raw[@]}" --preset ct-bone -o flat.png 2> err.txt
rc=$?
set -e
[ "$rc" -eq 1 ] && grep -q "cannot apply: every voxel has the value 7" err.txt && [ ! -e flat.png ] || { echo "preset on a constant volume"; cat err.txt; exit 1; }
"$tessera" volume render flat.raw "${raw[@]}" -o flat.pfm --quiet  # the default shows the box as a haze
"$tessera" volume render flat.raw "${raw[@]}" --mip -o flat_mip.png 2> warn.txt
grep -q "every voxel has the value 7: the projection is black" warn.txt || { echo "MIP of a constant volume"; cat warn.txt; exit 1; }
"$tessera" volume slice flat.raw "${raw[@]}" -o flat_slice.png 2> warn.txt
grep -q "every voxel has the value 7: the slice is black" warn.txt || { echo "slice of a constant volume"; cat warn.txt; exit 1; }
lit flat.pfm 0.04 || { echo "the default render of a constant volume is black"; exit 1; }
# Usage errors (exit 2): an unknown preset, --tf with --preset, --mip with a transfer function.
for args in "--preset bone" "--preset ct-bone --tf tf.csv" "--mip --preset mri" "--dtype uint9" "--endian middle" \
            "--dims 4,4" "--spacing 1,x,1" "--axis w" "--fovy 180" "--near 1"; do
  set +e
  "$tessera" volume $([[ $args == --axis* ]] && echo slice || echo render) sphere:8 $args -o usage.png 2> err.txt
  rc=$?
  set -e
  [ "$rc" -eq 2 ] || { echo "expected exit 2 for $args, got $rc"; cat err.txt; exit 1; }
done

# Errors: exit 1, a clear message, no output file.
expect_error() {
  local pattern="$1" out="$2"
  shift 2
  set +e
  "$tessera" "$@" 2> err.txt
  local rc=$?
  set -e
  [ "$rc" -eq 1 ] || { echo "expected exit 1, got $rc for: $*"; exit 1; }
  grep -q "$pattern" err.txt || { echo "message lacks '$pattern':"; cat err.txt; exit 1; }
  [ ! -e "$out" ] || { echo "$out was written"; exit 1; }
}
expect_error "too short" bad.obj volume isosurface short.raw "${raw[@]}" --iso 1 -o bad.obj
expect_error "dims" bad2.obj volume isosurface cube.raw --dims 4,0,4 --iso 1 -o bad2.obj
expect_error "needs --dims" bad3.obj volume isosurface cube.raw --iso 1 -o bad3.obj
expect_error "describes raw files only" bad4.obj volume isosurface sphere:8 --dims 8,8,8 --iso 0 -o bad4.obj
/usr/bin/python3 -c "open('head.mhd', 'w').write('NDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\nElementDataFile = cube.raw\n')"
"$tessera" volume info head.mhd | grep -q '^max=200$'
expect_error "dtype describes raw files only" bad5.png volume slice head.mhd --dtype int16 -o bad5.png
expect_error "outside" bad.png volume slice sphere:8 --slice 9 -o bad.png
expect_error "SVG's colors are not encoded" bad.svg volume contour sphere:8 --iso 0 --srgb -o bad.svg
# Issue 24, class 1: a step below half an ulp of the ray distance hung (t += step stopped advancing); class 2: a tiny
# step rendered black (the per-step opacity rounded to 0) with exit 0. Both are refused with the limit named.
for mode in --mip ""; do
  set +e
  timeout 60 "$tessera" volume render sphere:16 -o step.pfm --size 8x8 $mode --step 1e-9 2> err.txt
  rc=$?
  set -e
  [ "$rc" -eq 1 ] || { echo "--step 1e-9 $mode: expected exit 1, got $rc (124: it hung)"; cat err.txt; exit 1; }
  grep -q "samples per ray.*at most 1048576" err.txt || { echo "--step 1e-9: unclear message:"; cat err.txt; exit 1; }
  [ ! -e step.pfm ] || { echo "--step 1e-9 wrote step.pfm"; exit 1; }
done
# Class 2: NaN and infinite voxels, and a box beyond the finite numbers, are errors naming the input, never a file.
/usr/bin/python3 -c "
import struct
for name, bad in (('nan.raw', float('nan')), ('inf.raw', float('inf'))):
    v = [0.0] * 8
    v[5] = bad  # voxel (1, 0, 1) of 2x2x2: byte offset 20
    open(name, 'wb').write(struct.pack('<8f', *v))
"
for bad in nan inf; do
  expect_error "$bad.raw: voxel (1, 0, 1) at byte offset 20 is $bad" bad.obj \
    volume isosurface $bad.raw --dims 2,2,2 --dtype float32 --iso 0.5 -o bad.obj
  expect_error "$bad.raw: voxel (1, 0, 1)" bad.pfm volume render $bad.raw --dims 2,2,2 --dtype float32 -o bad.pfm --size 8x8
  expect_error "$bad.raw: voxel (1, 0, 1)" bad.pfm volume slice $bad.raw --dims 2,2,2 --dtype float32 -o bad.pfm
done
expect_error "beyond the finite numbers" bad.obj volume isosurface cube.raw "${raw[@]}" --spacing 1e308,1,1 --iso 100 -o bad.obj
# Class 5: header lines and values are quoted through printable(): an escape byte is spelled \x1b, a 10 KB value is cut
# with its length, and the message stays short (NRRD type, MetaImage ElementType, a MetaImage data file name).
/usr/bin/python3 -c "
hostile = b'\x1b[31m' + b'A' * 10240
open('esc.nrrd', 'wb').write(b'NRRD0004\ntype: ' + hostile + b'\n')
open('esc.mhd', 'wb').write(b'NDims = 3\nElementType = ' + hostile + b'\n')
open('escfile.mhd', 'wb').write(b'NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = ' + hostile + b'\n')
"
for case in "esc.nrrd:esc.nrrd:2: unsupported type '" "esc.mhd:esc.mhd:2: unsupported ElementType '" \
  "escfile.mhd:escfile.mhd: cannot open '"; do
  expect_error "${case#*:}\\\\x1b\[31mAAAA.*bytes)" bad.png volume slice "${case%%:*}" -o bad.png
  ! grep -q $'\x1b' err.txt || { echo "${case%%:*}: a raw escape byte reached the message"; exit 1; }
  [ "$(wc -c < err.txt)" -lt 400 ] || { echo "${case%%:*}: the message is $(wc -c < err.txt) bytes"; exit 1; }
done
# Class 3: a 700x700x1 uint8 checkerboard. Reading it needs 8 bytes a voxel (its float copy and the copy that
# profiling sorts: 3.7 MiB), a slice 24 bytes a pixel (11.2 MiB: a flat volume's slice is as large as the volume), and marching squares,
# which counts the segments and checks 200 bytes each before storing them, 2 x 699^2 saddle segments (186 MiB).
/usr/bin/python3 -c "
open('checker.raw', 'wb').write(bytes(255 * ((x + y) % 2) for y in range(700) for x in range(700)))
"
expect_error "checker.raw: reading 700x700x1 uint8 voxels needs about 3.7 MiB, the memory budget is 1.0 MiB" \
  bad.png volume slice checker.raw --dims 700,700,1 -o bad.png --max-memory 1M
expect_error "a 700x700 slice needs about 11.2 MiB, the memory budget is 8.0 MiB" \
  bad.png volume slice checker.raw --dims 700,700,1 -o bad.png --max-memory 8M
expect_error "marching squares: 977202 contour segments of a 700x700 field needs about 186.4 MiB, the memory budget is 20.0 MiB" \
  bad.svg volume contour checker.raw --dims 700,700,1 --iso 100 -o bad.svg --max-memory 20M
"$tessera" volume slice checker.raw --dims 700,700,1 -o slice_checker.png --max-memory 12M && test -s slice_checker.png
echo "volume CLI ok"
