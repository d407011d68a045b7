#!/usr/bin/env bash
# tessera fractal end to end: every subcommand writes its file, the --stats figures land where the notes say (box
# counting against analytic dimensions, on pictures drawn here by PIL), --srgb follows the sRGB formula, malformed
# values are usage errors (exit 2) and runtime failures exit 1 with a message. $1: the tessera binary, $2: a scratch
# folder.
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

# The issue's case: the depth-7 Cantor set as one row of 2187 pixels across a 2187 x 64 picture (it measured 0.53 when
# the largest box was a quarter of the shorter side), the same as a column of a 64 x 2187 picture, and rows of other
# lengths at offsets; drawn here by PIL, dimension log 2 / log 3 = 0.6309.
py=/usr/bin/python3
"$py" - "$dir" <<'EOF'
import sys
from PIL import Image
def cantor(width, height, x0, y0, length, depth, vertical=False):
    picture = Image.new("L", (width, height), 255)
    for p in range(length):
        c, inside = (p + 0.5) / length, True
        for k in range(1, depth + 1):
            inside &= int(c * 3**k) % 3 != 1
        if inside:
            picture.putpixel((x0, y0 + p) if vertical else (x0 + p, y0), 0)
    return picture
cantor(2187, 64, 0, 31, 2187, 7).save(sys.argv[1] + "/cantor_row.png")
cantor(64, 2187, 40, 0, 2187, 7, True).save(sys.argv[1] + "/cantor_column.png")
cantor(1200, 7, 150, 3, 1000, 6).save(sys.argv[1] + "/cantor_1000.png")
cantor(3050, 50, 17, 49, 3000, 7).save(sys.argv[1] + "/cantor_3000.png")
EOF
for picture in cantor_row cantor_column; do
  stats=$("$tessera" fractal dimension "$dir/$picture.png" --stats)
  dim=$(echo "$stats" | stat dimension)
  within "$dim" 0.6109 0.6509 || fail "$picture dimension $dim, expected 0.6309 within 0.02"
  [ "$(echo "$stats" | stat extent)" = 2187 ] || fail "$picture extent: $stats"
  dim=$("$tessera" fractal dimension "$dir/$picture.png" --factor 3 --stats | stat dimension)
  within "$dim" 0.6308 0.6310 || fail "$picture dimension with --factor 3: $dim, expected 0.6309"
done
for picture in cantor_1000 cantor_3000; do
  dim=$("$tessera" fractal dimension "$dir/$picture.png" --stats | stat dimension)
  within "$dim" 0.5909 0.6709 || fail "$picture dimension $dim, expected 0.6309 within 0.04"
done
# Transparency is paper: a line drawn by canvas render on its default transparent background measures 1 (the
# transparent pixels, RGBA 0,0,0,0, were black ink once, and the whole picture measured 2).
printf '<svg width="300" height="100"><rect x="10" y="50" width="256" height="1" fill="black"/></svg>' >"$dir/line.svg"
"$tessera" canvas render "$dir/line.svg" -o "$dir/line.png" --no-antialias
dim=$("$tessera" fractal dimension "$dir/line.png" --stats | stat dimension)
within "$dim" 0.999999 1.000001 || fail "a line on a transparent background measured $dim"
printf '<svg width="300" height="100"><rect x="10" y="50" width="256" height="1" fill="white"/></svg>' >"$dir/light.svg"
"$tessera" canvas render "$dir/light.svg" -o "$dir/light.png" --no-antialias
dim=$("$tessera" fractal dimension "$dir/light.png" --invert --stats | stat dimension)
within "$dim" 0.999999 1.000001 || fail "a light line on a transparent background measured $dim with --invert"

# A Sierpinski triangle and a Koch curve drawn by tessera: log 3 / log 2 = 1.585 and log 4 / log 3 = 1.2619.
"$tessera" fractal sierpinski -o "$dir/triangle.png" --shape triangle --depth 5 --size 512x512
dim=$("$tessera" fractal dimension "$dir/triangle.png" --stats | stat dimension)
within "$dim" 1.535 1.635 || fail "Sierpinski triangle dimension $dim, expected 1.585 within 0.05"
"$tessera" fractal koch -o "$dir/koch_curve.png" --shape curve --depth 6 --size 1500x600 --line-width 1
dim=$("$tessera" fractal dimension "$dir/koch_curve.png" --stats | stat dimension)
within "$dim" 1.2119 1.3119 || fail "Koch curve dimension $dim, expected 1.2619 within 0.05"

