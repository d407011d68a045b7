#!/usr/bin/env bash
# tessera fractal end to end: every subcommand writes its file, the --stats figures land where the notes say, and bad
# input exits 1 with a message. $1: the tessera binary, $2: a scratch folder.
set -euo pipefail
tessera=$1
dir=$2
rm -rf "$dir" && mkdir -p "$dir"

fail() { echo "FAIL: $*" >&2; exit 1; }
# stat KEY < stats lines: the value of KEY
stat() { sed -n "s/^$1=//p"; }
# within VALUE LO HI: LO <= VALUE <= HI
within() { awk -v v="$1" -v lo="$2" -v hi="$3" 'BEGIN { exit !(v >= lo && v <= hi) }'; }
nonempty() { [ -s "$1" ] || fail "$1 was not written"; }

# Every subcommand writes its file.
"$tessera" fractal mandelbrot -o "$dir/m.png" --size 160x120 --quiet; nonempty "$dir/m.png"
"$tessera" fractal julia -o "$dir/j.png" --c -0.123,0.745 --size 160x120 --palette fire; nonempty "$dir/j.png"
"$tessera" fractal cantor -o "$dir/cantor.png" --depth 4 --size 243x243; nonempty "$dir/cantor.png"
"$tessera" fractal cantor -o "$dir/dust.png" --dust --depth 4 --size 243x243; nonempty "$dir/dust.png"
"$tessera" fractal sierpinski -o "$dir/tri.png" --shape triangle --depth 5 --size 256x256; nonempty "$dir/tri.png"
"$tessera" fractal koch -o "$dir/koch.png" --depth 3 --size 200x200; nonempty "$dir/koch.png"
"$tessera" fractal hilbert -o "$dir/hilbert.png" --depth 4 --size 128x128; nonempty "$dir/hilbert.png"
"$tessera" fractal peano -o "$dir/peano.png" --depth 2 --size 162x162; nonempty "$dir/peano.png"
"$tessera" fractal terrain -o "$dir/profile.png" --method midpoint --depth 8; nonempty "$dir/profile.png"
"$tessera" fractal terrain -o "$dir/heights.png" --depth 6; nonempty "$dir/heights.png"
"$tessera" fractal terrain -o "$dir/grid.obj" --depth 4; nonempty "$dir/grid.obj"
"$tessera" fractal terrain -o "$dir/mountain.ply" --method triangles --depth 4; nonempty "$dir/mountain.ply"
grep -q '^f ' "$dir/grid.obj" || fail "grid.obj has no faces"

# Mandelbrot area by pixel counting over the whole set: 1.5066, within 2% on a 512^2 grid.
stats=$("$tessera" fractal mandelbrot -o "$dir/area.png" --center -0.75,0 --scale 2.5 --size 512x512 \
        --iterations 5000 --stats)
area=$(echo "$stats" | stat area)
within "$area" 1.48 1.54 || fail "mandelbrot area $area not near 1.5066"
seconds=$(echo "$stats" | stat seconds)
within "$seconds" 0 1000 || fail "mandelbrot seconds '$seconds'"

# Every SIMD path draws the same picture (bit-identical iteration counts, so identical files).
"$tessera" fractal mandelbrot -o "$dir/scalar.ppm" --size 96x64 --simd scalar --center -0.74,0.11 --scale 0.05
"$tessera" fractal mandelbrot -o "$dir/auto.ppm" --size 96x64 --center -0.74,0.11 --scale 0.05 --threads 2
cmp -s "$dir/scalar.ppm" "$dir/auto.ppm" || fail "scalar and SIMD pictures differ"

# Julia connectedness (the notes: the orbit of 0 stays bounded).
[ "$("$tessera" fractal julia -o "$dir/j2.png" --c -1,0 --size 32x32 --stats | stat connected)" = 1 ] ||
  fail "c = -1 should be connected"
[ "$("$tessera" fractal julia -o "$dir/j3.png" --c 0.4,0.6 --size 32x32 --stats | stat connected)" = 0 ] ||
  fail "c = 0.4+0.6i should be dust"

# Box-counting dimension of a rendered Sierpinski carpet: log 8 / log 3 = 1.8928, within 0.05.
"$tessera" fractal sierpinski -o "$dir/carpet.png" --depth 6 --size 729x729
dim=$("$tessera" fractal dimension "$dir/carpet.png" --stats | stat dimension)
within "$dim" 1.8428 1.9428 || fail "carpet dimension $dim"
"$tessera" fractal dimension "$dir/carpet.png" | grep -q "box-counting dimension" || fail "human-readable dimension"

# Errors: a clear message and exit 1.
expect_error() {
  local rc=0
  "$@" >"$dir/out.txt" 2>"$dir/err.txt" || rc=$?
  [ "$rc" -eq 1 ] || fail "expected exit 1, got $rc: $*"
  grep -q "tessera: error:" "$dir/err.txt" || fail "no error message: $*"
}
expect_error "$tessera" fractal mandelbrot -o "$dir/x.png" --scale abc
expect_error "$tessera" fractal mandelbrot -o "$dir/x.png" --size=-5x10
expect_error "$tessera" fractal mandelbrot -o "$dir/x.png" --iterations 0
expect_error "$tessera" fractal julia -o "$dir/x.png" --c 1
expect_error "$tessera" fractal sierpinski -o "$dir/x.png" --depth 99
expect_error "$tessera" fractal koch -o "$dir/x.png" --depth 2x
expect_error "$tessera" fractal sierpinski -o "$dir/x.png" --shape hexagon
expect_error "$tessera" fractal terrain -o "$dir/x.obj" --method midpoint
expect_error "$tessera" fractal terrain -o "$dir/x.png" --roughness 1.5
expect_error "$tessera" fractal dimension "$dir/missing.png"
[ ! -e "$dir/x.png" ] || fail "a failed command left a file"
echo "fractal CLI: all checks passed"
