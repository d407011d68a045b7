#!/usr/bin/env bash
# The CLI's common contract: help lists every command, usage errors exit 2, runtime errors exit 1 with
# "tessera: error:", and the gallery writes pictures plus an index.html.
set -euo pipefail
tessera=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"

help=$("$tessera" --help)
for command in demo gallery canvas color mesh curve patch fractal; do
  grep -q "^  $command" <<<"$help" || { echo "--help does not list '$command'"; exit 1; }
done
"$tessera" --version | grep -q '^tessera '

expect_exit() {  # expect_exit CODE PATTERN COMMAND...: runs COMMAND, checks its exit code and that stderr matches
  local code=$1 pattern=$2; shift 2
  local status=0
  "$@" 2>"$scratch/stderr" >/dev/null || status=$?
  [ "$status" -eq "$code" ] || { echo "expected exit $code, got $status: $*"; cat "$scratch/stderr"; exit 1; }
  grep -q -- "$pattern" "$scratch/stderr" || { echo "stderr lacks '$pattern': $*"; cat "$scratch/stderr"; exit 1; }
}
# A bare tessera lists the commands; unknown commands are named, with the nearest one suggested.
expect_exit 2 "fractal  *Fractals" "$tessera"
expect_exit 2 "tessera: error: unknown command 'no-such-command'" "$tessera" no-such-command
expect_exit 2 "unknown command 'frobnicate'" "$tessera" frobnicate
expect_exit 2 "did you mean 'fractal'" "$tessera" fractl
expect_exit 2 "unknown command 'mesh subdvide' (did you mean 'mesh subdivide'?)" "$tessera" mesh subdvide x.obj
expect_exit 2 "'tessera fractal' needs a subcommand: mandelbrot, julia" "$tessera" fractal
expect_exit 2 "'tessera mesh' needs a subcommand: info" "$tessera" mesh --stats
# CLI11's own parse errors carry the same prefix and exit 2.
expect_exit 2 "tessera: error: .*no-such-option" "$tessera" gallery --no-such-option
expect_exit 2 "tessera: error: " "$tessera" gallery --threads -3
expect_exit 2 "tessera: error: .*--scheme" "$tessera" mesh subdivide x.obj -o y.obj --scheme cubic
# Malformed values are usage errors (exit 2), not runtime errors.
expect_exit 2 "tessera: error: --size: expected WIDTHxHEIGHT, got .800." "$tessera" fractal mandelbrot -o "$scratch/m.png" --size 800
expect_exit 2 "tessera: error: .*--progress" "$tessera" gallery --only 01 -o "$scratch/g" --progress loud
# --help shows choices by name, never the internal numbers behind them (CLI11's CheckedTransformer printed
# {catmull-clark->2,...}).
for words in "mesh subdivide" "mesh smooth" "mesh normals" "raster" "trace" "render" "volume render" "fractal mandelbrot" \
             "canvas render" "patch" "curve" "color convert"; do
  # shellcheck disable=SC2086
  help=$("$tessera" $words --help)
  if grep -E -- '->[0-9]' <<<"$help"; then echo "'tessera $words --help' shows internal enum numbers"; exit 1; fi
  grep -q -- "--progress" <<<"$help" || { echo "'tessera $words --help' lacks --progress"; exit 1; }
  grep -q -- "--stats" <<<"$help" || { echo "'tessera $words --help' lacks --stats"; exit 1; }
done
# Floating-point options refuse NaN and infinities (CLI11's range checks let NaN through).
expect_exit 2 "expected a finite number, got 'nan'" "$tessera" volume render sphere:8 -o "$scratch/nan.png" --fovy nan
expect_exit 2 "expected a finite number, got 'inf'" "$tessera" volume render sphere:8 -o "$scratch/inf.png" --far inf
[ ! -e "$scratch/nan.png" ] && [ ! -e "$scratch/inf.png" ] || { echo "a picture was written"; exit 1; }
expect_exit 1 "tessera: error:" "$tessera" gallery -o /proc/forbidden/gallery

"$tessera" gallery --only 01 -o "$scratch/gallery" >/dev/null

# --progress plain prints one line per phase (start, 10% steps, done) for batch logs; --quiet and none print nothing.
"$tessera" volume isosurface sphere:24 --iso 0 -o "$scratch/ball.ply" >/dev/null
"$tessera" trace "$scratch/ball.ply" -o "$scratch/ball.png" --size 32x32 --progress plain 2>"$scratch/progress" >/dev/null
grep -q "^building BVH: started$" "$scratch/progress" || { echo "no plain progress start line"; cat "$scratch/progress"; exit 1; }
grep -q "^building BVH: done in [0-9.]* s$" "$scratch/progress" || { echo "no plain progress end line"; exit 1; }
for quiet in "--quiet" "--progress none"; do
  # shellcheck disable=SC2086
  "$tessera" trace "$scratch/ball.ply" -o "$scratch/ball.png" --size 32x32 $quiet 2>"$scratch/progress" >/dev/null
  [ ! -s "$scratch/progress" ] || { echo "$quiet printed progress"; cat "$scratch/progress"; exit 1; }
done

# Every command prints --stats, with total_s.
stats_of() {  # stats_of COMMAND...: runs it with --stats; checks that it ends in key=value lines, total_s the last
  local out
  out=$("$@" --stats) || { echo "failed: $*"; exit 1; }
  tail -n 1 <<<"$out" | grep -Eq '^total_s=[0-9.e-]+$' || { echo "no total_s at the end from: $*"; echo "$out"; exit 1; }
  [ "$(grep -Ec '^[a-z_0-9]+=' <<<"$out")" -ge 2 ] || { echo "no figures besides total_s from: $*"; echo "$out"; exit 1; }
}
cd "$scratch"
stats_of "$tessera" mesh info ball.ply
stats_of "$tessera" mesh convert ball.ply -o ball.obj
stats_of "$tessera" mesh normals ball.obj -o normals.obj
stats_of "$tessera" mesh smooth ball.obj -o smooth.obj --method laplacian --iterations 2
stats_of "$tessera" mesh triangulate ball.obj -o tri.obj
stats_of "$tessera" mesh subdivide ball.obj -o sub.obj --scheme loop
stats_of "$tessera" volume info sphere:16
stats_of "$tessera" volume slice sphere:16 -o slice.png
stats_of "$tessera" volume contour sphere:16 -o contour.svg
stats_of "$tessera" volume render sphere:16 -o render.png --size 16x16
stats_of "$tessera" volume isosurface sphere:16 -o iso.ply
stats_of "$tessera" raster ball.ply -o raster.png --size 32x32
stats_of "$tessera" trace ball.ply -o trace.png --size 32x32
stats_of "$tessera" render whitted -o whitted.png --size 32x24 --spp 1
stats_of "$tessera" fractal mandelbrot -o m.png --size 32x32
stats_of "$tessera" fractal koch -o k.png
stats_of "$tessera" curve --points 0,0,1,2,3,0 -o c.png
stats_of "$tessera" color convert --from rgb --to hsv --values 1,0.5,0
stats_of "$tessera" gallery --only 01 -o g2
cd - >/dev/null
[ -s "$scratch/gallery/index.html" ] || { echo "no index.html"; exit 1; }
ls "$scratch"/gallery/*.png >/dev/null
echo "cli basics: ok"