# Progress of the escape-time loop: plain lines on stderr for logs (a start, 10% steps, the end), nothing on stdout,
# and nothing at all off a terminal by default (one thread: with more, a step two tasks cross at once prints once).
"$tessera" fractal mandelbrot -o "$dir/p.png" --size 64x40 --threads 1 --progress plain >"$dir/out.txt" 2>"$dir/err.txt"
[ ! -s "$dir/out.txt" ] || fail "progress on stdout: $(cat "$dir/out.txt")"
for line in started 50% done; do
  grep -q "^mandelbrot: escape times: $line" "$dir/err.txt" || fail "no progress line '$line': $(cat "$dir/err.txt")"
done
"$tessera" fractal julia -o "$dir/p.png" --size 64x40 2>"$dir/err.txt"
[ ! -s "$dir/err.txt" ] || fail "progress off a terminal without --progress: $(cat "$dir/err.txt")"

# --stats: the shared vocabulary on every subcommand (docs/cli.md), and the figures' own keys.
has_keys() {  # has_keys STATS KEY...: every KEY is printed
  local stats=$1; shift
  for key in "$@"; do grep -q "^$key=" <<<"$stats" || fail "--stats lacks $key: $stats"; done
}
has_keys "$("$tessera" fractal julia -o "$dir/s.png" --size 40x30 --stats)" \
  connected seconds iterations width height pixels compute_s write_s total_s
for figure in "cantor --depth 3" "cantor --dust --depth 3" "sierpinski --depth 3" "koch --depth 2" "hilbert --depth 3" \
              "peano --depth 2"; do
  # shellcheck disable=SC2086
  has_keys "$("$tessera" fractal $figure -o "$dir/s.png" --size 81x81 --stats)" \
    elements dimension width height pixels compute_s write_s total_s
done
stats=$("$tessera" fractal mandelbrot -o "$dir/s.png" --size 40x30 --stats)
has_keys "$stats" area seconds iterations simd width height pixels compute_s write_s total_s
[ "$(echo "$stats" | stat pixels)" = 1200 ] || fail "mandelbrot pixels: $stats"
has_keys "$("$tessera" fractal terrain -o "$dir/s.obj" --depth 3 --stats)" vertices faces compute_s write_s total_s
has_keys "$("$tessera" fractal terrain -o "$dir/s.png" --method midpoint --depth 5 --stats)" \
  vertices width height pixels compute_s write_s total_s
has_keys "$("$tessera" fractal dimension "$dir/carpet.png" --stats)" \
  dimension box_sizes fitted_sizes extent smallest_box_count width height pixels read_s compute_s total_s

# --srgb: 8-bit values are round(255 * srgb(linear)) with the sRGB formula. The profile's sky is linear
# (0.85, 0.92, 1.0) and its ground (0.35, 0.3, 0.25); the Mandelbrot picture's every pixel is checked against the
# same picture written as linear floats (PFM).
"$tessera" fractal terrain -o "$dir/profile_srgb.png" --method midpoint --depth 5 --size 64x64 --srgb
"$tessera" fractal terrain -o "$dir/profile_linear.png" --method midpoint --depth 5 --size 64x64
"$tessera" fractal mandelbrot -o "$dir/m_srgb.png" --size 64x48 --palette fire --srgb
"$tessera" fractal mandelbrot -o "$dir/m.pfm" --size 64x48 --palette fire
"$py" "$(dirname "$0")/srgb_check.py" pfm "$dir/m.pfm" "$dir/m_srgb.png" || fail "mandelbrot --srgb"
"$py" "$(dirname "$0")/srgb_check.py" pixel "$dir/profile_srgb.png" 0 0 0.85,0.92,1.0 || fail "profile --srgb sky"
"$py" "$(dirname "$0")/srgb_check.py" pixel "$dir/profile_srgb.png" 32 40 0.35,0.3,0.25 || fail "profile --srgb ground"
"$py" -c "import sys; from PIL import Image; sys.exit(Image.open(sys.argv[1]).convert('RGB').getpixel((0, 0)) != \
  (217, 235, 255))" "$dir/profile_linear.png" || fail "without --srgb the sky is not 255 * (0.85, 0.92, 1.0)"

