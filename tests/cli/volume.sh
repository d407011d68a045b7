#!/usr/bin/env bash
# tessera volume: every subcommand on a procedural volume and on a small raw file; --stats keys; clean failures.
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
for key in tris verts area volume seconds; do grep -q "^$key=" stats.txt || { echo "missing $key"; exit 1; }; done
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
expect_error "outside" bad.png volume slice sphere:8 --slice 9 -o bad.png
expect_error "fovy" bad2.png volume render sphere:8 --fovy 180 -o bad2.png
expect_error "near < far" bad3.png volume render sphere:8 --near 5 --far 2 -o bad3.png
echo "volume CLI ok"