# Usage errors: malformed values, unknown choices and depths past a figure's limit exit 2 with "tessera: error:",
# the option's name, and no internal enum numbers.
expect_usage() {  # expect_usage PATTERN COMMAND...
  local pattern=$1 rc=0; shift
  "$@" >"$dir/out.txt" 2>"$dir/err.txt" || rc=$?
  [ "$rc" -eq 2 ] || fail "expected exit 2, got $rc: $* ($(cat "$dir/err.txt"))"
  grep -q "tessera: error:" "$dir/err.txt" || fail "no error message: $*"
  grep -q -- "$pattern" "$dir/err.txt" || fail "the message lacks '$pattern': $* ($(cat "$dir/err.txt"))"
  ! grep -q -- "->" "$dir/err.txt" || fail "internal enum values in the message: $(cat "$dir/err.txt")"
}
expect_usage "--scale" "$tessera" fractal mandelbrot -o "$dir/x.png" --scale abc
expect_usage "--scale" "$tessera" fractal mandelbrot -o "$dir/x.png" --scale 0
expect_usage "--size" "$tessera" fractal mandelbrot -o "$dir/x.png" --size=-5x10
expect_usage "--size" "$tessera" fractal mandelbrot -o "$dir/x.png" --size 800
expect_usage "--iterations" "$tessera" fractal mandelbrot -o "$dir/x.png" --iterations 0
expect_usage "--center" "$tessera" fractal mandelbrot -o "$dir/x.png" --center 1
expect_usage "classic" "$tessera" fractal mandelbrot -o "$dir/x.png" --palette neon
expect_usage "scalar" "$tessera" fractal julia -o "$dir/x.png" --simd sse9
expect_usage "--c" "$tessera" fractal julia -o "$dir/x.png" --c 1
expect_usage "--depth" "$tessera" fractal sierpinski -o "$dir/x.png" --depth 99
expect_usage "carpet goes up to depth 7" "$tessera" fractal sierpinski -o "$dir/x.png" --depth 9
expect_usage "--depth" "$tessera" fractal cantor -o "$dir/x.png" --dust --depth 11
expect_usage "--depth" "$tessera" fractal koch -o "$dir/x.png" --depth 2x
expect_usage "--line-width" "$tessera" fractal koch -o "$dir/x.png" --line-width 0
expect_usage "--margin" "$tessera" fractal hilbert -o "$dir/x.png" --margin -1
expect_usage "--margin" "$tessera" fractal koch -o "$dir/x.png" --size 10x10 --margin 5
expect_usage "carpet" "$tessera" fractal sierpinski -o "$dir/x.png" --shape hexagon
expect_usage "snowflake" "$tessera" fractal koch -o "$dir/x.png" --shape square
expect_usage "picture" "$tessera" fractal terrain -o "$dir/x.obj" --method midpoint
expect_usage "mesh" "$tessera" fractal terrain -o "$dir/x.png" --method triangles
expect_usage "diamond-square" "$tessera" fractal terrain -o "$dir/x.obj" --method volcano
expect_usage "--roughness" "$tessera" fractal terrain -o "$dir/x.png" --roughness 1.5
expect_usage "--depth: diamond-square goes up to depth 12, got 20" "$tessera" fractal terrain -o "$dir/x.obj" --depth 20
expect_usage "--depth: the triangle mountain goes up to depth 10" "$tessera" fractal terrain -o "$dir/x.obj" \
  --method triangles --depth 11
expect_usage "--factor" "$tessera" fractal dimension "$dir/carpet.png" --factor 1
expect_usage "--min-box" "$tessera" fractal dimension "$dir/carpet.png" --min-box 0.5
expect_usage "--max-box: 0.5 is smaller than --min-box 1" "$tessera" fractal dimension "$dir/carpet.png" --max-box 0.5
expect_usage "--threshold" "$tessera" fractal dimension "$dir/carpet.png" --threshold x

# Runtime errors: exit 1 with a message that names the file and what was wrong.
expect_error() {  # expect_error PATTERN COMMAND...
  local pattern=$1 rc=0; shift
  "$@" >"$dir/out.txt" 2>"$dir/err.txt" || rc=$?
  [ "$rc" -eq 1 ] || fail "expected exit 1, got $rc: $*"
  grep -q "tessera: error:.*$pattern" "$dir/err.txt" || fail "the message lacks '$pattern': $(cat "$dir/err.txt")"
}
expect_error "missing.png" "$tessera" fractal dimension "$dir/missing.png"
"$py" -c "import sys; from PIL import Image; Image.new('L', (20, 20), 255).save(sys.argv[1])" "$dir/blank.png"
expect_error "empty" "$tessera" fractal dimension "$dir/blank.png"
expect_error "the set spans 729 pixels" "$tessera" fractal dimension "$dir/carpet.png" --min-box 5000
[ ! -e "$dir/x.png" ] && [ ! -e "$dir/x.obj" ] || fail "a failed command left a file"
echo "fractal CLI: all checks passed"
